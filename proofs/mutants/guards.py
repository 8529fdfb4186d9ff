#!/usr/bin/env python3
"""Removes each soundness guard of the rigorous engine alone and runs the tests that must see it.

Usage (from the repository root; a clean work tree): python3 proofs/mutants/guards.py [NAME...]
       python3 proofs/mutants/guards.py --check   (each guard's text occurs exactly once; no build)
Each mutation is applied to a copy of the tree in a temporary directory (the work tree is never
changed), `cargo test --release` runs the named test targets there, and a line per guard says
which tests failed. A guard whose removal leaves every test green is reported as SURVIVED and the
script exits 1. The results are in proofs/MUTANTS.md.
"""
import os, re, shutil, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# the test targets that check enclosures: the library's unit tests and these files of tests/
TESTS = ["--lib", "--test", "guards", "--test", "rigorous", "--test", "references",
         "--test", "outward"]


def commands(tests):
    """The `cargo test` argument lists that run `tests`, written as targets and filters
    (`--lib`, `--test FILE`, test-name filters). The files of tests/ are modules of one program,
    tests/suite.rs: `--test FILE` runs `--test suite` with the filters given,
    or with `FILE::` when none is. The library's unit tests run in a command of their own (a
    module filter would leave them out)."""
    lib, files, filters = False, [], []
    it = iter(tests)
    for a in it:
        if a == "--lib":
            lib = True
        elif a == "--test":
            files.append(next(it))
        elif a != "--":
            filters.append(a)
    out = []
    if lib:
        out.append(["--lib", "--", *filters])
    if files:
        out.append(["--test", "suite", "--", *(filters or [f + "::" for f in files])])
    return out

