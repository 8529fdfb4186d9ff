//! Tests of the f64 DOP853 engine against known solutions and against SciPy's DOP853.

use bwcl::engines::dop853::{Dop853, Dop853Error, Options, integrate};

/// y' = y cos t, y(t0) = y0 ⇒ y(t) = y0 exp(sin t − sin t0).
fn exp_sin(t: f64, y: &[f64; 1]) -> [f64; 1] {
    [y[0] * t.cos()]
}

fn exp_sin_exact(t0: f64, y0: f64, t: f64) -> f64 {
    y0 * (t.sin() - t0.sin()).exp()
}

/// Harmonic oscillator x'' = −x as a system: (x, v)' = (v, −x).
fn oscillator(_t: f64, y: &[f64; 2]) -> [f64; 2] {
    [y[1], -y[0]]
}

fn van_der_pol(_t: f64, y: &[f64; 2]) -> [f64; 2] {
    [y[1], (1.0 - y[0] * y[0]) * y[1] - y[0]]
}

fn lorenz(_t: f64, y: &[f64; 3]) -> [f64; 3] {
    let (s, r, b) = (10.0, 28.0, 8.0 / 3.0);
    [
        s * (y[1] - y[0]),
        y[0] * (r - y[2]) - y[1],
        y[0] * y[1] - b * y[2],
    ]
}

