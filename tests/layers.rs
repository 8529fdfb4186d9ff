//! The arithmetic layer's folders are families that import only the root traits and their own
//! family (issue #15, deliverable 5): `src/arith/{real,scalar,enclosure}.rs` at the root, then
//! `float/`, `interval/`, `jet/`, `mpfr/`. This test reads the sources and fails on an import across families, an
//! import from the root into a family, or a circle of imports between files.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// (file, family) for every .rs file under src/arith; the family is "" at the root.
fn files() -> Vec<(String, String)> {
    let mut out = Vec::new();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/arith");
    for e in std::fs::read_dir(&root).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            let fam = p.file_name().unwrap().to_string_lossy().to_string();
            for f in std::fs::read_dir(&p).unwrap() {
                let f = f.unwrap().path();
                let name = f.file_stem().unwrap().to_string_lossy().to_string();
                out.push((format!("{fam}/{name}"), fam.clone()));
            }
        } else {
            let name = p.file_stem().unwrap().to_string_lossy().to_string();
            out.push((name, String::new()));
        }
    }
    out
}

/// The arith files a source file imports (by `use super::x`, `use crate::arith::fam::x`,
/// `crate::arith::fam::x::` paths), its tests excluded.
fn imports(file: &str, family: &str) -> BTreeSet<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src/arith")
        .join(format!("{file}.rs"));
    let text = std::fs::read_to_string(path).unwrap();
    let code = text.split("#[cfg(test)]").next().unwrap();
    let mut out = BTreeSet::new();
    for line in code.lines() {
        let l = line.trim_start();
        if l.starts_with("//") {
            continue;
        }
        for (i, _) in l.match_indices("crate::arith::") {
            let rest = &l[i + "crate::arith::".len()..];
            let parts: Vec<&str> = rest
                .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .next()
                .unwrap()
                .split("::")
                .collect();
            let first = parts[0];
            if ["float", "interval", "jet", "mpfr"].contains(&first) {
                let sub = parts.get(1).copied().unwrap_or("mod");
                let sub = if sub.chars().next().is_some_and(|c| c.is_uppercase()) {
                    "mod"
                } else {
                    sub
                };
                out.insert(format!("{first}/{sub}"));
            } else if ["real", "scalar", "enclosure"].contains(&first) {
                out.insert(first.to_string());
            } else {
                // a re-export of the root (crate::arith::Real, Dot, …)
                out.insert("mod".to_string());
            }
        }
        if let Some(rest) = l.strip_prefix("use super::") {
            let first = rest
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
                .unwrap();
            if first.is_empty() || first == "super" {
                continue;
            }
            if family.is_empty() {
                out.insert(first.to_string());
            } else {
                out.insert(format!("{family}/{first}"));
            }
        }
        if let Some(rest) = l.strip_prefix("use ") {
            // `use ulp::x;` inside a family's mod.rs
            let first = rest.split("::").next().unwrap();
            if !family.is_empty() && file.ends_with("/mod") && !first.contains(' ') {
                let cand = format!("{family}/{first}");
                if files().iter().any(|(f, _)| *f == cand) {
                    out.insert(cand);
                }
            }
        }
    }
    out.remove(file);
    out
}

fn family_of(f: &str) -> &str {
    f.split_once('/').map(|(a, _)| a).unwrap_or("")
}

/// Err on an import across families or a circle of imports.
fn check(graph: &BTreeMap<String, BTreeSet<String>>) -> Result<(), String> {
    for (f, deps) in graph {
        let fam = family_of(f);
        for d in deps {
            let dfam = family_of(d);
            if !(dfam.is_empty() || dfam == fam) {
                return Err(format!(
                    "{f} (family '{fam}') imports {d} from another family"
                ));
            }
        }
    }
    // no circles: repeatedly remove files that import nothing left
    let mut left = graph.clone();
    loop {
        let leaves: Vec<String> = left
            .iter()
            .filter(|(_, d)| d.iter().all(|x| !left.contains_key(x) || x == "mod"))
            .map(|(f, _)| f.clone())
            .collect();
        if leaves.is_empty() {
            break;
        }
        for l in leaves {
            left.remove(&l);
        }
    }
    left.remove("mod");
    if left.is_empty() {
        Ok(())
    } else {
        Err(format!("files importing each other in a circle: {left:?}"))
    }
}

#[test]
fn families_import_only_the_root_and_themselves_and_no_file_imports_in_a_circle() {
    let files = files();
    assert!(files.len() >= 12, "{files:?}");
    let graph: BTreeMap<String, BTreeSet<String>> = files
        .iter()
        .map(|(f, fam)| (f.clone(), imports(f, fam)))
        .collect();
    check(&graph).unwrap();
}

#[test]
fn the_check_sees_a_circle_and_a_cross_family_import() {
    // the parser sees the real imports
    let g = imports("interval/mod", "interval");
    assert!(g.contains("interval/ulp") && g.contains("real"), "{g:?}");
    let set = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
    let mut graph = BTreeMap::new();
    graph.insert("real".to_string(), set(&[]));
    graph.insert("interval/ulp".to_string(), set(&["real"]));
    graph.insert("interval/dot".to_string(), set(&["interval/ulp"]));
    assert!(check(&graph).is_ok());
    // the old layout's circle: ulp → dot (UlpDot) → ulp
    graph.insert("interval/ulp".to_string(), set(&["real", "interval/dot"]));
    assert!(check(&graph).unwrap_err().contains("circle"));
    graph.insert("interval/ulp".to_string(), set(&["real"]));
    graph.insert("jet/series".to_string(), set(&["interval/dot"]));
    assert!(check(&graph).unwrap_err().contains("another family"));
}
