//! Proved enclosures of T_s and e from the rigorous Taylor engine ([`crate::engines::taylor`]).

use crate::engines::taylor::{
    Ended, Flow, RigorError, TaylorOptions, integrate_system_until, integrate_to_separation,
    model_tape,
};
use crate::models::CollisionModel;
use crate::models::{ModelKind, NdParams};
use inari::Interval;

/// A proved result: the true T_s lies in `ts` and the true e = V(T_s) in `e`, for every
/// parameter value in the model's (interval) parameters.
#[derive(Clone, Debug)]
pub struct Enclosure<const N: usize> {
    pub ts: Interval,
    pub e: Interval,
    /// An enclosure of Φ(T_s).
    pub state: [Interval; N],
    /// The proved flow from T = 0 to past T_s: rigorous dense output.
    pub flow: Flow<N>,
}

/// Encloses T_s and e for `model` (parameters as intervals). Fails with the reason (and where)
/// when it cannot prove separation before the horizon or the enclosure grows too wide.
pub fn rigorous_impact<M: CollisionModel<Interval, N>, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
) -> Result<Enclosure<N>, RigorError> {
    let (flow, ev) = integrate_to_separation(model, opts)?;
    Ok(Enclosure {
        ts: ev.ts,
        e: ev.e,
        state: ev.state,
        flow,
    })
}

/// The proved flow a curve (`trajectory`, `loop`) is sampled on, the time its samples end at,
/// and whether the model never separates: T_s's upper end (or `t_end`) when the model
/// separates; for a model that never separates by its closed form
/// ([`CollisionModel::never_separates`]), up to `t_end` (beyond the horizon too) or the horizon, run
/// with F replaced by 1 in the separation condition (F > 0 for every T > 0 by the closed form:
/// the condition the engine would otherwise test, F's sign at the rounding level, stops the run
/// as undecidable). `t_end` beyond the proved flow is refused.
pub fn curve_flow<M: CollisionModel<Interval, N> + Sync, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
    t_end: Option<f64>,
) -> Result<(Flow<N>, f64, bool), CurveError> {
    let never = model.never_separates().is_some();
    let (flow, end) = if never {
        let end = t_end.unwrap_or(opts.horizon);
        // past `end`, so that the run stops by the test rather than at its horizon
        let past = TaylorOptions {
            horizon: 2.0 * end + 1.0,
            ..opts.clone()
        };
        let mut stop = |f: &Flow<N>, _: f64| f.t_end() >= end;
        let tape = model_tape(model, false);
        match integrate_system_until(&tape, model.initial_state(), N, &past, &mut stop) {
            Ok(Ended::Stopped { flow, .. }) => (flow, end),
            Ok(Ended::Separated(..)) => {
                return Err(CurveError::Other(
                    "the flow without the separation condition separated (an internal error)"
                        .into(),
                ));
            }
            Err(e) => return Err(CurveError::Engine(e)),
        }
    } else {
        let enc = rigorous_impact(model, opts).map_err(CurveError::Engine)?;
        let end = enc.ts.sup().min(enc.flow.t_end());
        (enc.flow, t_end.unwrap_or(end))
    };
    if end > flow.t_end() {
        return Err(CurveError::Other(format!(
            "--t-end {end} lies beyond the proved flow, which ends at T = {}",
            flow.t_end()
        )));
    }
    Ok((flow, end, never))
}

/// Why [`curve_flow`] has no flow: the engine's reason, or another.
#[derive(Clone, Debug)]
pub enum CurveError {
    Engine(RigorError),
    Other(String),
}

impl std::fmt::Display for CurveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CurveError::Engine(e) => write!(f, "{e}"),
            CurveError::Other(m) => write!(f, "{m}"),
        }
    }
}

/// Proved T_s and e for every impact speed in a range (all in the hulls).
#[derive(Clone, Debug)]
pub struct RangeEnclosure {
    pub ts: Interval,
    pub e: Interval,
    /// How many sub-ranges were proved.
    pub pieces: usize,
}