# (name, file, [(exact text, replacement)], what it removes[, the cargo test arguments that
# must see it: TESTS when not given])
GUARDS = [
    # issue #34: the derived outputs' maxima enclosed on the proved flow (observables/derived.rs)
    ("derived-lower-inside", "src/observables/derived.rs",
     [("        if t <= ts_lo {\n", "        if t <= ts.hi() {\n")],
     "a maximum's lower bound read only at times ≤ inf T_s (inside [0, T_s] for every T_s)",
     ["--lib", "derived"]),
    ("derived-upper-to-sup", "src/observables/derived.rs",
     [("        let b = p.t1().min(ts_hi);", "        let b = p.t1().min(ts_lo);")],
     "a maximum's upper bound covers [0, sup T_s]",
     ["--lib", "derived"]),
    ("derived-empty-upper", "src/observables/derived.rs",
     [("    if x.is_empty() { f64::INFINITY } else { x.hi() }", "    x.hi()")],
     "an empty enclosure bounds nothing from above (+∞, not inari's −∞)",
     ["--lib", "derived"]),
    ("derived-mvf-rate", "src/observables/derived.rs",
     [("let mvf = centre + (t - mid) * q.rate(m, &bx);",
       "let mvf = centre + (t - mid) * (q.rate(m, &bx) * I::from_exact_f64(0.5));")],
     "the mean-value form's slope ∇q·f over the whole cell (halved: too narrow a bound)",
     ["--lib", "derived"]),
    # issue #33: a classical law's physical parameters to its nondimensional model
    # (models/classical.rs), checked against the closed forms in seconds (tests/law_cor.rs)
    ("law-sigma-physical", "src/models/classical.rs",
     [("self.d.clone() * v0.clone() / self.k.clone()", "self.d.clone() * v0.clone()")],
     "Hunt–Crossley σ = χ·v0/k: the division by k dropped",
     ["--test", "law_cor", "one_law"]),
    ("law-zeta-physical", "src/models/classical.rs",
     [("self.d.clone() / (R::from_int(2) * (self.m.clone() * self.k.clone()).sqrt())",
       "self.d.clone() / (self.m.clone() * self.k.clone()).sqrt()")],
     "Kelvin–Voigt ζ = c/(2√(mk)): the factor 2 dropped",
     ["--test", "law_cor", "closed_forms"]),
    ("law-time-scale", "src/models/classical.rs",
     [(".pow(&(one.clone() / (self.n.clone() + one)));", ".pow(&(one.clone() / self.n.clone()));")],
     "the length scale L = (m v0²/k)^(1/(n+1)) (the time scale T_c = L/v0 with it)",
     ["--test", "law_cor", "closed_forms"]),
    ("law-params-outward", "src/cli/output.rs",
     [("m.iter().map(|(k, v)| (*k, JsonPair(*v))).collect();", "m.iter().map(|(k, v)| (*k, *v)).collect();")],
     "a law's parameter enclosures in JSON rounded outward (not the doubles' shortest decimals)",
     ["--test", "law_cor", "json_names"]),
    ("sample-last", "src/observables/trajectory.rs",
     [("            if i == last {\n                end", "            if i == last && false {\n                end")],
     "the last sample time of a trajectory exactly its end (end·i/(N − 1) rounds off it)",
     ["--lib", "the_last_sample_time"]),
    ("cancel-taylor", "src/engines/taylor/options.rs",
     [("        crate::engines::cancel::requested()\n            || self", "        self")],
     "the Taylor engine stops on a cancellation request (Ctrl-C in Python) as at its deadline",
     ["--test", "cancel"]),
    ("law-positive-mk", "src/models/classical.rs",
     [('_ if must_be_positive(law, key) && v[0] <= zero => fail("> 0"),',
       '_ if must_be_positive(law, key) && v[0] < zero => fail("> 0"),')],
     "m, k > 0 checked as written (0 refused)",
     ["--test", "law_cor", "bad_law_input"]),
    # issue #33: the Hunt–Crossley CoR proved from its closed form (observables/restitution.rs)
    ("laws-sign", "src/observables/restitution.rs",
     [("    } else if h.lo() > 0.0 {\n        1", "    } else if h.hi() > 0.0 {\n        1")],
     "the proved sign H > 0 (an H straddling 0 taken as positive)",
     ["--test", "laws"]),
    ("laws-ends-hull", "src/identify/laws.rs",
     [(".map(|(x, y)| Some(x.as_ref()?.convex_hull(*y.as_ref()?)))", ".map(|(x, _y)| Some(*x.as_ref()?))")],
     "a law's e over [a, b] is the hull of both ends' enclosures (monotone e): the b end dropped",
     ["--test", "compare", "hunt_crossley_feasible"]),
    ("laws-extend-side", "src/identify/laws.rs",
     [("            && below == down\n", "            && below != down\n")],
     "an end refutation is carried to θ → ∞ only when the monotone e keeps the row's side there",
     ["--test", "compare", "not_extended"]),
    ("laws-judge-side", "src/identify/laws.rs",
     [("RowVerdict::Outside(e.sup() < t.outer().inf())", "RowVerdict::Outside(e.inf() > t.outer().sup())")],
     "a refuting row records whether its e is below or above its target (the side the extension reads)",
     ["--test", "compare", "not_extended"]),
    ("laws-tighten", "src/observables/restitution.rs",
     [("        if f(&c) == s {", "        if f(&c) != -s {")],
     "a bracket end moved only to a midpoint whose sign is proved (an undecided one taken)",
     ["--test", "laws", "every_rational"]),
    ("laws-monotone-ends", "src/observables/restitution.rs",
     [("    let (lo, _) = cor_at(sigma.sup(), tight)?;", "    let (lo, _) = cor_at(sigma.inf(), tight)?;")],
     "e over [σ] from the bracket at sup σ (e decreasing): the lower end taken at inf σ",
     ["--lib", "restitution"]),
    ("laws-exact-ends", "src/observables/restitution.rs",
     [("    let (lo, _) = exact_sigma_at(e.sup(), tight)?;", "    let (lo, _) = exact_sigma_at(e.inf(), tight)?;")],
     "σ* over [e] from the bracket at sup e (σ* decreasing): the lower end taken at inf e",
     ["--lib", "restitution"]),
    ("laws-within", "src/observables/restitution.rs",
     [("    } else if x.hi() <= t.lo() && x.lo() >= -t.lo() {", "    } else if x.hi() <= t.lo() {")],
     "the lower half of |e − e*| ≤ tol in a piece's verdict",
     ["--test", "laws", "paving"]),
    ("laws-outside", "src/observables/restitution.rs",
     [("    } else if x.lo() > t.hi() || x.hi() < -t.hi() {", "    } else if x.lo() > t.hi() || x.hi() < t.hi() {")],
     "|e − e*| > tol on a whole piece (an error below +tol taken as outside)",
     ["--test", "laws", "paving"]),
    ("laws-range-outward", "src/observables/restitution.rs",
     [("outward(hi, Rounding::Up)?", "outward(hi, Rounding::Down)?")],
     "the paving's upper end rounded up to a double (the decimal range covered whole)",
     ["--test", "laws", "cover"]),
    # issue #32: the adaptive split of ranges (observables/split.rs)
    ("split-inner", "src/observables/split.rs",
     [("        .map(|p| pick(p).sup())\n        .fold(f64::INFINITY, f64::min);",
       "        .map(|p| pick(p).inf())\n        .fold(f64::INFINITY, f64::min);")],
     "the inner bound min e ≤ a from the points' upper ends (their lower ends taken)",
     ["--test", "sets"]),
    ("split-overshoot", "src/observables/split.rs",
     [("            .filter(|&(o, _)| o > 1.0)", "            .filter(|&(o, _)| o > f64::INFINITY)")],
     "the cuts of the pieces that overshoot the hull's ends (the hull of the first proved pieces)",
     ["--test", "sets"]),
    ("split-json-inner", "src/cli/output.rs",
     [("        Some(p) => json_directed_pair(*p, [Rounding::Up, Rounding::Down], s),",
       "        Some(p) => json_directed_pair(*p, [Rounding::Down, Rounding::Down], s),")],
     "the inward rounding of the printed inner bound a (rounded down)",
     ["--test", "cli", "a_range_reports"]),
    # issue #31: set-membership identification (the paving's claims)
    ("identify-form-slopes", "src/identify/form.rs",
     [("        y += term(gj, uj, cj);", "")],
     "the slope terms of the mean-value form over a box (the centre's value alone)",
     ["--test", "identify"]),
    ("identify-hull-violated", "src/identify/paving.rs",
     [("            if y.disjoint(target.outer()) {\n                return Verdict::Violated;",
       "            if !y.subset(target.outer()) {\n                return Verdict::Violated;")],
     "a box refuted by a row's hull over it only where the hull misses the outer target",
     ["--test", "identify"]),
    ("identify-hull-inside", "src/identify/paving.rs",
     [("            if target.inner().is_some_and(|i| y.subset(i)) {\n                still[k] = false;",
       "            if !y.disjoint(target.outer()) {\n                still[k] = false;")],
     "a row closed on a box by its hull only where the hull is inside the inner target",
     ["--test", "identify"]),
    # issue #31: the f64 inner estimate of F's hull reports only points that meet every row
    ("sample-meets", "src/identify/sample.rs",
     [("meets(e, &r.e) && r.tc", "(meets(e, &r.e) || true) && r.tc")],
     "a sampled point kept only where its e meets the row's target",
     ["--test", "identify", "sampled_points"]),
    ("sample-push-end", "src/identify/sample.rs",
     [("    if feasible(problem, &end) {\n        return (end, 1);",
       "    if true {\n        return (end, 1);")],
     "a push keeps the face's point only when it is feasible",
     ["--test", "identify", "sampled_points"]),
    ("apriori", "src/engines/taylor/step.rs",
     [("            if subset(&ynew, &y, tape.params()) {", "            if true {")],
     "the a-priori inclusion test of the Taylor step"),
    ("picard", "src/engines/taylor/step.rs",
     [("if ynew.iter().all(|c| c.is_finite() && !c.is_empty()) && subset(&ynew, &y, params) {",
       "if ynew.iter().all(|c| c.is_finite() && !c.is_empty()) {")],
     "the Picard inclusion test of the low-order step"),
    # issue #32 item 4: the second variational system's steps (src/engines/taylor/integrable.rs)
    ("integrable-bound", "src/engines/taylor/integrable.rs",
     [("let avg = integral.hi();", "let avg = 0.5 * integral.hi();")],
     "the bound ∫_{Y_w}|w|^r dw / min|ẇ| of a singular power's integral over a step (halved)",
     ["--lib", "integrable"]),
    ("integrable-signed", "src/engines/taylor/integrable.rs",
     [("I::from_bounds(if p.signed { -avg } else { 0.0 }, avg)?", "I::from_bounds(0.0, avg)?")],
     "a signed power's average of either sign (taken as nonnegative)",
     ["--lib", "integrable"]),
    ("integrable-interior", "src/engines/taylor/integrable.rs",
     [("std::array::from_fn(|i| x[i].clone() + tau1.clone() * dh[i].clone());",
       "std::array::from_fn(|i| x[i].clone());")],
     "the singular part hull(0, h·q_i) of the piece at interior times",
     ["--lib", "integrable"]),
    ("integrable-rate", "src/engines/taylor/integrable.rs",
     [("        } else {\n            return None;\n        };\n        let r1",
       "        } else {\n            rate.lo().abs()\n        };\n        let r1")],
     "the operand's rate keeps its sign over the box (min|ẇ| > 0)",
     ["--lib", "integrable"]),
    ("integrable-exact-sign", "src/engines/taylor/integrable.rs",
     [("items.push((p.node, -(minus * inv)));", "items.push((p.node, minus * inv));")],
     "a signed power's negative part at rate ±1 (its integral taken with the wrong sign)",
     ["--lib", "integrable"]),
    ("integrable-exact-direction", "src/engines/taylor/integrable.rs",
     [("                (w1, x[p.var].clone())\n", "                (x[p.var].clone(), w1)\n")],
     "the range a decreasing operand traverses, [w(h), w(0)]",
     ["--lib", "integrable"]),
    # issue #32 item 4: a branch point crossed in its variable (src/engines/taylor/crossing.rs)
    ("crossing-entry-length", "src/engines/taylor/crossing.rs",
     [("    let ds = (pt(s_a) - s0).sup();", "    let ds = (pt(s_a) - s0).inf();")],
     "the entry's lengths Δs ∈ [0, s_a − s₀] for every member (the shortest taken)",
     ["--lib", "crossing"]),
    ("crossing-exit-length", "src/engines/taylor/crossing.rs",
     [("    let dt = (pt(t1) - xb[D]).sup();", "    let dt = (pt(t1) - xb[D]).inf();")],
     "the exit's lengths Δt ∈ [0, t₁ − t_b] for every member (the shortest taken)",
     ["--lib", "crossing"]),
    ("crossing-direction", "src/engines/taylor/crossing.rs",
     [("    if (sgi * tape.eval(xa)[j]).inf() <= 0.0 {", "    if false && (sgi * tape.eval(xa)[j]).inf() <= 0.0 {")],
     "a set is crossed only when it moves towards the branch point",
     ["--lib", "crossing"]),
    ("crossing-clear-separation", "src/engines/taylor/crossing.rs",
     [("    kinks_off && (f.inf() > 0.0 || v.sup() < 0.0)", "    kinks_off && (true || f.inf() > 0.0 || v.sup() < 0.0)")],
     "no box of a crossing may hold the separation condition",
     ["--lib", "crossing"]),
    ("crossing-clear-kinks", "src/engines/taylor/crossing.rs",
     [("        .all(|&k| k >= n_state || !b[k].contains(0.0));", "        .all(|&k| true || k >= n_state || !b[k].contains(0.0));")],
     "no box of a crossing may hold a kink component's 0",
     ["--lib", "crossing"]),
    ("crossing-windows-clear", "src/engines/taylor/crossing.rs",
     [("    if !boxes_clear {", "    if false && !boxes_clear {")],
     "no box of the windows in s (nor the step across 0) may hold a kink's 0 or the separation",
     ["--lib", "crossing"]),
    ("crossing-watch-before", "src/engines/taylor/crossing.rs",
     [("            if p.t1() >= before {", "            if false && p.t1() >= before {")],
     "a branch point is reported only in pieces that end before the separation may start",
     ["--lib", "crossing"]),
    # a window whose end no step length lands on (src/engines/taylor/window.rs, 2026-11-29)
    ("window-landing", "src/engines/taylor/window.rs",
     [("let (target, to_end) = landing(t, t1).ok_or_else",
       "let (target, to_end) = end_length(t, t1).map(|h| (t1, h)).ok_or_else")],
     "a window stops at a power of 2 on the way where no length lands on its end",
     ["--lib", "window"]),
    ("second-order-jumps-off-kinks", "src/observables/curvature.rs",
     [("    if let Some(j) = tape.jump_off_the_kinks() {", "    if let Some(j) = None::<usize> {")],
     "a derivative that jumps off the kinks uncarried (an exponent 0 or varying) refuses the second-order form",
     ["--test", "curvature", "jumps_off"]),
    # SHC DSA's |Z|^n with n = 1 in the second variational system (2026-11-29, third session)
    ("sign-jump-in-time", "src/engines/taylor/integrable.rs",
     [("        .chain(&signs)\n", "        .chain(&signs[..0])\n")],
     "the jump of S₂ where a low-order step crosses the 0 of a component whose sign the tape takes",
     ["--lib", "integrable"]),
    ("sign-jump-crossing", "src/engines/taylor/crossing.rs",
     [("        mid[lay.s2(i)] = mid[lay.s2(i)] + di;", "        let _ = di;")],
     "the jump of S₂ at s = 0 of a branch point crossed in its variable where the tape takes its sign",
     ["--test", "curvature", "shc_dsa_second"]),
    ("sign-jump-crossing-side", "src/engines/taylor/crossing.rs",
     [("let di = if sg > 0.0 { d[i] } else { -d[i] };",
       "let di = if sg > 0.0 { -d[i] } else { d[i] };")],
     "that jump's sign from the side x_j comes from",
     ["--test", "curvature", "shc_dsa_second"]),
    ("sign-jumps-in-df", "src/engines/taylor/tape/integrable.rs",
     [("if !self.kinks.contains(&j) && in_df(i) {",
       "if !self.kinks.contains(&j) && (in_df(i) || true) {")],
     "only a sgn that reaches the rates of S (D_x f) is taken as a jump of S₂",
     ["--lib", "integrable"]),
    ("sign-in-the-rates", "src/engines/taylor/tape/integrable.rs",
     [(".find_map(|(i, j)| self.reaches(i, 0..n.min(N)).then_some(j))",
       ".find_map(|(i, j)| (self.reaches(i, 0..n.min(N)) && false).then_some(j))")],
     "a field that itself takes a component's sign (a jump of f, not of D_x f) is found",
     ["--lib", "integrable"]),
    ("switch-on-an-expression", "src/engines/taylor/tape/integrable.rs",
     [("(!self.tconst[a] && !matches!(self.ops[a], Op::Var(_))).then_some(i)",
       "(!self.tconst[a] && !matches!(self.ops[a], Op::Var(_)) && false).then_some(i)")],
     "a switch (|g|, sgn g, a non-entire power, ln|g|) on an expression g of the state is found",
     ["--lib", "integrable"]),
    ("second-order-switch-refused", "src/engines/taylor/integrate.rs",
     [("if tape.second_order().is_some() && tape.switch_on_an_expression().is_some() {",
       "if tape.second_order().is_some() && tape.switch_on_an_expression().is_some() && false {")],
     "a second variational system switching on an expression (S₂'s jumps there carried by "
     "nothing) is refused before any step",
     ["--lib", "integrable"]),
    ("integrable-affine", "src/engines/taylor/tape/integrable.rs",
     [("                        (Free, d) | (d, Free) => d,\n                        _ => Other,",
       "                        (Free, d) | (d, Free) => d,\n                        _ => Affine,")],
     "the field affine in the singular powers (a product of two refused)",
     ["--lib", "integrable"]),
    ("kink-jump", "src/engines/taylor/step.rs",
     [("            if let Some(j) = super::integrable::kink_jump(tape, x, &ynew, Some(&x1)) {\n                x1 = ",
       "            if let Some(j) = None::<[I; N]> {\n                x1 = ")],
     "the jump of S₂ at a kink crossed by a low-order step",
     ["--test", "curvature", "maxwell_dsa"]),
    ("kink-jump-decided", "src/engines/taylor/integrable.rs",
     [("let crossed = matches!((before, after), (Some(b), Some(a)) if a == -b);",
       "let crossed = before.is_some() && after != before;")],
     "ΔS₂ itself only where every member has crossed (else hull(0, ΔS₂))",
     ["--lib", "integrable"]),
    ("kink-jump-sign", "src/engines/taylor/integrable.rs",
     [("                Some(-1) => d[i].clone(),", "                Some(-1) => -d[i].clone(),")],
     "the jump's sign from the side the kink is crossed from",
     ["--lib", "integrable"]),
    # issue #32: the set carried between steps as an affine set (src/engines/taylor/affine.rs)
    ("affine-spread", "src/engines/taylor/affine.rs",
     [("(bj[i].clone() - gj[i].clone(), u.clone())", "(gj[i].clone() - gj[i].clone(), u.clone())")],
     "the image's error term (B_j − mid B_j)·u_j: an interval Jacobian's spread",
     ["--lib", "affine"]),
    ("affine-centre", "src/engines/taylor/affine.rs",
     [("            (z0[i].clone() - c[i].clone())\n", "            I::zero()\n")],
     "the image's error term z0 − c′: the new centre's rounding",
     ["--lib", "affine"]),
    ("affine-displacement", "src/engines/taylor/affine.rs",
     [("+ (s[i].clone()\n                    + I::dot(\n                        b.iter()\n                            .zip(&g)",
       "+ (I::zero()\n                    + I::dot(\n                        b.iter()\n                            .zip(&g)")],
     "the image's error term s − mid s: the step's displacement and remainder beyond the centre",
     ["--lib", "affine"]),
    ("affine-shift", "src/engines/taylor/affine.rs",
     [("std::array::from_fn(|i| z[i].clone() - c[i].clone());", "std::array::from_fn(|_| I::zero());")],
     "a shifted set's error term c + D − c′",
     ["--lib", "affine"]),
    ("affine-merge", "src/engines/taylor/affine.rs",
     [("        self.push_box(&e);\n    }\n\n    fn finite", "    }\n\n    fn finite")],
     "the merged symbols' box (the smallest symbols dropped instead)",
     ["--lib", "affine"]),
    ("affine-finite", "src/engines/taylor/affine.rs",
     [("let ok = |x: &I| x.is_finite();", "let ok = |_x: &I| true;")],
     "an unbounded set dropped for the direct box (image, shifted)",
     ["--lib", "affine"]),
    ("step-end-remainder", "src/engines/taylor/step.rs",
     [("let d = taylor_eval(&cm[1..], &rem, &tau1);",
       "let d = taylor_eval(&cm[1..], &rem.clone().map(|_| I::zero()), &tau1);")],
     "the remainder x_K(Y) in the step's end state (the displacement s of the affine image)",
     ["--test", "guards", "a_taylor_step"]),
    ("newton", "src/engines/taylor/newton.rs",
     [("        if n.interior(&t) {", "        if true {")],
     "interval Newton's existence proof N(T) ⊆ int T"),
    ("ts-midpoint", "src/engines/taylor/event.rs",
     [("Some(Some(ts)) => return self.found(ts),",
       "Some(Some(ts)) => return self.found(point(ts.mid())),")],
     "the T_s enclosure (collapsed to its midpoint)"),
    ("event-which-zero", "src/engines/taylor/event.rs",
     [("        let attempt = if v.lo() > 0.0 {", "        let attempt = if v.lo() < 0.0 {")],
     "the separation event's condition V > 0 for a zero of F (a zero of F while V < 0 taken)"),
    ("kink-side", "src/engines/taylor/step.rs",
     [("        let sd = if side[i] > 0 { d } else { -d };", "        let sd = d;")],
     "the kink check's side (the rate of x_i instead of s·x_i)"),
    ("kink-old", "src/engines/taylor/step.rs",
     # s·d.lo() and s·d.hi() of the rate d of x_i, written through sd = s·d (d is moved)
     [("        if sd.lo() > 0.0 {", "        if (if side[i] > 0 { sd.lo() } else { sd.hi() }) > 0.0 {"),
      ("        if sd.hi() >= 0.0 {", "        if (if side[i] > 0 { sd.hi() } else { sd.lo() }) >= 0.0 {")],
     "the kink check as it was before issue #12 (right for s = +1 only)"),
    ("span", "src/engines/taylor/step.rs",
     [("    (t1, span(tau::<Interval>(&point(t1), t0).sup()))",
       "    (t1, span((t1 - t0).max(h)))")],
     "the validated span's upper bound of t1 − t0"),
    ("integral-exponent", "src/engines/taylor/tape/shortcuts.rs",
     [("&& consts[c].encloses(&q1)", "")],
     "the check q′ ⊇ q − 1 before a power is taken as the integral of a product"),
    ("integral-mpfr-ends", "src/engines/taylor/tape/shortcuts.rs",
     [("&& consts[c].encloses(&q1)", "&& consts[c].lo() <= q1.lo() && q1.hi() <= consts[c].hi()")],
     "the check q′ ⊇ q − 1 on the exponents' own ends (on their f64 bounds instead)"),
    ("integral-twin", "src/engines/taylor/tape/shortcuts.rs",
     [(" || read_by_twin(s)", "")],
     "no integral for a power whose series a Twin reads"),
    ("sign-copy-parameter", "src/engines/taylor/tape/shortcuts.rs",
     [("        Op::Abs(_) if tconst[n] => None,\n", "")],
     "no sign copy through |·| of a parameter (whose sign a jet never sets)"),
    ("integral-derivative", "src/engines/taylor/tape/shortcuts.rs",
     [("                    d == field[v]\n", "                    true\n")],
     "the check that the product's other factor is the field's ẋ_v"),
    ("integral-factor", "src/engines/taylor/tape/jet.rs",
     [("c[m * k1 + k - 1].mul_constant(qv).div_int(k as i64)",
       "c[m * k1 + k - 1].div_int(k as i64)")],
     "the factor q of an integral power's coefficients u_k = q·m_{k−1}/k"),
    ("sign-copy", "src/engines/taylor/tape/jet.rs",
     [(".map(|&n| if n == NO_SIGN { 1 } else { sign[n] })",
       ".map(|&n| if n == NO_SIGN { 1 } else { 1 })")],
     "the sign of a product copied from an earlier one"),
    ("merge-sign", "src/engines/taylor/tape/merges.rs",
     [("let merged = if sign[m] < 0 {", "let merged = if sign[m] > 0 {")],
     "the sign s of a merged pair's constant c_j + s·c_j′ (the copy's sign, reversed)"),
    ("merge-always-sum", "src/engines/taylor/tape/merges.rs",
     [("let merged = if sign[m] < 0 {", "let merged = if false {")],
     "a merged pair's constant always c_j + c_j′ (the copy's sign ignored)"),
    ("sign-copy-exponent", "src/engines/taylor/tape/shortcuts.rs",
     [("!same_exponent(qi, qj)", "false")],
     "the check that a sign copy's two powers have the same exponent"),
    ("sign-copy-holder", "src/engines/taylor/tape/shortcuts.rs",
     [("            let holder = if hj {", "            let holder = if true {")],
     "the choice of the power node that holds the sign of w (an entire power holds none)"),
    ("merge-origin", "src/engines/taylor/tape/record.rs",
     [("nodes.iter().all(|&n| n == NO_SIGN || !ambiguous[n])",
       "nodes.iter().all(|&n| n == NO_SIGN || true)")],
     "no merged pair through a node that stands for operations of different origin"),
    ("merge-exponent-origin", "src/engines/taylor/tape/record.rs",
     [("&& (c == d || (thin_point(c) && thin_point(d) && same_const(c, d)))",
       "&& (c == d || same_const(c, d))")],
     "a merged pair's exponents one recorded constant (or one exact point), not equal enclosures"),
    ("const-exact", "src/engines/taylor/tape/record.rs",
     [("c == d || (consts[c].encloses(&consts[d]) && consts[d].encloses(&consts[c]))",
       "c == d || cbits(c) == cbits(d)")],
     "constants compared on the type's own ends (MPFR), not their f64 bounds, before operations are one"),
    ("pow-factors-exponent", "src/engines/taylor/tape/powers.rs",
     [("if table.len() < len || !key.as_ref().is_some_and(|k| k.identical(q)) {",
       "if table.len() < len {")],
     "a power's factor table q(k − j) − j made anew for another exponent (a reused Workspace)"),
    ("pow-factors-f64-key", "src/engines/taylor/tape/powers.rs",
     [("!key.as_ref().is_some_and(|k| k.identical(q))",
       "!key.as_ref().is_some_and(|k| (k.lo(), k.hi()) == (q.lo(), q.hi()))")],
     "the factor table's exponent compared on its own ends (MPFR), not its f64 bounds"),
    ("merge-once", "src/engines/taylor/tape/merges.rs",
     [(" && !used(a) && !used(b))", ")")],
     "each term of a fused form in at most one merged pair (a product with two sign copies)"),
    ("sign-copy-other-factor", "src/engines/taylor/tape/shortcuts.rs",
     [("|| xi != xj ", "")],
     "a sign copy's other factor the same x as its product's (x or |x|)"),
    ("ln-memo-key-hi", "src/arith/interval/elementary.rs",
     [("get_or([a, b, 0, 0], || ln(x))", "get_or([a, a, 0, 0], || ln(x))")],
     "the remembered logarithm keyed by both ends of x (without the upper end)"),
    ("ln-memo-key-lo", "src/arith/interval/elementary.rs",
     [("get_or([a, b, 0, 0], || ln(x))", "get_or([b, b, 0, 0], || ln(x))")],
     "the remembered logarithm keyed by both ends of x (without the lower end)"),
    ("pow-memo-exponent", "src/arith/interval/elementary.rs",
     [(".get_or([a, b, c, d], ||", ".get_or([a, b, 0, 0], ||")],
     "the remembered power keyed by the exponent"),
    ("pow-memo-exponent-hi", "src/arith/interval/elementary.rs",
     [(".get_or([a, b, c, d], ||", ".get_or([a, b, c, c], ||")],
     "the remembered power keyed by both ends of the exponent (without the upper end)"),
    ("pow-memo-exponent-lo", "src/arith/interval/elementary.rs",
     [(".get_or([a, b, c, d], ||", ".get_or([a, b, d, d], ||")],
     "the remembered power keyed by both ends of the exponent (without the lower end)"),
    ("pow-memo-base-hi", "src/arith/interval/elementary.rs",
     [(".get_or([a, b, c, d], ||", ".get_or([a, a, c, d], ||")],
     "the remembered power keyed by both ends of the base (without the upper end)"),
    ("pow-memo-base-lo", "src/arith/interval/elementary.rs",
     [(".get_or([a, b, c, d], ||", ".get_or([b, b, c, d], ||")],
     "the remembered power keyed by both ends of the base (without the lower end)"),
    ("pow-minus-one-rounding", "src/arith/interval/elementary.rs",
     [("then(|| div_as_inari(ONE, x));",
       "then(|| Interval::try_from((1.0 / x.sup(), 1.0 / x.inf())).unwrap());")],
     "x^(−1) = 1/x rounded outward (to nearest instead)"),
    ("pow-minus-one-lo-only", "src/arith/interval/elementary.rs",
     [("if q.inf() == -1.0 && q.sup() == -1.0 {", "if q.inf() == -1.0 {")],
     "the quotient 1/x only for q = −1 exactly (taken for q = [−1, b])"),
    ("pow-minus-one-hi-only", "src/arith/interval/elementary.rs",
     [("if q.inf() == -1.0 && q.sup() == -1.0 {", "if q.sup() == -1.0 {")],
     "the quotient 1/x only for q = −1 exactly (taken for q = [a, −1])"),
    ("truncated-move", "src/engines/taylor/singular/puiseux.rs",
     [("                rem = add(&rem, &mul(c, &ctx.ranges[*i as usize]));\n", "")],
     "the remainder of the terms a value moved into a truncated context drops"),
    ("truncated-integral", "src/engines/taylor/singular/puiseux.rs",
     [("                    rem = add(&rem, &mul(&c1, &ctx.ranges[j as usize]))\n", "")],
     "the remainder of an integral's terms above a truncated cut-off"),
    ("truncated-monomial", "src/engines/taylor/singular/puiseux.rs",
     [("                rem: c * ctx.ranges[i as usize].clone(),", "                rem: c * I::zero(),")],
     "the remainder of a monomial above a truncated cut-off"),
    # issue #30: the verdicts, the admissible set as written, the band's pieces, Ulp division
    ("step-min-length", "src/engines/taylor/step.rs",
     [("    let h_min = h_min.max(MIN_STEP_ULPS * time_spacing(t0));\n", "")],
     "a Taylor step at least MIN_STEP_ULPS spacings of the doubles at t0 (steps of length 0)",
     ["--test", "verdicts", "digits_in_the_hunt_crossley_limit"]),
    ("horizon-pending", "src/engines/taylor/integrate.rs",
     [("            if let Some(p) = self.pending {\n                return Err(RigorError {",
       "            if let Some(p) = self.pending.filter(|_| false) {\n                return Err(RigorError {")],
     "a stretch pending at the horizon is undecided, not a proof of no separation",
     ["--test", "guards", "an_undecided_stretch_at_the_horizon"]),
    ("kink-now", "src/engines/taylor/integrate.rs",
     [("        let kink_now = w <= WIDE_SET\n", "        let kink_now = false && w <= WIDE_SET\n")],
     "a kink component a few ulps ahead crossed by a low-order step at once",
     ["--test", "guards", "a_kink_just_ahead"]),
    ("monotone-refute", "src/observables/band.rs",
     [("            } else if p.de.inf() > 0.0 {\n", "            } else if false {\n")],
     "prove monotone refutes the claim where inf de/dv0 > 0 (else it splits to the minimum width)",
     ["--test", "verdicts", "--test", "sets", "--", "a_false_monotonicity_claim", "monotonicity"]),
    ("band-no-slope", "src/observables/band.rs",
     [("        if lo < hi {\n", "        if false {\n")],
     "a range's piece without a slope is refused (not taken as de = 0)",
     ["--lib", "a_piece_without_a_slope"]),
    ("admissible-as-written", "src/models/params.rs",
     [("        check_decimals(kind, text)?;\n", "")],
     "the decimals checked against 𝓟 exactly (the enclosures only against what rounding keeps)",
     ["--test", "verdicts", "--", "decimals_inside_the_admissible_set"]),
    ("physical-as-written", "src/models/scaling.rs",
     [("        check_physical_decimals(kind, text)?;\n", "")],
     "the physical decimals checked exactly (β > 0, γ ∈ (−β, β), c > 0)",
     ["--test", "verdicts", "physical_parameters"]),
    ("digits-f64-floor", "src/observables/precision.rs",
     [("    let Ok((ts, e, pieces)) = f64_run else {", "    let Ok((ts, e, pieces)) = f64_run.and(Err(precise.clone())) else {")],
     "--digits never proves less than the f64-interval engine",
     ["--lib", "digits_fall_back"]),
    ("div-zero-dividend", "src/arith/interval/ulp.rs",
     [("    if dividend_zero || (c < 0.0 && d > 0.0)", "    if (c < 0.0 && d > 0.0)")],
     "0/y over a divisor reaching 0 is the whole line (it may be 0/0)",
     ["--lib", "ulp::tests"]),
    ("div-half-line-side", "src/arith/interval/ulp.rs",
     [("            lo: div_dir(a, d, false),\n            hi: f64::INFINITY,",
       "            lo: div_dir(a, d, true),\n            hi: f64::INFINITY,")],
     "the finite end of a half-line quotient rounded outward",
     ["--lib", "ulp::tests"]),
    # issue #30: the singular steps' inclusion T(S) ⊆ S, unbounded operands, the start step
    ("subset-remainder", "src/engines/taylor/singular/puiseux.rs",
     [("        if !self.rem.subset(&other.rem) {\n            return false;\n        }\n", "")],
     "T(S) ⊆ S: the remainder's inclusion (Gts::subset_of)",
     ["--lib", "singular"]),
    ("subset-only-in-self", "src/engines/taylor/singular/puiseux.rs",
     [("self.terms[i].1.subset(&zero) // a term only in self", "true // a term only in self")],
     "T(S) ⊆ S: a term only in T(S) needs its coefficient ⊆ [0, 0]",
     ["--lib", "singular"]),
    ("subset-only-in-other", "src/engines/taylor/singular/puiseux.rs",
     [("zero.subset(&other.terms[j].1) // a term only in other",
       "true // a term only in other")],
     "T(S) ⊆ S: a term only in S needs 0 in its coefficient",
     ["--lib", "singular"]),
    ("subset-in-both", "src/engines/taylor/singular/puiseux.rs",
     [("                self.terms[i].1.subset(&other.terms[j].1)\n", "                true\n")],
     "T(S) ⊆ S: a term in both needs C ⊆ C′",
     ["--lib", "singular"]),
    ("subset-context", "src/engines/taylor/singular/puiseux.rs",
     [("            (Some(a), Some(b)) => a.same_domain(b),", "            (Some(_), Some(_)) => true,")],
     "T(S) ⊆ S only for values on one basis and domain",
     ["--lib", "singular"]),
    ("same-domain-delta", "src/engines/taylor/singular/puiseux.rs",
     [("        self.delta == other.delta && same_basis", "        same_basis")],
     "one domain: the same δ (Ctx::same_domain)",
     ["--lib", "singular"]),
    ("same-domain-basis", "src/engines/taylor/singular/puiseux.rs",
     [("        self.delta == other.delta && same_basis", "        self.delta == other.delta")],
     "one basis: a key index is the same exponent (Ctx::same_domain)",
     ["--lib", "singular"]),
    ("unbounded-operands", "src/engines/taylor/singular/puiseux.rs",
     [("        a.is_bounded() && b.is_bounded()\n", "        true\n")],
     "a product or power of an unbounded generalized polynomial is unbounded (Gts::both_bounded)",
     ["--lib", "singular"]),
    ("unbounded-product", "src/engines/taylor/singular/puiseux.rs",
     [("        if !Self::both_bounded(self, o) {", "        if false {")],
     "… in a product (x·unbounded read as x·0)",
     ["--lib", "singular"]),
    ("positive-factor", "src/engines/taylor/singular/puiseux.rs",
     [("(f.1.range().lo() > 0.0).then_some((f.0, &f.1))", "Some((f.0, &f.1))")],
     "the start step's W_j > 0 before |s·u·W| = u·W (Gts::positive_factor)",
     ["--lib", "singular"]),
    ("start-image-bounded", "src/engines/taylor/singular/start.rs",
     [("        if !yj.is_bounded() {", "        if false {")],
     "the start step refuses an unbounded image of a component (start.rs, picard)",
     ["--lib", "singular"]),
    ("validate-inclusion", "src/engines/taylor/singular/mod.rs",
     [(".all(|(j, (a, b))| j == skip || a.subset_of(b))", ".all(|(j, (_a, _b))| j == skip || true)")],
     "a singular step's candidate S accepted only where T(S) ⊆ S (validate)",
     ["--lib", "singular"]),
    ("start-rate-bounded", "src/engines/taylor/singular/start.rs",
     [("    if !dt.is_bounded() {\n        return None;\n    }\n", "")],
     "the start step refuses an unbounded dt/du = σ/f_w (a rate reaching 0)",
     ["--lib", "singular"]),
    ("partial-form-time", "src/observables/sets.rs",
     [("    e_c + dv_du * du + dv_dt * dts\n", "    e_c + dv_du * du + dv_dt * dts * Interval::zero()\n")],
     "the partial form's time term [dV/dT]([T_s] − [T_s]) (sets.rs, partial_form)",
     ["--lib", "partial_form"]),
    ("piece-e-inside", "src/observables/band.rs",
     [("    pub fn e_at(&self, v0: Interval) -> Option<Interval> {\n        if v0.inf() < self.v0_lo || v0.sup() > self.v0_hi {",
       "    pub fn e_at(&self, v0: Interval) -> Option<Interval> {\n        if v0.inf() < self.v0_lo {")],
     "a band piece's e(v0) only for v0 inside the piece (e_at, the upper end)",
     ["--lib", "a_piece_answers_only_inside_it"]),
    ("piece-ts-inside", "src/observables/band.rs",
     [("    pub fn ts_at(&self, v0: Interval) -> Option<Interval> {\n        if v0.inf() < self.v0_lo || v0.sup() > self.v0_hi {",
       "    pub fn ts_at(&self, v0: Interval) -> Option<Interval> {\n        if v0.sup() > self.v0_hi {")],
     "a band piece's T_s(v0) only for v0 inside the piece (ts_at, the lower end)",
     ["--lib", "a_piece_answers_only_inside_it"]),
    ("piece-thickness-margin", "src/observables/band.rs",
     [("        w + 8.0 * f64::EPSILON * self.e.mag().max(1.0)\n", "        w\n")],
     "a piece's thickness covers the rounding of e(v0) at interior points",
     ["--lib", "a_piece_answers_only_inside_it"]),
    # claims over sets printed inward, proved results said as proved (2026-11-29, fourth session)
    ("identify-boxes-inward", "src/cli/identify.rs",
     [("    s != Status::Undecided\n}", "    let _ = s;\n    false\n}")],
     "feasible and infeasible boxes printed inward (a claim on every point of the box)",
     ["--test", "identify", "printed_boxes_claim_only_what_was_proved"]),
    ("certificate-ends-exact", "src/cli/compare.rs",
     [('format!("{}]", decimal::exact(r.hi))', 'format!("{}]", outward(r.hi, Rounding::Up))')],
     "a refuted range of a classical law's parameter printed with its exact ends",
     ["--test", "identify", "a_refutation_certificate_prints_its_ends_exactly"]),
    ("horizon-rounded-down", "src/cli/commands.rs",
     [("h = output::outward(horizon, bwcl::observables::decimal::Rounding::Down)", "h = num(horizon)")],
     "'T_s > T' with the horizon's double rounded down",
     ["--test", "cli", "no_separation_is_reported_not_a_number"]),
    ("digits-short-noted", "src/cli/precise.rs",
     [("                .or_else(|| short_of(&enc, digits)),", "                .or_else(|| short_of(&enc, 0)),")],
     "--digits says where an enclosure determines fewer digits than asked",
     ["--test", "cli", "digits_say_what_they_proved"]),
    ("digits-no-separation-proved", "src/cli/precise.rs",
     [("        Err(e) if e.no_separation() => Outcome {", "        Err(e) if e.no_separation() && false => Outcome {")],
     "--digits reports no separation before the horizon as proved (exit 0)",
     ["--test", "cli", "digits_say_what_they_proved"]),

    ("identify-undecided-share-up", "src/identify/paving.rs",
     [("round(&v[1], false), round(&v[2], true)]", "round(&v[1], false), round(&v[2], false)]")],
     "identify's undecided share summed exactly and rounded up (the proved shares down)",
     ["--test", "identify", "printed_boxes_claim_only_what_was_proved"]),

    ("v0-range-inward", "src/cli/output.rs",
     [("    [outward(lo, Rounding::Up), outward(hi, Rounding::Down)]", "    [outward(lo, Rounding::Down), outward(hi, Rounding::Up)]")],
     "a range of v0 a result holds for printed inward (table, note, CSV, JSON)",
     ["--test", "cli", "a_range_of_v0_is_printed_inward"]),

]


