//! Review probes of the linear-chain fusion (an adversarial review of commit 3359293, kept as
//! tests): random fused tapes against exact rational Taylor coefficients (values and first
//! derivatives, wide and point constants, boxes), the Dot accumulators' `add_scaled` against
//! exact rational enclosures (zeros, subnormals, infinities), and structural edge cases
//! (shift-only tapes, unused chains, parameters, variable powers, fusing twice). The review's
//! one failure (a node merged from two parameters given as the same range cancelled to an
//! exact 0) is `linear::tests::a_merged_node_does_not_cancel`.

// several tapes' coefficients are compared at the same index k
#![allow(clippy::needless_range_loop)]

use super::rec::Rec;
use super::tape::{Op, Rounding, Tape, Workspace};
use crate::arith::interval::dot::{IntervalDot, UlpDot};
use crate::arith::interval::ulp::Ulp;
use crate::arith::interval::ulp::adversarial::iters;
use crate::arith::jet::dual::Dual;
use crate::arith::{Dot, Enclosure, Real, Scalar};
use inari::Interval;
use rug::Rational;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        crate::arith::interval::xorshift_step(&mut self.0)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap()
}
fn q(x: f64) -> Rational {
    Rational::from_f64(x).unwrap()
}
/// lo ≤ r ≤ hi with infinite ends allowed.
fn within(lo: f64, hi: f64, r: &Rational) -> bool {
    let lo_ok = lo == f64::NEG_INFINITY || (lo.is_finite() && q(lo) <= *r);
    let hi_ok = hi == f64::INFINITY || (hi.is_finite() && *r <= q(hi));
    lo_ok && hi_ok
}

/// A constant of the table: its enclosure and the real it stands for.
#[derive(Clone)]
struct K {
    lo: f64,
    hi: f64,
    real: Rational,
}

fn table() -> Vec<K> {
    let thin = |x: f64| K {
        lo: x,
        hi: x,
        real: q(x),
    };
    let mut t: Vec<K> = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        2.0,
        0.5,
        3.0,
        -0.75,
        0.1,
        -3.7,
        1e-300,
        -1e300,
        5e-324,
        1e16,
        1.0 + f64::EPSILON,
    ]
    .into_iter()
    .map(thin)
    .collect();
    // wide ones, each standing for one real inside
    for (lo, hi, r) in [
        (0.9, 1.1, q(0.9)),
        (0.9000000000000001, 1.1, q(1.1)),
        (-1.0, 1.0, q(0.25)),
        (0.0, 2.0, q(2.0)),
        (-2.0, -0.0, q(-2.0)),
        (1.0, 1e300, q(7.0)),
        (-1e-310, 1e-310, q(1e-310)),
    ] {
        t.push(K { lo, hi, real: r });
    }
    t
}

#[derive(Clone, Copy, Debug)]
enum I {
    Add(usize, usize),
    Sub(usize, usize),
    Neg(usize),
    Scale(usize, usize),
    Shift(usize, usize),
    Mul(usize, usize),
}

struct Prog<const N: usize> {
    ins: Vec<I>,
    outs: Vec<usize>,
}

fn random_prog<const N: usize>(rng: &mut Rng, nk: usize) -> Prog<N> {
    let len = 3 + rng.below(14);
    let mut ins = Vec::new();
    let pick = |rng: &mut Rng, n: usize| {
        // mostly the recent nodes, so that chains form
        if rng.below(3) > 0 && n > 1 {
            n - 1 - rng.below(n.min(3))
        } else {
            rng.below(n)
        }
    };
    for _ in 0..len {
        let n = N + ins.len();
        let a = pick(rng, n);
        let b = pick(rng, n);
        let k = rng.below(nk);
        ins.push(match rng.below(10) {
            0 | 1 => I::Add(a, b),
            2 | 3 => I::Sub(a, b),
            4 => I::Neg(a),
            5 | 6 => I::Scale(a, k),
            7 => I::Shift(a, k),
            _ => I::Mul(a, b),
        });
    }
    let n = N + ins.len();
    let nout = N + rng.below(3);
    let outs = (0..nout)
        .map(|_| {
            if rng.below(2) == 0 {
                n - 1 - rng.below(n.min(4))
            } else {
                rng.below(n)
            }
        })
        .collect();
    Prog { ins, outs }
}