fn rel_err(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Options for constant steps `h`: tolerances so loose that no step is rejected.
fn fixed_step(h: f64) -> Options {
    Options {
        rtol: 1e6,
        atol: 1e6,
        max_step: h,
        first_step: Some(h),
        max_steps: 1_000_000,
    }
}

/// y' = 1 + y², y(0) = 0 ⇒ y = tan t (nonlinear, exercises the full order conditions).
fn tan_rhs(_t: f64, y: &[f64; 1]) -> [f64; 1] {
    [1.0 + y[0] * y[0]]
}

/// Observed order `log2(err(h)/err(h/2))` of the global error at `T = 11/8` with constant steps
/// `h = T/16, T/32, T/64` (exact binary fractions, so every step has exactly length `h`).
///
/// Measured (same in SciPy): errors 2.9e-8, 1.4e-10, 6.0e-13, orders 7.63, 7.91. (On
/// y' = y cos t over [0, 8] both codes superconverge, order ≈ 9.8 then 9.0, so that problem is
/// not used here.)
#[test]
fn order_is_eight_with_fixed_steps() {
    let t1: f64 = 1.375;
    let exact = t1.tan();
    let errs: Vec<f64> = [16usize, 32, 64]
        .iter()
        .map(|&n| {
            let h = t1 / n as f64;
            let (y, st) = integrate(tan_rhs, 0.0, [0.0], t1, fixed_step(h)).unwrap();
            assert_eq!(st.nrejected, 0, "h = {h}");
            assert_eq!(st.naccepted, n, "h = {h}");
            rel_err(y[0], exact)
        })
        .collect();
    for w in errs.windows(2) {
        let p = (w[0] / w[1]).log2();
        assert!(
            (7.5..=8.5).contains(&p),
            "observed order {p}, errors {errs:?}"
        );
    }
    // The asymptotic regime is above rounding: the finest error is still ~1000 ulp.
    assert!(errs[2] > 1e-13, "{errs:?}");
}

/// Local order of the interpolant: one step of size `h` from exact data on y = tan t; the max
/// error at 49 interior points must fall like `h⁸` (a 7th-degree interpolant). Measured
/// log2 ratios 10.1, 9.3, 8.8 (tending to 8; SciPy gives the same); a wrong `D` coefficient
/// would give ≤ 5.
#[test]
fn dense_output_local_order() {
    let t0: f64 = 0.25;
    let errs: Vec<f64> = [0.5, 0.25, 0.125]
        .iter()
        .map(|&h| {
            let mut s = Dop853::new(tan_rhs, t0, [t0.tan()], t0 + h, fixed_step(h)).unwrap();
            assert!(s.step().unwrap());
            assert!(!s.step().unwrap(), "one step only");
            let d = s.dense_output();
            (1..50)
                .map(|m| {
                    let t = t0 + h * m as f64 / 50.0;
                    (d.eval_component(t, 0) - t.tan()).abs()
                })
                .fold(0.0, f64::max)
        })
        .collect();
    for w in errs.windows(2) {
        let p = (w[0] / w[1]).log2();
        assert!(p >= 7.5, "interpolant order {p}, errors {errs:?}");
    }
    assert!(errs[2] < 1e-11, "{errs:?}");
}

/// Checks the interpolant of every step of y' = y cos t on [0, 10] at 50 interior points and
/// returns (max interior error, max step-end error), both relative. Also checks that it is
/// bitwise exact at the ends and continuous into them.
fn dense_errors(opts: Options) -> (f64, f64, usize) {
    let (t0, t1) = (0.0, 10.0);
    let mut s = Dop853::new(exp_sin, t0, [1.0], t1, opts).unwrap();
    let (mut max_inner, mut max_end) = (0.0f64, 0.0f64);
    let mut steps = 0;
    while s.step().unwrap() {
        steps += 1;
        let d = s.dense_output();
        assert_eq!(d.t_old(), s.t_old());
        assert_eq!(d.t_new(), s.t());
        assert_eq!(d.eval(s.t_old()), *s.y_old());
        assert_eq!(d.eval(s.t()), *s.y());
        // The polynomial itself (not the end-point shortcut) meets the end points.
        let near_end = s.t().next_down();
        assert!(rel_err(d.eval_component(near_end, 0), s.y()[0]) < 1e-14);
        let near_start = s.t_old().next_up();
        assert!(rel_err(d.eval_component(near_start, 0), s.y_old()[0]) < 1e-14);
        max_end = max_end.max(rel_err(s.y()[0], exp_sin_exact(t0, 1.0, s.t())));
        for m in 1..=50 {
            let t = d.t_old() + (d.t_new() - d.t_old()) * m as f64 / 51.0;
            let u = d.eval(t)[0];
            assert_eq!(u, d.eval_component(t, 0));
            max_inner = max_inner.max(rel_err(u, exp_sin_exact(t0, 1.0, t)));
        }
    }
    (max_inner, max_end, steps)
}

/// With the paper's settings (`max_step = 1e-2`) the interpolant is as accurate as the steps:
/// measured 1.1e-14 relative, step ends 1.1e-14 (SciPy: the same).
#[test]
fn dense_output_accuracy_paper_options() {
    let (inner, end, steps) = dense_errors(Options::paper());
    assert!(steps >= 1000, "{steps}");
    assert!(end < 1e-9, "step-end error {end:e}");
    assert!(inner < 1e-9, "dense error {inner:e} (step ends {end:e})");
    assert!(inner < 10.0 * end + 1e-13, "{inner:e} vs {end:e}");
}

/// With unlimited steps (44 steps on [0, 10]) the 7th-order interpolant is ~100× less accurate
/// than the 8th-order step ends: measured 3.6e-9 vs 3.9e-11 relative, exactly as SciPy's
/// DOP853 dense output (3.64e-9 vs 3.92e-11). The interpolation error is not controlled by the
/// tolerance, so the bound here is 100 rtol.
#[test]
fn dense_output_accuracy_default_options() {
    let (inner, end, steps) = dense_errors(Options::default());
    assert!(steps > 10, "{steps}");
    assert!(end < 1e-9, "step-end error {end:e}");
    assert!(inner < 1e-8, "dense error {inner:e} (step ends {end:e})");
}

/// Dense output of a backward integration on the oscillator (x = cos t, v = −sin t).
#[test]
fn dense_output_backward() {
    let mut s = Dop853::new(
        oscillator,
        3.0,
        [3.0f64.cos(), -3.0f64.sin()],
        -1.0,
        Options::default(),
    )
    .unwrap();
    let mut max = 0.0f64;
    while s.step().unwrap() {
        let d = s.dense_output();
        assert!(d.t_new() < d.t_old());
        for m in 0..=20 {
            let t = d.t_old() + (d.t_new() - d.t_old()) * m as f64 / 20.0;
            let u = d.eval(t);
            max = max.max((u[0] - t.cos()).abs()).max((u[1] + t.sin()).abs());
        }
    }
    assert_eq!(s.t(), -1.0);
    assert!(max < 1e-9, "{max:e}");
}

/// Non-autonomous problems: y' = −2ty (y = exp(−t²)) and y' = cos t (y = sin t).
#[test]
fn non_autonomous() {
    let (y, _) = integrate(
        |t, y: &[f64; 1]| [-2.0 * t * y[0]],
        0.0,
        [1.0],
        2.0,
        Options::default(),
    )
    .unwrap();
    let e = rel_err(y[0], (-4.0f64).exp());
    assert!(e < 1e-9, "{e:e}");

    let (y, _) = integrate(
        |t, _y: &[f64; 1]| [t.cos()],
        0.0,
        [0.0],
        10.0,
        Options::default(),
    )
    .unwrap();
    let e = rel_err(y[0], 10.0f64.sin());
    assert!(e < 1e-9, "{e:e}");
}

/// A span not starting at 0, and a backward span.
#[test]
fn shifted_and_backward_spans() {
    let (y, st) = integrate(exp_sin, 5.0, [2.0], 7.5, Options::default()).unwrap();
    let e = rel_err(y[0], exp_sin_exact(5.0, 2.0, 7.5));
    assert!(e < 1e-9, "t0 = 5: {e:e}");
    assert!(st.naccepted > 0);

    let mut s = Dop853::new(exp_sin, 2.0, [1.5], 0.0, Options::default()).unwrap();
    let mut last = 2.0;
    while s.step().unwrap() {
        assert!(s.t() < last, "time must decrease");
        last = s.t();
    }
    assert_eq!(s.t(), 0.0);
    let e = rel_err(s.y()[0], exp_sin_exact(2.0, 1.5, 0.0));
    assert!(e < 1e-9, "backward: {e:e}");

    // Backward then forward returns to the start.
    let (y1, _) = integrate(oscillator, 4.0, [1.0, 0.5], -3.0, Options::default()).unwrap();
    let (y2, _) = integrate(oscillator, -3.0, y1, 4.0, Options::default()).unwrap();
    assert!(
        (y2[0] - 1.0).abs() < 1e-9 && (y2[1] - 0.5).abs() < 1e-9,
        "{y2:?}"
    );
}

/// The last step is clipped to `t_bound` exactly, and `max_step` is honoured.
#[test]
fn last_step_clipped_and_max_step() {
    let mut s = Dop853::new(exp_sin, 0.3, [1.0], 1.7, Options::paper()).unwrap();
    while s.step().unwrap() {
        assert!(
            s.t() - s.t_old() <= 1e-2 * (1.0 + 1e-15),
            "{}",
            s.t() - s.t_old()
        );
    }
    assert_eq!(s.t(), 1.7);
    assert!(s.naccepted() >= 140, "{}", s.naccepted());
}

fn reference() -> serde_json::Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/scipy_dop853_reference.json"
    );
    let text = std::fs::read_to_string(path).expect("reference file");
    serde_json::from_str(&text).expect("reference JSON")
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Same problem, same tolerances, same controller as SciPy ⇒ the same answer and (nearly) the
/// same steps and evaluations.
fn check_against_scipy<F, const N: usize>(name: &str, mut f: F)
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    let r = reference();
    assert!(r["rtol"].as_f64() == Some(1e-10) && r["atol"].as_f64() == Some(1e-12));
    let p = r["problems"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == name)
        .unwrap_or_else(|| panic!("{name} not in the reference"));
    let y0: [f64; N] = floats(&p["y0"]).try_into().unwrap();
    let y_ref = floats(&p["y_end"]);
    let (t0, t1) = (p["t0"].as_f64().unwrap(), p["t_end"].as_f64().unwrap());
    let (y, st) = integrate(&mut f, t0, y0, t1, Options::default()).unwrap();
    println!(
        "{name}: y = {y:?} vs SciPy {y_ref:?}; steps {} (+{} rejected) vs {}; nfev {} vs {}",
        st.naccepted, st.nrejected, p["steps"], st.nfev, p["nfev"]
    );
    for i in 0..N {
        let e = rel_err(y[i], y_ref[i]);
        assert!(
            e <= 1e-9,
            "{name}[{i}]: {} vs SciPy {} (rel {e:e})",
            y[i],
            y_ref[i]
        );
    }
    let steps = p["steps"].as_u64().unwrap() as i64;
    let nfev = p["nfev"].as_u64().unwrap() as f64;
    assert!(
        (st.naccepted as i64 - steps).abs() <= 2,
        "{name}: {} steps vs SciPy {steps}",
        st.naccepted
    );
    assert!(
        (st.nfev as f64 - nfev).abs() <= 0.05 * nfev,
        "{name}: nfev {} vs SciPy {nfev}",
        st.nfev
    );

    // Same controller ⇒ the same step sequence. Rounding alone moves the step sizes by up to
    // 3e-4 relative (Van der Pol: its error norm comes from heavy cancellation in Σ E5 K;
    // Lorenz: 2e-8), while a changed exponent, safety factor, post-rejection cap or initial
    // step moves them by ≥ 2.5e-2 or changes the count. No trial is near the accept/reject
    // boundary (closest: err = 0.977 and 0.990), so the counts are equal, not just within ±2.
    let t_ref = floats(&p["t_steps"]);
    let mut s = Dop853::new(&mut f, t0, y0, t1, Options::default()).unwrap();
    let mut ts = vec![s.t()];
    while s.step().unwrap() {
        ts.push(s.t());
    }
    assert_eq!(ts.len(), t_ref.len(), "{name}: step count");
    for (k, (a, b)) in ts.windows(2).zip(t_ref.windows(2)).enumerate() {
        let (h, h_ref) = (a[1] - a[0], b[1] - b[0]);
        assert!(
            rel_err(h, h_ref) < 5e-3,
            "{name}: step {k}: h = {h} vs SciPy {h_ref}"
        );
    }

    // SciPy's interpolant at interior times, from a second run that asks for dense output.
    let dense_t = floats(&p["dense_t"]);
    let dense_y: Vec<Vec<f64>> = p["dense_y"]
        .as_array()
        .unwrap()
        .iter()
        .map(floats)
        .collect();
    let mut s = Dop853::new(&mut f, t0, y0, t1, Options::default()).unwrap();
    let mut checked = 0;
    while s.step().unwrap() {
        let (lo, hi) = (s.t_old().min(s.t()), s.t_old().max(s.t()));
        for (t, yr) in dense_t.iter().zip(&dense_y) {
            if *t > lo && *t <= hi {
                let u = s.dense_output().eval(*t);
                for i in 0..N {
                    let e = (u[i] - yr[i]).abs() / yr[i].abs().max(1.0);
                    assert!(
                        e <= 1e-9,
                        "{name} dense at t = {t}: {} vs SciPy {}",
                        u[i],
                        yr[i]
                    );
                }
                checked += 1;
            }
        }
    }
    assert_eq!(checked, dense_t.len());
}

