//! Core of `proof-equilibria` (thm:BWSHCCM_eq, thm:BWMCM_eq) on the implementation's `field`
//! in interval arithmetic, for parameter sets given as decimals (enclosed exactly):
//!
//! 1. every equilibrium in the region [−L, L]^N lies within δ of 𝓔: branch and bound over
//!    state boxes; a box is excluded when some component of f(box) does not contain 0 (no
//!    equilibrium in it), accepted when the implementation's `equilibrium_distance` over the box
//!    is ≤ δ, split otherwise (the Maxwell R is never split: f does not depend on R, and the
//!    evaluation over the whole R range covers it);
//! 2. f vanishes on 𝓔: 0 ∈ f(box) for the box `equilibrium_point` gives at sampled points of 𝓔
//!    (an enclosure check of the implementation's 𝓔 parametrisation; f = 0 on 𝓔 itself is the
//!    identity κ|X|^p = κ_c ((κ/κ_c)^(1/p)|X|)^p).
#![allow(dead_code)]

use bwcl::arith::Real;
use bwcl::models::{BoucWenModel, Maxwell, ModelKind, NdParams, Shc};
use inari::Interval;

#[derive(Debug, Default, Clone)]
pub struct EqOutcome {
    pub excluded: usize,
    pub near: usize,
    pub undecided: usize,
    /// Largest width of f over the 𝓔 point boxes, and whether 0 ∈ f there every time.
    pub e_width: f64,
    pub e_contains_zero: bool,
}

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

/// Branch and bound for one model: `split` lists the state components that are split.
pub fn prove_model<M: BoucWenModel<Interval, N>, const N: usize>(
    m: &M,
    split: &[usize],
    half: f64,
    delta: f64,
    max_boxes: usize,
) -> EqOutcome {
    let mut o = EqOutcome {
        e_contains_zero: true,
        ..Default::default()
    };
    let root: [Interval; N] = std::array::from_fn(|_| iv(-half, half));
    let mut stack = vec![root];
    let mut n = 0;
    while let Some(b) = stack.pop() {
        n += 1;
        let f = m.field(&b);
        if f.iter().any(|c| !c.contains(0.0)) {
            o.excluded += 1;
            continue;
        }
        if m.equilibrium_distance(&b).sup() <= delta {
            o.near += 1;
            continue;
        }
        if n >= max_boxes {
            o.undecided += 1;
            continue;
        }
        let k = *split
            .iter()
            .max_by(|&&i, &&j| b[i].wid().total_cmp(&b[j].wid()))
            .unwrap();
        let mid = b[k].mid();
        let (mut l, mut r) = (b, b);
        l[k] = iv(b[k].inf(), mid);
        r[k] = iv(mid, b[k].sup());
        stack.push(l);
        stack.push(r);
    }
    for i in 0..=40 {
        let x = -half + 2.0 * half * i as f64 / 40.0;
        let e = m.equilibrium_point([iv(0.3, 0.3), iv(x, x)].map(|v| v));
        let e = if N == 3 {
            m.equilibrium_point([iv(x, x), iv(0.0, 0.0)])
        } else {
            e
        };
        for c in m.field(&e) {
            o.e_width = o.e_width.max(c.wid());
            o.e_contains_zero &= c.contains(0.0);
        }
    }
    o
}

/// Runs the proof for one parameter set (decimals "B,Γ,κ,σ,n,p").
pub fn prove_set(kind: ModelKind, set: &str, half: f64, delta: f64, max_boxes: usize) -> EqOutcome {
    let p = NdParams::<Interval>::parse(kind, set).expect("an admissible set");
    match kind {
        ModelKind::Shc => prove_model(&Shc::new(p), &[0, 1, 2], half, delta, max_boxes),
        ModelKind::Maxwell => prove_model(&Maxwell::new(p), &[1, 2, 3], half, delta, max_boxes),
    }
}

/// The parameter sets of the proof: the Table 1 base sets and edge sets of 𝓟.
pub const SETS: [(ModelKind, &str); 8] = [
    (ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27"),
    (ModelKind::Shc, "0.63,-0.611,0.188,0.00594,1,2.02"),
    (ModelKind::Shc, "1,-0.99,0.01,0.01,1,1"),
    (ModelKind::Shc, "2,0.99,0.99,2,3,4"),
    (ModelKind::Maxwell, "0.655,-0.64,0.519,0.0118,1.94,2.28"),
    (ModelKind::Maxwell, "0.44,-0.418,0.113,0.00785,1.27,3.14"),
    (ModelKind::Maxwell, "1,0,0.5,1,1,1"),
    (ModelKind::Maxwell, "2,-0.9,0.05,0.5,2,4"),
];

pub fn unused() -> Interval {
    <Interval as Real>::from_int(0)
}