fn record<const N: usize>(p: &Prog<N>, ks: &[K]) -> Tape<Interval, N> {
    Tape::<Interval, N>::record(|v| {
        let mut nodes: Vec<Rec<Interval>> = v.to_vec();
        for ins in &p.ins {
            let x = match *ins {
                I::Add(a, b) => nodes[a].clone() + nodes[b].clone(),
                I::Sub(a, b) => nodes[a].clone() - nodes[b].clone(),
                I::Neg(a) => -nodes[a].clone(),
                I::Scale(a, k) => nodes[a].scale(&iv(ks[k].lo, ks[k].hi)),
                I::Shift(a, k) => nodes[a].shift(&iv(ks[k].lo, ks[k].hi)),
                I::Mul(a, b) => nodes[a].clone() * nodes[b].clone(),
            };
            nodes.push(x);
        }
        p.outs.iter().map(|&o| nodes[o].clone()).collect()
    })
}

/// An exact dual number: value and N partial derivatives (by the initial state).
type RD = Vec<Rational>;
fn rd_zero(n: usize) -> RD {
    vec![Rational::new(); n + 1]
}

/// Exact Taylor coefficients (with derivatives by x0) of every node, orders 0..=order.
fn exact<const N: usize>(p: &Prog<N>, ks: &[K], x0: &[Rational; N], order: usize) -> Vec<Vec<RD>> {
    let nn = N + p.ins.len();
    let mut c: Vec<Vec<RD>> = vec![Vec::new(); nn];
    for k in 0..=order {
        for i in 0..nn {
            let val: RD = if i < N {
                if k == 0 {
                    let mut d = rd_zero(N);
                    d[0] = x0[i].clone();
                    d[1 + i] = Rational::from(1);
                    d
                } else {
                    c[p.outs[i]][k - 1]
                        .iter()
                        .map(|r| r.clone() / k as u32)
                        .collect()
                }
            } else {
                let g = |a: usize| c[a][k].clone();
                match p.ins[i - N] {
                    I::Add(a, b) => g(a).iter().zip(g(b)).map(|(x, y)| x.clone() + y).collect(),
                    I::Sub(a, b) => g(a).iter().zip(g(b)).map(|(x, y)| x.clone() - y).collect(),
                    I::Neg(a) => g(a).into_iter().map(|x| -x).collect(),
                    I::Scale(a, kk) => g(a).into_iter().map(|x| x * &ks[kk].real).collect(),
                    I::Shift(a, kk) => {
                        let mut v = g(a);
                        if k == 0 {
                            v[0] += &ks[kk].real;
                        }
                        v
                    }
                    I::Mul(a, b) => {
                        let mut s = rd_zero(N);
                        for j in 0..=k {
                            let (u, w) = (&c[a][j], &c[b][k - j]);
                            s[0] += u[0].clone() * &w[0];
                            for d in 1..=N {
                                s[d] += u[0].clone() * &w[d] + u[d].clone() * &w[0];
                            }
                        }
                        s
                    }
                }
            };
            c[i].push(val);
        }
    }
    c
}

struct Stats {
    cases: usize,
    checks: usize,
    each_differs: usize,
    each_wider: usize,
    max_ratio: f64,
}

