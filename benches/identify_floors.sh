#!/usr/bin/env bash
# The floors of issue #31 for `bwcl identify` (not a timed test: run by hand, quote the load).
#   bash benches/identify_floors.sh [2d|6d|1d] [time limit s]
# 2d: σ_b ∈ [0.001, 0.1] × κ ∈ [0.4, 0.8], the others at the generating values, the 20-point DSS
#     data, E = 0.02, resolution 1/128 (floor: ≤ 60 s, undecided ≤ 5 %).
# 6d: all six free over the issue's box, E = 0.02 (floor: hull within 2× of the sampled hull in
#     ≤ 15 min); --sample 20000 prints the hull of f64-feasible points and the ratio of widths.
# Cores: RAYON_NUM_THREADS=1 bash benches/identify_floors.sh 2d (the paving on one thread).
# 1d: σ_b ∈ [0.001, 0.02] alone, resolution 1/64 (a reference point).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin bwcl
B=target/release/bwcl
D=paper_repro/data/synthetic_dss.csv
P=1.43,-1.42,0.632,0.00715,1.31,1.27
what="${1:-2d}"; limit="${2:-300}"
uptime
case "$what" in
  1d) args=(--bounds sigma_b=0.001..0.02 --resolution 64) ;;
  2d) args=(--bounds sigma_b=0.001..0.1,kappa=0.4..0.8 --resolution 128) ;;
  6d) args=(--bounds B_b=0.8..1.6,Gamma_b=-1.6..1,kappa=0.5..0.7,sigma_b=0.004..0.06,n=1.1..1.4,p=1.1..1.4 --resolution 16
          --sample 20000) ;;
  *) echo "usage: $0 [1d|2d|6d] [seconds]" >&2; exit 2 ;;
esac
/usr/bin/time -f "%e s wall, %U s user" "$B" identify --model shc --data "$D" --error 0.02 \
    --base="$P" "${args[@]}" --time-limit "$limit" || true
uptime
