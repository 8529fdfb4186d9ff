//! `paper-repro --quick --identifiability` regenerates the CSVs, the plots and REPORT.md into a
//! scratch directory: one run for both the paper's figures and tables and the identifiability
//! section (issue #31; one run instead of two: the quick figures and fit are half its time).

use std::path::PathBuf;
use std::process::Command;

#[test]
fn regenerates_csvs_plots_and_report() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("paper-repro-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let report = dir.join("REPORT.md");
    let o = Command::new(env!("CARGO_BIN_EXE_paper-repro"))
        .args([
            "--quick",
            "--identifiability",
            // one second per paving: measured 48 boxes proved infeasible (135 with 4 s, 12 s
            // more of the run), the check below needs one
            "--ident-seconds",
            "1",
            "--out",
        ])
        .arg(&dir)
        .arg("--report")
        .arg(&report)
        .output()
        .expect("paper-repro runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "cor_float.csv",
        "fig3_NDBWSHCCM.svg",
        "fig3_NDBWSHCCM.png",
        "fig3_NDBWMCM.svg",
        "fig3_NDBWMCM.png",
        "fig4_loop_2_15.csv",
        "fig4_loop_5_02.csv",
        "table2_loops.csv",
        "fig4_RCross.svg",
        "fig4_RCross.png",
        "fit_curve.csv",
        "fit_starts.csv",
        "fit_demo.svg",
        "fit_demo.png",
    ] {
        let p = dir.join(f);
        let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        assert!(len > 100, "{} missing or empty", p.display());
    }
    let png = std::fs::read(dir.join("fig4_RCross.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let svg = std::fs::read_to_string(dir.join("fig3_NDBWSHCCM.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("v0 (m/s)"));
    // the CoR grid: 12 speeds × 4 sets, every e in the paper's window [0.5, 1]
    let cor = std::fs::read_to_string(dir.join("cor_float.csv")).unwrap();
    let rows: Vec<&str> = cor.lines().skip(1).collect();
    assert_eq!(rows.len(), 12);
    for r in rows {
        for x in r.split(',').skip(1) {
            let e: f64 = x.parse().unwrap();
            assert!((0.5..=1.0).contains(&e), "{r}");
        }
    }
    // four loops with five positive numbers each
    let t2 = std::fs::read_to_string(dir.join("table2_loops.csv")).unwrap();
    assert_eq!(t2.lines().count(), 5);
    for r in t2.lines().skip(1) {
        assert!(r.split(',').all(|x| x.parse::<f64>().unwrap() > 0.0), "{r}");
    }
    let rep = std::fs::read_to_string(&report).unwrap();
    for s in [
        "Fig. 3",
        "Table 1",
        "Fig. 4",
        "Table 2",
        "peak force",
        "cannot be reproduced",
        "not computable",
        "Noise level",
    ] {
        assert!(rep.contains(s), "REPORT.md lacks '{s}'");
    }
    identifiability(&dir, &rep);
}

/// The identifiability section (issue #31, item 5): the minima, profiles and pavings are written
/// and reported, and no box proved infeasible holds the generating P*, whose f64 residuals are
/// within the bounded errors (e: 0.0095 ≤ 0.02, tc: 0.0397 ≤ 0.04).
fn identifiability(dir: &std::path::Path, rep: &str) {
    for f in [
        "ident_minima.csv",
        "ident_profiles.csv",
        "ident_pavings.csv",
        "ident_profiles.svg",
        "ident_profiles.png",
        "ident_pavings.svg",
        "ident_pavings.png",
    ] {
        let len = std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
        assert!(len > 100, "{f} missing or empty");
    }
    for s in [
        "Identifiability (issue #31)",
        "Distinct minima",
        "Profiles",
        "Proved feasible sets",
    ] {
        assert!(rep.contains(s), "REPORT.md lacks '{s}'");
    }
    // the generating point in each plane: (σ_b, κ) and (Γ_b, B_b)
    let truth = |plane: &str| match plane {
        "sigma_b-kappa" => (0.00715, 0.632),
        "Gamma_b-B_b" => (-1.42, 1.43),
        p => panic!("unknown plane {p}"),
    };
    let csv = std::fs::read_to_string(dir.join("ident_pavings.csv")).unwrap();
    let (mut infeasible, mut planes) = (0, std::collections::BTreeSet::new());
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 7, "{line}");
        planes.insert((f[0].to_string(), f[1].to_string()));
        if f[6] != "infeasible" {
            continue;
        }
        infeasible += 1;
        let n = |i: usize| f[i].parse::<f64>().unwrap();
        let (x, y) = truth(f[1]);
        let inside = n(2) <= x && x <= n(3) && n(4) <= y && y <= n(5);
        assert!(
            !inside,
            "the generating P* is in a box proved infeasible: {line}"
        );
    }
    assert_eq!(planes.len(), 4, "two data sets × two planes");
    assert!(
        infeasible > 0,
        "no box was proved infeasible: the check is empty"
    );
}
