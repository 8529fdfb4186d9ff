#!/usr/bin/env bash
# Machine setup for a fresh machine: rug builds GMP and MPFR from source, which needs m4; the
# plots of paper_repro lay out text with a TrueType font (DejaVu).
set -euo pipefail
need=()
command -v m4 >/dev/null 2>&1 || need+=(m4)
[ -e /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || need+=(fonts-dejavu-core)
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]}" >&2
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi
command -v cargo >/dev/null || { echo "setup: cargo not found" >&2; exit 1; }