/// Encloses T_s and e for every v0 in the interval `v0` of base set `base` (𝓟(P*, v0)): the
/// adaptive split of [`super::split`] (pieces cut where unproved or where they overshoot the
/// hull's ends) with at most `max_pieces` pieces; the hull over the pieces, valid for every v0
/// in the range. Fails with the reason if some sub-range is still not proved when the budget is
/// spent.
pub fn rigorous_impact_over_speeds(
    kind: ModelKind,
    base: &NdParams<Interval>,
    v0: Interval,
    opts: &TaylorOptions,
    max_pieces: usize,
) -> Result<RangeEnclosure, RigorError> {
    let inputs = super::sets::Inputs::Base {
        base: base.clone(),
        v0,
    };
    let split = super::split::SplitOptions {
        max_pieces,
        ..Default::default()
    };
    super::split::prove_over_set_adaptive(kind, &inputs, opts, &split).map(|r| RangeEnclosure {
        ts: r.ts,
        e: r.e,
        pieces: r.pieces,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::{Maxwell, ModelKind, NdParams, Shc};
    use crate::observables::{FloatOptions, impact};

    fn shc(s: &str) -> (Shc<Interval>, Shc<f64>) {
        (
            Shc::new(NdParams::parse(ModelKind::Shc, s).unwrap()),
            Shc::new(NdParams::parse(ModelKind::Shc, s).unwrap()),
        )
    }

    /// The NDBWMCM of Table 1's DSA set at v0 = 5 m/s.
    fn maxwell_dsa_v0_5() -> Maxwell<Interval> {
        let base =
            NdParams::<Interval>::parse(ModelKind::Maxwell, "0.44,-0.418,0.113,0.00785,1.27,3.14")
                .unwrap();
        let v0: Interval = "[5]".parse().unwrap();
        Maxwell::new(crate::models::scaling::nd_from_base(ModelKind::Maxwell, &base, &v0).unwrap())
    }

    #[test]
    fn dss_shc_enclosure_contains_the_float_value() {
        let (mi, mf) = shc("1.43,-1.42,0.632,0.00715,1.31,1.27");
        let t0 = std::time::Instant::now();
        let r = rigorous_impact(&mi, &TaylorOptions::default());
        let dt = t0.elapsed();
        let f = impact(&mf, &FloatOptions::default()).unwrap();
        match &r {
            Ok(enc) => eprintln!(
                "ts {:?} e {:?} width {:e} pieces {} in {:?}",
                enc.ts,
                enc.e,
                enc.e.wid(),
                enc.flow.len(),
                dt
            ),
            Err(e) => eprintln!("{e} in {dt:?}"),
        }
        let enc = r.unwrap();
        assert!(
            enc.e.contains(f.e) || (enc.e.inf() - f.e).abs() < 1e-9,
            "{:?} vs {}",
            enc.e,
            f.e
        );
    }

    #[test]
    fn maxwell_dsa_at_v0_5() {
        let t0 = std::time::Instant::now();
        let r = rigorous_impact(&maxwell_dsa_v0_5(), &TaylorOptions::default());
        match &r {
            Ok(enc) => eprintln!(
                "ts {:?} e {:?} width {:e} pieces {} in {:?}",
                enc.ts,
                enc.e,
                enc.e.wid(),
                enc.flow.len(),
                t0.elapsed()
            ),
            Err(e) => eprintln!("{e}"),
        }
        r.unwrap();
    }

    /// Timing of the rigorous engine (median of 5 runs): `cargo test --release --lib
    /// rigorous_timing -- --ignored --nocapture`; `BWCL_ORDER` overrides the order.
    #[test]
    #[ignore]
    fn rigorous_timing() {
        let mut opts = TaylorOptions::default();
        if let Some(k) = std::env::var("BWCL_ORDER")
            .ok()
            .and_then(|s| s.parse().ok())
        {
            opts.order = k;
        }
        let median = |f: &dyn Fn() -> (f64, usize)| {
            let mut ts = Vec::new();
            let mut info = (0.0, 0);
            for _ in 0..5 {
                let t0 = std::time::Instant::now();
                info = f();
                ts.push(t0.elapsed().as_secs_f64());
            }
            ts.sort_by(f64::total_cmp);
            (ts[2], info)
        };
        let (mi, _) = shc("1.43,-1.42,0.632,0.00715,1.31,1.27");
        let (t, (w, n)) = median(&|| {
            let r = rigorous_impact(&mi, &opts).unwrap();
            (r.e.wid(), r.flow.len())
        });
        eprintln!(
            "K {} SHC DSS: median {:.2} ms, pieces {n}, e width {w:e}",
            opts.order,
            t * 1e3
        );
        let m = maxwell_dsa_v0_5();
        let (t, (w, n)) = median(&|| {
            let r = rigorous_impact(&m, &opts).unwrap();
            (r.e.wid(), r.flow.len())
        });
        eprintln!(
            "K {} Maxwell DSA v0=5: median {:.2} ms, pieces {n}, e width {w:e}",
            opts.order,
            t * 1e3
        );
    }
}