/// Checks the three tapes (recorded, Each, Once) over Interval, Ulp and Dual<Ulp, N>, from
/// points (`width` 0) or boxes of relative width `width`.
fn check_prog_box<const N: usize>(
    p: &Prog<N>,
    ks: &[K],
    xs: &[[f64; N]],
    order: usize,
    st: &mut Stats,
    width: f64,
) {
    let rec = record(p, ks);
    let tapes = [
        ("recorded", rec.clone()),
        ("each", rec.fused(Rounding::Each)),
        ("once", rec.fused(Rounding::Once)),
    ];
    // the recorded outputs' node indices differ from p.outs only by CSE: compare by output
    for x in xs {
        let xh: [f64; N] = std::array::from_fn(|i| x[i] + width * (1.0 + x[i].abs()));
        let corner = (st.cases % 2 == 1) && width > 0.0;
        let xq: [Rational; N] = std::array::from_fn(|i| q(if corner { xh[i] } else { x[i] }));
        let ex = exact(p, ks, &xq, order);
        let xi: [Interval; N] = std::array::from_fn(|i| iv(x[i], xh[i]));
        st.cases += 1;
        let mut unfused: Vec<Vec<Interval>> = Vec::new();
        for (name, t) in &tapes {
            // Interval jets
            let mut ws = Workspace::default();
            let r = t.jet(&xi, order, &mut ws);
            let Ok(_) = r else {
                panic!("{name}: jet failed {r:?}")
            };
            let mut got_all = Vec::new();
            for (o, &node) in p.outs.iter().enumerate() {
                let mut row = Vec::new();
                for k in 0..=order {
                    let g = t.output_coef(&ws, order, o, k);
                    let w = &ex[node][k][0];
                    st.checks += 1;
                    assert!(
                        within(g.inf(), g.sup(), w),
                        "{name} Interval: out {o} coef {k} = {g:?} misses {w}\nprog {:?} outs {:?} x {x:?}\n{:?}",
                        p.ins,
                        p.outs,
                        t.ops()
                    );
                    row.push(g);
                }
                got_all.push(row);
            }
            if *name == "recorded" {
                unfused = got_all.clone();
            } else if *name == "each" {
                for (a, b) in unfused.iter().flatten().zip(got_all.iter().flatten()) {
                    if a != b && !(a.is_empty() && b.is_empty()) {
                        st.each_differs += 1;
                        if b.wid() > a.wid() {
                            st.each_wider += 1;
                            if a.wid() > 0.0 && a.wid().is_finite() {
                                let r = b.wid() / a.wid();
                                if r > st.max_ratio && (r > 4.0) {
                                    eprintln!(
                                        "Each wider ×{r}: recorded {a:?}, Each {b:?}; prog {:?} outs {:?} x {x:?} order {order}",
                                        p.ins, p.outs
                                    );
                                }
                                st.max_ratio = st.max_ratio.max(r);
                            }
                        }
                    }
                }
            }
            // eval at order 0
            let e = t.eval(&xi);
            for (o, &node) in p.outs.iter().enumerate() {
                let w = &ex[node][0][0];
                assert!(
                    within(e[o].inf(), e[o].sup(), w),
                    "{name} eval out {o}: {:?} misses {w}",
                    e[o]
                );
            }
            // Ulp jets
            let tu: Tape<Ulp, N> = t.map(|c| c.to_jet());
            let xu: [Ulp; N] = std::array::from_fn(|i| Ulp {
                lo: x[i],
                hi: xh[i],
            });
            let mut wu = Workspace::default();
            tu.jet(&xu, order, &mut wu).unwrap();
            for (o, &node) in p.outs.iter().enumerate() {
                for k in 0..=order {
                    let g = tu.output_coef(&wu, order, o, k);
                    let w = &ex[node][k][0];
                    st.checks += 1;
                    assert!(
                        within(g.lo, g.hi, w),
                        "{name} Ulp: out {o} coef {k} = {g:?} misses {w}\nprog {:?} outs {:?} x {x:?}",
                        p.ins,
                        p.outs
                    );
                }
            }
            // Dual<Ulp> jets (value and ∂/∂x0_i)
            let td: Tape<Dual<Ulp, N>, N> = t.map(|c| Dual::constant(c.to_jet()));
            let xd = Dual::seed(&xu);
            let mut wd = Workspace::default();
            td.jet(&xd, order, &mut wd).unwrap();
            for (o, &node) in p.outs.iter().enumerate() {
                for k in 0..=order {
                    let g = td.output_coef(&wd, order, o, k);
                    let w = &ex[node][k];
                    st.checks += 1 + N;
                    assert!(
                        within(g.v.lo, g.v.hi, &w[0]),
                        "{name} Dual v: out {o} coef {k} = {:?} misses {}\nprog {:?} outs {:?} x {x:?}",
                        g.v,
                        w[0],
                        p.ins,
                        p.outs
                    );
                    for d in 0..N {
                        assert!(
                            within(g.d[d].lo, g.d[d].hi, &w[1 + d]),
                            "{name} Dual d{d}: out {o} coef {k} = {:?} misses {}\nprog {:?} outs {:?} x {x:?}",
                            g.d[d],
                            w[1 + d],
                            p.ins,
                            p.outs
                        );
                    }
                }
            }
        }
    }
}

fn random_x(rng: &mut Rng) -> f64 {
    match rng.below(8) {
        0 => 0.0,
        1 => -0.0,
        2 => 1e-200 * (rng.unit() - 0.5),
        3 => 1e10 * (rng.unit() - 0.5),
        4 => 5e-324,
        _ => 4.0 * (rng.unit() - 0.5),
    }
}

