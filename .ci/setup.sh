#!/usr/bin/env bash
# Machine setup for a fresh machine. Prints the cargo flags to build with on stdout (nothing, or
# `--no-default-features --features plots` for the fallback below); everything else goes to
# stderr. Use: FLAGS=$(bash .ci/setup.sh).
#
# GMP and MPFR (for rug): the system's libraries (Debian 12: libgmp-dev 6.2, libmpfr-dev 4.2),
# installed here when missing; the default cargo feature `system-gmp` links them. Where they
# cannot be installed (no apt, no root), or with BWCL_BUILD_GMP=1, the fallback: cargo builds
# GMP and MPFR from source (about 3 min more; needs m4), selected by leaving out the default
# feature `system-gmp`.
# The plots of paper_repro lay out text with a TrueType font (DejaVu).
set -euo pipefail
command -v cargo >/dev/null || { echo "setup: cargo not found" >&2; exit 1; }
if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
have_header() { # name: the header is on the compiler's default include path
  printf '#include <%s>\n' "$1" | cc -E -x c - >/dev/null 2>&1
}
install() { # packages…
  echo "setup: installing $*" >&2
  { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "$@"; } >/dev/null 2>&1
}
need=()
[ -e /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || need+=(fonts-dejavu-core)
system_gmp=1
if [ "${BWCL_BUILD_GMP:-0}" = 1 ]; then
  system_gmp=0
elif ! { have_header gmp.h && have_header mpfr.h; }; then
  need+=(libgmp-dev libmpfr-dev)
fi
if [ ${#need[@]} -gt 0 ]; then
  install "${need[@]}" || echo "setup: could not install ${need[*]}" >&2
fi
if [ "$system_gmp" = 1 ] && ! { have_header gmp.h && have_header mpfr.h; }; then
  echo "setup: no system GMP/MPFR: building them from source (fallback)" >&2
  system_gmp=0
fi
if [ "$system_gmp" = 0 ]; then
  command -v m4 >/dev/null 2>&1 || install m4 || echo "setup: could not install m4" >&2
  echo "--no-default-features --features plots"
fi
