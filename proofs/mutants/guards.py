#!/usr/bin/env python3
"""Removes each soundness guard of the rigorous engine alone and runs the tests that must see it.

Usage (from the repository root; a clean work tree): python3 proofs/mutants/guards.py [NAME...]
Each mutation is applied to a copy of the tree in a temporary directory (the work tree is never
changed), `cargo test --release` runs the named test targets there, and a line per guard says
which tests failed. A guard whose removal leaves every test green is reported as SURVIVED and the
script exits 1. The results are in proofs/MUTANTS.md.
"""
import os, re, shutil, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# the test targets that check enclosures (those present in this tree)
TESTS = ["--lib"] + [a for t in ["guards", "rigorous", "references", "outward"]
                     if os.path.exists(os.path.join(ROOT, "tests", t + ".rs"))
                     for a in ("--test", t)]

# (name, file, [(exact text, replacement)], what it removes)
GUARDS = [
    ("apriori", "src/engines/taylor/step.rs",
     [("            if subset(&ynew, &y) {", "            if true {")],
     "the a-priori inclusion test of the Taylor step"),
    ("picard", "src/engines/taylor/step.rs",
     [("if ynew.iter().all(|c| c.is_common_interval()) && subset(&ynew, &y) {",
       "if ynew.iter().all(|c| c.is_common_interval()) {")],
     "the Picard inclusion test of the low-order step"),
    ("q-inverse", "src/engines/taylor/lohner.rs", [("pt(r[i][j]) + ball", "pt(r[i][j])")],
     "the error term of the enclosure of Q⁻¹ (Lohner)"),
    ("q-inverse-1+e", "src/engines/taylor/lohner.rs",
     [("e_norm / (ONE - e_norm) * r_norm", "e_norm / (ONE + e_norm) * r_norm")],
     "the Neumann factor 1/(1 − e) of the Q⁻¹ error term, as 1/(1 + e)"),
    ("q-inverse-e(1-e)", "src/engines/taylor/lohner.rs",
     [("e_norm / (ONE - e_norm) * r_norm", "e_norm * (ONE - e_norm) * r_norm")],
     "the Neumann factor 1/(1 − e) of the Q⁻¹ error term, as (1 − e)"),
    ("newton", "src/engines/taylor/newton.rs",
     [("        if n.interior(t) {", "        if true {")],
     "interval Newton's existence proof N(T) ⊆ int T"),
    ("ts-midpoint", "src/engines/taylor/event.rs",
     [("Some(Some(ts)) => return self.found(ts),",
       "Some(Some(ts)) => return self.found(point(ts.mid())),")],
     "the T_s enclosure (collapsed to its midpoint)"),
    ("event-which-zero", "src/engines/taylor/event.rs",
     [("        let attempt = if v.inf() > 0.0 {", "        let attempt = if v.inf() < 0.0 {")],
     "the separation event's condition V > 0 for a zero of F (a zero of F while V < 0 taken)"),
    ("kink-side", "src/engines/taylor/step.rs",
     [("        let sd = if side[i] > 0 { d } else { -d };", "        let sd = d;")],
     "the kink check's side (the rate of x_i instead of s·x_i)"),
    ("kink-old", "src/engines/taylor/step.rs",
     [("        if sd.inf() > 0.0 {", "        if (side[i] as f64) * d.inf() > 0.0 {"),
      ("        if sd.sup() >= 0.0 {", "        if (side[i] as f64) * d.sup() >= 0.0 {")],
     "the kink check as it was before issue #12 (right for s = +1 only)"),
    ("span", "src/engines/taylor/step.rs",
     [("    (t1, span(super::flow::tau(point(t1), t0).sup()))",
       "    (t1, span((t1 - t0).max(h)))")],
     "the validated span's upper bound of t1 − t0"),
    ("integral-exponent", "src/engines/taylor/tape.rs",
     [("&& consts[c].encloses(&q1)", "")],
     "the check q′ ⊇ q − 1 before a power is taken as the integral of a product"),
    ("integral-mpfr-ends", "src/engines/taylor/tape.rs",
     [("&& consts[c].encloses(&q1)", "&& consts[c].lo() <= q1.lo() && q1.hi() <= consts[c].hi()")],
     "the check q′ ⊇ q − 1 on the exponents' own ends (on their f64 bounds instead)"),
    ("integral-twin", "src/engines/taylor/tape.rs",
     [(" || read_by_twin(s)", "")],
     "no integral for a power whose series a Twin reads"),
    ("sign-copy-parameter", "src/engines/taylor/tape.rs",
     [("        Op::Abs(_) if tconst[n] => None,\n", "")],
     "no sign copy through |·| of a parameter (whose sign a jet never sets)"),
    ("integral-derivative", "src/engines/taylor/tape.rs",
     [("                    d == field[v]\n", "                    true\n")],
     "the check that the product's other factor is the field's ẋ_v"),
    ("integral-factor", "src/engines/taylor/tape.rs",
     [("c[m * k1 + k - 1].mul_constant(qv).div_int(k as i64)",
       "c[m * k1 + k - 1].div_int(k as i64)")],
     "the factor q of an integral power's coefficients u_k = q·m_{k−1}/k"),
    ("sign-copy", "src/engines/taylor/tape.rs",
     [(".map(|&n| if n == NO_SIGN { 1 } else { sign[n] })",
       ".map(|&n| if n == NO_SIGN { 1 } else { 1 })")],
     "the sign of a product copied from an earlier one"),
    ("merge-sign", "src/engines/taylor/tape.rs",
     [("let merged = if sign[m] < 0 {", "let merged = if sign[m] > 0 {")],
     "the sign s of a merged pair's constant c_j + s·c_j′ (the copy's sign, reversed)"),
    ("merge-always-sum", "src/engines/taylor/tape.rs",
     [("let merged = if sign[m] < 0 {", "let merged = if false {")],
     "a merged pair's constant always c_j + c_j′ (the copy's sign ignored)"),
    ("sign-copy-exponent", "src/engines/taylor/tape.rs",
     [("!same_exponent(qi, qj)", "false")],
     "the check that a sign copy's two powers have the same exponent"),
    ("sign-copy-holder", "src/engines/taylor/tape.rs",
     [("            let holder = if hj {", "            let holder = if true {")],
     "the choice of the power node that holds the sign of w (an entire power holds none)"),
    ("merge-origin", "src/engines/taylor/tape.rs",
     [("nodes.iter().all(|&n| n == NO_SIGN || !ambiguous[n])",
       "nodes.iter().all(|&n| n == NO_SIGN || true)")],
     "no merged pair through a node that stands for operations of different origin"),
    ("merge-exponent-origin", "src/engines/taylor/tape.rs",
     [("&& (c == d || (thin_point(c) && thin_point(d) && same_const(c, d)))",
       "&& (c == d || same_const(c, d))")],
     "a merged pair's exponents one recorded constant (or one exact point), not equal enclosures"),
    ("const-exact", "src/engines/taylor/tape.rs",
     [("c == d || (consts[c].encloses(&consts[d]) && consts[d].encloses(&consts[c]))",
       "c == d || cbits(c) == cbits(d)")],
     "constants compared on the type's own ends (MPFR), not their f64 bounds, before operations are one"),
    ("truncated-move", "src/engines/taylor/singular/puiseux.rs",
     [("                rem = add(&rem, &mul(c, &ctx.ranges[*i as usize]));\n", "")],
     "the remainder of the terms a value moved into a truncated context drops"),
    ("truncated-integral", "src/engines/taylor/singular/puiseux.rs",
     [("                    rem = add(&rem, &mul(&c1, &ctx.ranges[j as usize]))\n", "")],
     "the remainder of an integral's terms above a truncated cut-off"),
    ("truncated-monomial", "src/engines/taylor/singular/puiseux.rs",
     [("                rem: c * ctx.ranges[i as usize].clone(),", "                rem: c * I::zero(),")],
     "the remainder of a monomial above a truncated cut-off"),
    ("subset-remainder", "src/engines/taylor/singular/puiseux.rs",
     [("        if !self.rem.subset(&other.rem) {\n            return false;\n        }\n", "")],
     "T(S) ⊆ S: the remainder's inclusion (Gts::subset_of)"),
    ("subset-only-in-self", "src/engines/taylor/singular/puiseux.rs",
     [("self.terms[i].1.subset(&zero) // a term only in self", "true // a term only in self")],
     "T(S) ⊆ S: a term only in T(S) needs its coefficient ⊆ [0, 0]"),
    ("subset-only-in-other", "src/engines/taylor/singular/puiseux.rs",
     [("zero.subset(&other.terms[j].1) // a term only in other",
       "true // a term only in other")],
     "T(S) ⊆ S: a term only in S needs 0 in its coefficient"),
    ("subset-in-both", "src/engines/taylor/singular/puiseux.rs",
     [("                self.terms[i].1.subset(&other.terms[j].1)\n", "                true\n")],
     "T(S) ⊆ S: a term in both needs C ⊆ C′"),
    ("subset-context", "src/engines/taylor/singular/puiseux.rs",
     [("            (Some(a), Some(b)) => a.same_domain(b),", "            (Some(_), Some(_)) => true,")],
     "T(S) ⊆ S only for values on one basis and domain"),
    ("same-domain-delta", "src/engines/taylor/singular/puiseux.rs",
     [("        self.delta == other.delta && same_basis", "        same_basis")],
     "one domain: the same δ (Ctx::same_domain)"),
    ("same-domain-basis", "src/engines/taylor/singular/puiseux.rs",
     [("        self.delta == other.delta && same_basis", "        self.delta == other.delta")],
     "one basis: a key index is the same exponent (Ctx::same_domain)"),
    ("unbounded-operands", "src/engines/taylor/singular/puiseux.rs",
     [("        a.is_bounded() && b.is_bounded()\n", "        true\n")],
     "a product or power of an unbounded generalized polynomial is unbounded (Gts::both_bounded)"),
    ("unbounded-product", "src/engines/taylor/singular/puiseux.rs",
     [("        if !Self::both_bounded(self, o) {", "        if false {")],
     "… in a product (x·unbounded read as x·0)"),
    ("positive-factor", "src/engines/taylor/singular/puiseux.rs",
     [("(f.1.range().lo() > 0.0).then_some((f.0, &f.1))", "Some((f.0, &f.1))")],
     "the start step's W_j > 0 before |s·u·W| = u·W (Gts::positive_factor)"),
    ("start-image-bounded", "src/engines/taylor/singular/start.rs",
     [("        if !yj.is_bounded() {", "        if false {")],
     "the start step refuses an unbounded image of a component (start.rs, picard)"),
]


def run(name, path, edits, what):
    tmp = tempfile.mkdtemp(prefix=f"bwcl-guard-{name}-")
    try:
        for entry in ["Cargo.toml", "Cargo.lock", "src", "tests", "benches", "proofs",
                      "paper_repro", ".cargo"]:
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
        p = subprocess.run(["cargo", "test", "--release", "--no-fail-fast", *TESTS],
                           cwd=tmp, env=env, capture_output=True, text=True)
        out = p.stdout + p.stderr
        failed = sorted(set(re.findall(r"^test (\S+) \.\.\. FAILED", out, re.M)))
        dt = time.time() - t0
        if "could not compile" in out:
            return f"{name}: ERROR the mutant does not compile"
        if failed:
            return f"{name}: KILLED in {dt:.0f} s by {', '.join(failed)}  ({what})"
        return f"{name}: SURVIVED ({what})"
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main():
    names = sys.argv[1:]
    results = [run(*g) for g in GUARDS if not names or g[0] in names]
    for r in results:
        print(r)
    sys.exit(1 if any("SURVIVED" in r or "ERROR" in r for r in results) else 0)


if __name__ == "__main__":
    main()