fn run_random<const N: usize>(seed: u64, progs: usize, st: &mut Stats) {
    run_random_box::<N>(seed, progs, st, 0.0)
}
fn run_random_box<const N: usize>(seed: u64, progs: usize, st: &mut Stats, width: f64) {
    let ks = table();
    let mut rng = Rng(seed);
    for _ in 0..progs {
        let p: Prog<N> = random_prog(&mut rng, ks.len());
        let order = 1 + rng.below(10);
        let xs: Vec<[f64; N]> = (0..3)
            .map(|_| std::array::from_fn(|_| random_x(&mut rng)))
            .collect();
        check_prog_box(&p, &ks, &xs, order, st, width);
    }
}

#[test]
fn random_fused_tapes_enclose_exact_jets() {
    let mut st = Stats {
        cases: 0,
        checks: 0,
        each_differs: 0,
        each_wider: 0,
        max_ratio: 0.0,
    };
    // BWCL_ADVERSARIAL_ITERS scales the runs (the review ran 3× these counts)
    let n = |k: u64| (iters(500) * k / 500) as usize;
    run_random::<2>(0x9e3779b97f4a7c15, n(500), &mut st);
    run_random::<3>(0x1234567887654321, n(330), &mut st);
    run_random::<1>(0x0badc0ffee0ddf00, n(170), &mut st);
    let mut sb = Stats {
        cases: 0,
        checks: 0,
        each_differs: 0,
        each_wider: 0,
        max_ratio: 0.0,
    };
    run_random_box::<2>(0x5555aaaa12345678, n(330), &mut sb, 1e-3);
    run_random_box::<3>(0x7777bbbb87654321, n(170), &mut sb, 1e-9);
    eprintln!("boxes: {} cases, {} checks", sb.cases, sb.checks);
    eprintln!(
        "random tapes: {} cases, {} checks; Each ≠ recorded in {} coefficients, wider in {} (max width ratio {})",
        st.cases, st.checks, st.each_differs, st.each_wider, st.max_ratio
    );
}

// ---------------------------------------------------------------- Dot accumulators

#[derive(Clone, PartialEq, PartialOrd, Debug)]
enum X {
    NegInf,
    F(Rational),
    PosInf,
}
fn xf(x: f64) -> X {
    if x == f64::INFINITY {
        X::PosInf
    } else if x == f64::NEG_INFINITY {
        X::NegInf
    } else {
        X::F(q(x))
    }
}
/// Product of extended reals; None for 0·∞ (left out, set-based).
fn xmul(a: &X, b: &X) -> Option<X> {
    match (a, b) {
        (X::F(x), X::F(y)) => Some(X::F(x.clone() * y)),
        (X::F(x), inf) | (inf, X::F(x)) => {
            if *x == 0 {
                None
            } else {
                let pos = (*x > 0) == (*inf == X::PosInf);
                Some(if pos { X::PosInf } else { X::NegInf })
            }
        }
        (a, b) => Some(if a == b { X::PosInf } else { X::NegInf }),
    }
}
fn xadd(a: X, b: X) -> X {
    match (a, b) {
        (X::F(x), X::F(y)) => X::F(x + y),
        (X::F(_), i) | (i, X::F(_)) => i,
        (a, _) => a, // same-signed infinities in each end's sum
    }
}

fn random_end(rng: &mut Rng) -> f64 {
    let s = if rng.below(2) == 0 { 1.0 } else { -1.0 };
    s * match rng.below(12) {
        0 => 0.0,
        1 => 5e-324 * (1 + rng.below(5)) as f64,
        2 => f64::MIN_POSITIVE * rng.unit(),
        3 => f64::MAX * (0.5 + 0.5 * rng.unit()),
        4 => f64::INFINITY,
        5 => 1e-160 * rng.unit(),
        6 => 1e160 * rng.unit(),
        7 => 1.0,
        _ => (rng.unit() - 0.5) * 10f64.powi(rng.below(20) as i32 - 10),
    }
}
fn random_iv(rng: &mut Rng) -> (f64, f64) {
    match rng.below(5) {
        0 => (0.0, 0.0),
        1 => (-0.0, 0.0),
        2 => {
            let x = random_end(rng);
            if x.is_finite() { (x, x) } else { (0.0, 0.0) }
        }
        _ => {
            let (a, b) = (random_end(rng), random_end(rng));
            let (a, b) = if a <= b { (a, b) } else { (b, a) };
            if a == f64::INFINITY || b == f64::NEG_INFINITY {
                (0.0, 0.0)
            } else {
                (a, b)
            }
        }
    }
}

