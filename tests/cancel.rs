//! The engines stop on a cancellation request ([`bwcl::engines::cancel`], what Ctrl-C in Python
//! sets): DOP853 before its first step, the Taylor engine as at its deadline — never with a
//! number — and run normally again once the request is withdrawn. (One test: the request is
//! process-wide, and this binary runs nothing else.)

use bwcl::engines::cancel::Request;
use bwcl::engines::dop853::Dop853Error;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::kelvin_voigt::KelvinVoigt;
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, ImpactError, impact};
use inari::Interval;

#[test]
fn a_request_stops_both_engines_and_its_withdrawal_restores_them() {
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
