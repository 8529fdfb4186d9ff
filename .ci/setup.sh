#!/usr/bin/env bash
# Machine setup for a fresh machine: rug builds GMP and MPFR from source, which needs m4.
set -euo pipefail
if ! command -v m4 >/dev/null 2>&1; then
  echo "setup: installing m4 (needed to build GMP/MPFR from source)" >&2
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq m4 >/dev/null
fi
command -v cargo >/dev/null || { echo "setup: cargo not found" >&2; exit 1; }