#[test]
fn add_scaled_sums_enclose_the_exact_sums() {
    let mut rng = Rng(0xdeadbeefcafef00d);
    let mut n_cases = 0;
    for _ in 0..iters(100_000) {
        let n = 1 + rng.below(6);
        let terms: Vec<((f64, f64), (f64, f64))> = (0..n)
            .map(|_| (random_iv(&mut rng), random_iv(&mut rng)))
            .collect();
        // exact hull of the set sum
        let (mut lo, mut hi) = (X::F(Rational::new()), X::F(Rational::new()));
        for &((a0, a1), (b0, b1)) in &terms {
            let ps: Vec<X> = [(a0, b0), (a0, b1), (a1, b0), (a1, b1)]
                .iter()
                .filter_map(|&(x, y)| xmul(&xf(x), &xf(y)))
                .collect();
            let (tl, th) = if ps.is_empty() {
                (X::F(Rational::new()), X::F(Rational::new()))
            } else {
                let mut tl = ps[0].clone();
                let mut th = ps[0].clone();
                for p in &ps {
                    if *p < tl {
                        tl = p.clone();
                    }
                    if *p > th {
                        th = p.clone();
                    }
                }
                (tl, th)
            };
            lo = xadd(lo, tl);
            hi = xadd(hi, th);
        }
        let mut d = IntervalDot::new();
        let mut u = UlpDot::new();
        for &((a0, a1), (b0, b1)) in &terms {
            d.add_scaled(&iv(a0, a1), &iv(b0, b1));
            u.add_scaled(&Ulp { lo: a0, hi: a1 }, &Ulp { lo: b0, hi: b1 });
        }
        let s = d.sum();
        let su = u.sum();
        let ok = |l: f64, h: f64| {
            let lo_ok = match &lo {
                X::NegInf => l == f64::NEG_INFINITY,
                X::F(r) => l == f64::NEG_INFINITY || (l.is_finite() && q(l) <= *r),
                X::PosInf => true,
            };
            let hi_ok = match &hi {
                X::PosInf => h == f64::INFINITY,
                X::F(r) => h == f64::INFINITY || (h.is_finite() && *r <= q(h)),
                X::NegInf => true,
            };
            lo_ok && hi_ok
        };
        assert!(
            ok(s.inf(), s.sup()),
            "IntervalDot {terms:?}: {s:?} vs [{lo:?}, {hi:?}]"
        );
        assert!(
            ok(su.lo, su.hi),
            "UlpDot {terms:?}: {su:?} vs [{lo:?}, {hi:?}]"
        );
        n_cases += 1;
    }
    eprintln!("dot sums: {n_cases} random sums checked");
}

// ---------------------------------------------------------------- targeted cases

fn c(x: f64) -> Interval {
    iv(x, x)
}

#[test]
fn edge_tapes_do_not_panic_and_enclose() {
    // only a shift; shift of shift; neg of neg; x − c·x; unused linear nodes; linear
    // output used by linear and non-linear ops; repeated leaves
    let rec = Tape::<Interval, 2>::record(|v| {
        let s = v[0].shift(&c(1.0)).shift(&c(-1.0)); // x0 exactly
        let nn = -(-v[1].clone()); // x1
        let _unused = v[0].clone() + v[1].clone();
        let _unused_chain = (v[0].clone() - v[1].clone()).scale(&c(3.0));
        let z = v[0].clone() - v[0].scale(&c(1.0)); // 0
        let o = s.clone() + nn.clone(); // x0 + x1, output, used below
        let m = o.clone() * o.clone();
        let f0 = o.clone().scale(&c(2.0)) + m.clone() + z.clone();
        let f1 = -o.clone() - o.clone() + m.scale(&c(0.5)).scale(&c(2.0)) - m;
        vec![f0, f1, o, z, nn]
    });
    for t in [rec.fused(Rounding::Each), rec.fused(Rounding::Once)] {
        let x = [c(0.3), c(-0.7)];
        let mut ws = Workspace::default();
        let j = t.jet(&x, 6, &mut ws).unwrap();
        let r = rec.jet(&x, 6, &mut Workspace::default()).unwrap();
        for i in 0..2 {
            for k in 0..=6 {
                assert!(
                    !j[i][k].intersection(r[i][k]).is_empty(),
                    "{:?} vs {:?}",
                    j[i][k],
                    r[i][k]
                );
            }
        }
        let z = t.output_coef(&ws, 6, 3, 0);
        eprintln!("z = x0 − 1·x0 fused: {z:?}; tape {:?}", t.ops());
        // infinite inputs
        let e = t.eval(&[Interval::ENTIRE, c(1.0)]);
        eprintln!("ENTIRE input eval: {e:?}");
        assert!(e[3].contains(0.0));
    }
    // a tape whose only op beyond the variables is a shift (an output)
    let t = Tape::<Interval, 1>::record(|v| vec![v[0].shift(&c(1.0))]).fused(Rounding::Once);
    let j = t.jet(&[c(0.0)], 4, &mut Workspace::default()).unwrap();
    assert!(j[0][1].contains(1.0));
    // fusing twice
    let twice = std::panic::catch_unwind(|| {
        Tape::<Interval, 1>::record(|v| vec![v[0].scale(&c(2.0)).shift(&c(1.0)).scale(&c(3.0))])
            .fused(Rounding::Once)
            .fused(Rounding::Once)
            .len()
    });
    assert!(twice.is_ok(), "fusing a fused tape panicked");
}