#[test]
fn reference_records_scipy_version() {
    let r = reference();
    let v = r["scipy_version"].as_str().expect("scipy_version");
    let major: u32 = v
        .split('.')
        .next()
        .unwrap()
        .parse()
        .expect("version number");
    assert!(major >= 1, "{v}");
    assert_eq!(r["method"], "DOP853");
}

#[test]
fn agrees_with_scipy_van_der_pol() {
    check_against_scipy("van_der_pol_mu1", van_der_pol);
}

#[test]
fn agrees_with_scipy_lorenz() {
    check_against_scipy("lorenz", lorenz);
}

fn new_err(opts: Options, y0: [f64; 1]) -> Dop853Error {
    match Dop853::new(exp_sin, 0.0, y0, 1.0, opts) {
        Err(e) => e,
        Ok(_) => panic!("accepted bad input"),
    }
}

#[test]
fn option_validation() {
    let d = Options::default;
    let cases: Vec<(Options, [f64; 1], &str)> = vec![
        (Options { rtol: 0.0, ..d() }, [1.0], "rtol = 0e0"),
        (Options { rtol: -1e-8, ..d() }, [1.0], "rtol = -1e-8"),
        (
            Options {
                rtol: f64::NAN,
                ..d()
            },
            [1.0],
            "rtol = NaN",
        ),
        (Options { atol: -1.0, ..d() }, [1.0], "atol = -1e0"),
        (
            Options {
                max_step: 0.0,
                ..d()
            },
            [1.0],
            "max_step = 0e0",
        ),
        (
            Options {
                max_step: -0.5,
                ..d()
            },
            [1.0],
            "max_step = -5e-1",
        ),
        (
            Options {
                first_step: Some(2.0),
                ..d()
            },
            [1.0],
            "first_step = 2e0",
        ),
        (
            Options {
                first_step: Some(0.0),
                ..d()
            },
            [1.0],
            "first_step = 0e0",
        ),
        (
            Options {
                max_steps: 0,
                ..d()
            },
            [1.0],
            "max_steps = 0",
        ),
        (d(), [f64::NAN], "y0[0] = NaN"),
        (d(), [f64::INFINITY], "y0[0] = inf"),
    ];
    for (opts, y0, needle) in cases {
        let e = new_err(opts, y0);
        let m = e.to_string();
        assert!(matches!(e, Dop853Error::BadOption(_)), "{m}");
        assert!(
            m.contains(needle),
            "message {m:?} should contain {needle:?}"
        );
        assert!(!m.contains('\n'));
    }
    let e = Dop853::new(exp_sin, 1.0, [1.0], 1.0, Options::default())
        .err()
        .unwrap();
    assert!(e.to_string().contains("t_bound = 1"), "{e}");
}

