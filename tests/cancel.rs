//! The engines stop on a cancellation request ([`bwcl::engines::cancel`], what Ctrl-C in Python
//! sets): DOP853 before its first step, the Taylor engine as at its deadline — never with a
//! number — and run normally again once the request is withdrawn. The request is
//! process-wide: the test runs itself alone in a child process (the suite's own program, this
//! one test), so that the other tests' runs in the suite are not stopped.

use bwcl::engines::cancel::Request;
use bwcl::engines::dop853::Dop853Error;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::kelvin_voigt::KelvinVoigt;
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, ImpactError, impact};
use inari::Interval;

/// Set in the child process that runs the test.
const CHILD: &str = "BWCL_CANCEL_CHILD";

#[test]
fn a_request_stops_both_engines_and_its_withdrawal_restores_them() {
    if std::env::var_os(CHILD).is_none() {
        let name = "cancel::a_request_stops_both_engines_and_its_withdrawal_restores_them";
        let out = std::process::Command::new(std::env::current_exe().expect("the suite"))
            .args(["--exact", name, "--test-threads=1"])
            .env(CHILD, "1")
            .output()
            .expect("the suite runs");
        let (stdout, stderr) = (
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
        );
        // the child ran this one test, and it passed
        assert!(
            out.status.success() && stdout.contains("1 passed") && stdout.contains(name),
            "{stdout}\n{stderr}"
        );
        return;
    }
    let float = KelvinVoigt::new(0.3).unwrap();
    let proved = KelvinVoigt::new(Interval::try_from((0.3, 0.3)).unwrap()).unwrap();
    let request = Request::new();
    assert!(bwcl::engines::cancel::requested());
    match impact(&float, &FloatOptions::default()) {
        Err(ImpactError::Integrator(e)) => {
            assert!(matches!(e, Dop853Error::Cancelled { .. }), "{e}")
        }
        other => panic!("the float engine went on: {other:?}"),
    }
    let e = rigorous_impact(&proved, &TaylorOptions::default()).expect_err("stopped");
    assert!(e.out_of_time(), "{e}");
    drop(request);
    assert!(!bwcl::engines::cancel::requested());
    assert!(impact(&float, &FloatOptions::default()).is_ok());
    assert!(rigorous_impact(&proved, &TaylorOptions::default()).is_ok());
}
