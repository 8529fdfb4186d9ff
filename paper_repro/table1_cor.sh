#!/usr/bin/env bash
# The main job: the CoR of the paper's four Table 1 base sets at the paper's speed grid, first by
# the f64 DOP853 engine (the paper's settings: rtol 1e-10, atol 1e-12, max_step 1e-2), then as
# proved enclosures by the rigorous interval Taylor engine.
set -euo pipefail
cd "$(dirname "$0")/.."
FLAGS=$(bash .ci/setup.sh)
# only the bwcl program, without the plots' dependencies: the system's GMP/MPFR unless the
# setup fell back to building them from source
if [ -z "$FLAGS" ]; then FEATURES=(--features system-gmp); else FEATURES=(); fi
cargo build --release --quiet --no-default-features "${FEATURES[@]}" --bin bwcl
BWCL="${CARGO_TARGET_DIR:-target}/release/bwcl"
V0="0.1,0.5,1,2,3,4,5"
run() { # model name base
  echo "== $2: $1 --base $3"
  "$BWCL" cor --model "$1" --base "$3" --v0 "$V0"
  echo "-- proved enclosures"
  "$BWCL" cor --model "$1" --base "$3" --v0 "$V0" --rigorous
  echo
}
run shc     "NDBWSHCCM, DSS" 1.43,-1.42,0.632,0.00715,1.31,1.27
run shc     "NDBWSHCCM, DSA" 0.63,-0.611,0.188,0.00594,1,2.02
run maxwell "NDBWMCM, DSS"   0.655,-0.64,0.519,0.0118,1.94,2.28
run maxwell "NDBWMCM, DSA"   0.44,-0.418,0.113,0.00785,1.27,3.14