def run(name, path, edits, what, tests=None):
    tmp = tempfile.mkdtemp(prefix=f"bwcl-guard-{name}-")
    try:
        for entry in ["Cargo.toml", "Cargo.lock", "src", "tests", "benches", "proofs",
                      "paper_repro", ".cargo", "bindings"]:
            src = os.path.join(ROOT, entry)
            if os.path.isdir(src):
                shutil.copytree(src, os.path.join(tmp, entry))
            elif os.path.exists(src):
                shutil.copy(src, tmp)
        f = os.path.join(tmp, path)
        text = open(f).read()
        for old, new in edits:
            if text.count(old) != 1:
                return f"{name}: ERROR the guard's text occurs {text.count(old)} times in {path}"
            text = text.replace(old, new)
        open(f, "w").write(text)
        env = dict(os.environ)
        # a target dir of its own: the mutated copies build artifacts under the same names as the
        # work tree (cargo hashes paths relative to the workspace), and a shared dir would leave
        # a mutant where a later ordinary build believes it is up to date
        env["CARGO_TARGET_DIR"] = os.path.join(ROOT, "target", "guard-mutants")
        t0 = time.time()
        out = ""
        for args in commands(tests or TESTS):
            p = subprocess.run(["cargo", "test", "--release", "--no-fail-fast", *args],
                               cwd=tmp, env=env, capture_output=True, text=True)
            out += p.stdout + p.stderr
        failed = sorted(set(re.findall(r"^test (\S+) \.\.\. FAILED", out, re.M)))
        dt = time.time() - t0
        if "could not compile" in out:
            return f"{name}: ERROR the mutant does not compile"
        if failed:
            return f"{name}: KILLED in {dt:.0f} s by {', '.join(failed)}  ({what})"
        return f"{name}: SURVIVED ({what})"
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def check():
    """The guards' texts occur exactly once each in their files (no build, no test): a
    guard whose code moved is found at once, not when its mutant is next run. Returns the
    problems, one line each."""
    problems = []
    names = [g[0] for g in GUARDS]
    for n in sorted(set(names)):
        if names.count(n) > 1:
            problems.append(f"{n}: the name is used {names.count(n)} times")
    for name, path, edits, *_ in GUARDS:
        text = open(os.path.join(ROOT, path)).read()
        for old, new in edits:
            if text.count(old) != 1:
                problems.append(f"{name}: the guard's text occurs {text.count(old)} times in {path}")
            if old == new:
                problems.append(f"{name}: the mutation changes nothing")
    return problems


def main():
    if sys.argv[1:] == ["--check"]:
        problems = check()
        for p in problems:
            print(p)
        print(f"{len(GUARDS)} guards, {len(problems)} problem(s)")
        sys.exit(1 if problems else 0)
    names = sys.argv[1:]
    results = [run(*g) for g in GUARDS if not names or g[0] in names]
    for r in results:
        print(r)
    sys.exit(1 if any("SURVIVED" in r or "ERROR" in r for r in results) else 0)


if __name__ == "__main__":
    main()