/// Parameter components and powers with a variable exponent (SpowV, PowLn, log_lead, Twin)
/// around linear chains: structure survives and the fused jets overlap the recorded ones.
#[test]
fn parameters_and_variable_powers_survive_fusion() {
    let params = [None, None, Some(iv(2.0, 2.0))];
    let rec = Tape::<Interval, 3>::record_with(params, |v| {
        let (x, y, p) = (v[0].clone(), v[1].clone(), v[2].clone());
        let xs = x.shift(&c(0.5)).scale(&c(2.0)) - y.clone(); // a chain feeding powers
        let s = <Rec<Interval> as Real>::spow(&xs, &p);
        let a = <Rec<Interval> as Real>::apow(&xs, &p);
        let l = <Rec<Interval> as Real>::pow_ln(&xs, &p, true);
        let q15 = Scalar::spow(&xs, &c(1.5));
        let q15b = Scalar::apow(&xs, &c(1.5)); // Twin
        let pp = p.shift(&c(1.0)).scale(&c(0.5)); // tconst chain
        let f0 = y.clone() + s.scale(&c(0.25)) - a.scale(&c(0.25)) + pp.clone() * x.clone();
        let f1 = -(x.clone() - q15.scale(&c(0.1))) + q15b - l.scale(&c(1e-3));
        let f2 = Rec::constant(c(0.0));
        vec![f0, f1, f2, xs, pp]
    });
    let x = [c(0.7), c(-0.2), c(2.0)];
    let mut w0 = Workspace::default();
    let r = rec.jet(&x, 8, &mut w0).unwrap();
    for (name, t) in [
        ("each", rec.fused(Rounding::Each)),
        ("once", rec.fused(Rounding::Once)),
    ] {
        let mut ws = Workspace::default();
        let j = t.jet(&x, 8, &mut ws).unwrap();
        for i in 0..3 {
            for k in 0..=8 {
                assert!(
                    !j[i][k].intersection(r[i][k]).is_empty(),
                    "{i} {k}: {:?} vs {:?}",
                    j[i][k],
                    r[i][k]
                );
                let (a, b) = (j[i][k].wid(), r[i][k].wid());
                if a > 2.0 * b + 1e-14 * (1.0 + r[i][k].mag()) {
                    eprintln!("{}: x{i}_{k} width {a:e} vs recorded {b:e}", name);
                }
            }
        }
        for o in 3..5 {
            for k in 0..=8 {
                assert!(
                    !t.output_coef(&ws, 8, o, k)
                        .intersection(rec.output_coef(&w0, 8, o, k))
                        .is_empty()
                );
            }
        }
        assert!(
            t.ops().iter().any(|o| matches!(o, Op::Lin(_))),
            "{:?}",
            t.ops()
        );
        // duals of the fused tape
        let td: Tape<Dual<Ulp, 3>, 3> = t.map(|c| Dual::constant(c.to_jet()));
        let tr: Tape<Dual<Ulp, 3>, 3> = rec.map(|c| Dual::constant(c.to_jet()));
        let xd = Dual::seed(&x.map(|x| x.to_jet()));
        let a = td.jet(&xd, 5, &mut Workspace::default()).unwrap();
        let b = tr.jet(&xd, 5, &mut Workspace::default()).unwrap();
        for i in 0..3 {
            for k in 0..=5 {
                let ov = |u: &Ulp, w: &Ulp| u.lo <= w.hi && w.lo <= u.hi;
                assert!(ov(&a[i][k].v, &b[i][k].v));
                for d in 0..3 {
                    assert!(
                        ov(&a[i][k].d[d], &b[i][k].d[d]),
                        "{i} {k} d{d}: {:?} {:?}",
                        a[i][k].d[d],
                        b[i][k].d[d]
                    );
                }
            }
        }
    }
}
