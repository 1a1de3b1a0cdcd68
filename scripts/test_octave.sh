#!/usr/bin/env bash
# The MATLAB/Octave route (docs/matlab.md), from a clean clone: installs GNU Octave with its MEX
# headers (Debian's octave and liboctave-dev) if mkoctfile is missing, builds the C library
# (crates/ehl-bearing-c) with its Rust reference programs, builds the MEX gateway
# with `mkoctfile --mex`, and runs in Octave: the interface tests against the Rust library's
# numbers and error paths (matlab/tests/test_ehl_mex.m), the Jeffcott rotor example against the
# Rust rotor model within 0.5 % (matlab/tests/test_jeffcott.m), and, with EHL_BENCH=1, the
# per-call timing (matlab/tests/bench_ehl_mex.m). Each stage line gives the time since the start.
# The library builds with cargo's `test` profile by default (EHL_PROFILE=release for another):
# the same optimization as release in this workspace (opt-level 3), and after
# `cargo test --workspace` (scripts/test.sh) nothing of it is left to compile.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
stage() { echo "== octave [$((SECONDS / 60)) min $((SECONDS % 60)) s] $*"; }
if ! command -v mkoctfile >/dev/null || ! command -v octave >/dev/null; then
    stage "apt-get install octave liboctave-dev (mkoctfile missing)"
    sudo=""
    if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
    t0=$SECONDS
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        octave liboctave-dev >/dev/null
    echo "apt-get install took $((SECONDS - t0)) s"
fi
# --install-only: scripts/test.sh starts the install in the background while Rust compiles.
if [ "${1:-}" = "--install-only" ]; then exit 0; fi
profile=${EHL_PROFILE:-test}
case "$profile" in test | dev) dir=debug ;; *) dir=$profile ;; esac
if [ "$profile" = test ]; then
    # The feature set of `cargo test --workspace` (dev-dependencies included): after the cargo
    # test stage of scripts/test.sh this compiles at most the C library's cdylib
    # (`-p ehl-bearing-c` alone resolves other features and rebuilds the library: minutes).
    stage "cargo build --profile test --workspace (the cargo test feature set)"
    cargo build --profile test --quiet --workspace --lib --bins --tests --examples
else
    stage "cargo build --profile $profile -p ehl-bearing-c (library and reference programs)"
    cargo build --profile "$profile" -p ehl-bearing-c --lib --examples
fi
lib="$CARGO_TARGET_DIR/$dir"
work="$CARGO_TARGET_DIR/octave"
mkdir -p "$work"
stage "Rust reference numbers and the Jeffcott rotor by the Rust rotor model"
"$lib/examples/write_reference" "$work/reference.txt"
"$lib/examples/jeffcott_reference" > "$work/jeffcott_rust.json"
matlab="$root/crates/ehl-bearing-c/matlab"
octave_run() {
    # Octave 7 prints "ignoring const execution_exception& while preparing to exit" at exit
    # without a display; it does not change the exit status.
    octave --no-gui --no-window-system --norc --quiet --eval \
        "addpath('$matlab'); addpath('$matlab/tests'); addpath('$matlab/examples'); $1" \
        2> >(grep -v "ignoring const execution_exception" >&2)
}
stage "mkoctfile --mex ehl_mex.c ($(mkoctfile --version 2>&1 | head -1))"
octave_run "ehl_build_mex('$lib')"
stage "MEX interface tests (matlab/tests/test_ehl_mex.m)"
octave_run "test_ehl_mex('$root', '$work/reference.txt')"
stage "Jeffcott rotor example against the Rust rotor model (matlab/tests/test_jeffcott.m)"
octave_run "test_jeffcott('$root', '$work/jeffcott_rust.json')"
if [ "${EHL_BENCH:-0}" = 1 ]; then
    stage "per-call timing (matlab/tests/bench_ehl_mex.m)"
    octave_run "bench_ehl_mex('$root', ${EHL_BENCH_CALLS:-20000})"
fi
stage "octave stages passed"
