#!/bin/sh
# cargo-mutants on src/arith alone (issue #12, proofs/MUTANTS.md §2).
#
# src/arith depends on nothing else in the crate, so its files and their unit tests form a
# crate of their own: a mutant there rebuilds in 2-5 s instead of 15-45 s for the whole crate
# with every test target. This copies them (verbatim, so the mutants' names and lines are the
# crate's) into a temporary crate and runs `cargo mutants ARGS --profile mutants` on its unit
# tests (`--lib`: every test of src/arith). A mutant this misses is then rerun on the whole
# crate, or killed by a new test; one it catches is caught by the crate's `--lib` tests too.
#
#   proofs/mutants/arith.sh -f src/arith/ulp.rs --re '…' --timeout 30 -j 1 -o /tmp/out
# (-o: an absolute directory; the temporary crate is removed at the end)
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d "${TMPDIR:-/tmp}/bwcl-arith.XXXXXX")
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/src" "$dir/.cargo"
cp -r "$root/src/arith" "$dir/src/"
cp "$root/Cargo.lock" "$dir/"
cp "$root/.cargo/config.toml" "$dir/.cargo/"
printf '//! src/arith of bwcl alone (mutation testing).\npub mod arith;\n' >"$dir/src/lib.rs"
# the versions and features of the crate's own manifest
inari=$(grep '^inari' "$root/Cargo.toml")
rug=$(grep '^rug' "$root/Cargo.toml")
cat >"$dir/Cargo.toml" <<TOML
[package]
name = "bwcl"
version = "0.1.0"
edition = "2024"

[dependencies]
$inari
$rug

[profile.test]
opt-level = 2

[profile.mutants]
inherits = "test"
opt-level = 1
debug = 0
TOML
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}/arith-only"
cd "$dir"
cargo mutants "$@" --profile mutants --cargo-arg=--lib
