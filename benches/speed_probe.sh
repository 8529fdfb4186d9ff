#!/usr/bin/env bash
# This machine's speed, to set beside a wall time (the host's speed drifts by up to 1.7x):
# 98 proved CoRs on one thread (SHC DSS and Maxwell DSA of Table 1 at v0 = 0.1, 0.2, ..., 4.9),
# three rounds with one `bwcl` program; prints each round's seconds and the load average.
#
#   bash benches/speed_probe.sh [path/to/bwcl]    # default: target/release/bwcl
set -euo pipefail
cd "$(dirname "$0")/.."
BWCL="${1:-${CARGO_TARGET_DIR:-target}/release/bwcl}"
V=$(python3 -c "print(','.join(f'{0.1 * i:.1f}' for i in range(1, 50)))")
rounds=()
for _ in 1 2 3; do
    s=$(date +%s.%N)
    RAYON_NUM_THREADS=1 "$BWCL" cor --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 \
        --v0 "$V" --rigorous >/dev/null
    RAYON_NUM_THREADS=1 "$BWCL" cor --model maxwell --base 0.44,-0.418,0.113,0.00785,1.27,3.14 \
        --v0 "$V" --rigorous >/dev/null
    e=$(date +%s.%N)
    rounds+=("$(python3 -c "print(f'{$e - $s:.3f}')")")
done
echo "speed probe: ${rounds[*]} s (median of the three is the figure; load $(cut -d' ' -f1-3 /proc/loadavg))"