/// y' = y², y(0) = 1 blows up at t = 1: an error, never a panic or a wrong "success".
#[test]
fn blow_up_is_an_error() {
    let r = integrate(
        |_t, y: &[f64; 1]| [y[0] * y[0]],
        0.0,
        [1.0],
        2.0,
        Options::default(),
    );
    match r {
        Err(Dop853Error::StepTooSmall { t, .. }) | Err(Dop853Error::NonFinite { t }) => {
            // The numerical blow-up time is 1 + O(tol): the solver may stop just past 1.
            assert!((t - 1.0).abs() < 1e-6, "stopped at {t}")
        }
        other => panic!("expected StepTooSmall/NonFinite, got {other:?}"),
    }
    // Loose tolerances reach the singularity with huge values: still an error.
    let loose = Options {
        rtol: 1e-3,
        atol: 1e-3,
        ..Options::default()
    };
    let r = integrate(|_t, y: &[f64; 1]| [y[0] * y[0]], 0.0, [1.0], 2.0, loose);
    assert!(
        matches!(
            r,
            Err(Dop853Error::StepTooSmall { .. }) | Err(Dop853Error::NonFinite { .. })
        ),
        "{r:?}"
    );
}

/// A right-hand side that is NaN at the start is reported, and `max_steps` is enforced.
#[test]
fn non_finite_rhs_and_too_many_steps() {
    let e = Dop853::new(
        |_t, _y: &[f64; 1]| [f64::NAN],
        0.0,
        [1.0],
        1.0,
        Options::default(),
    )
    .err()
    .unwrap();
    assert_eq!(e, Dop853Error::NonFinite { t: 0.0 });

    let opts = Options {
        max_steps: 5,
        ..Options::paper()
    };
    match integrate(exp_sin, 0.0, [1.0], 1.0, opts) {
        Err(Dop853Error::TooManySteps { t, steps: 5 }) => assert!(t > 0.0 && t <= 0.05, "{t}"),
        other => panic!("{other:?}"),
    }
}
