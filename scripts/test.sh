#!/usr/bin/env bash
# All the project's tests: the README's test command, run by CI (.ci/run).
# Formatting, lints, docs and the Rust tests (the C interface's test program among them), then the FMI
# unit with FMPy (scripts/test_fmi.sh), the MATLAB/Octave MEX gateway (scripts/test_octave.sh), the
# Slurm route (scripts/test_slurm.sh) beside the Python package (scripts/test_python.sh). Each stage line
# gives the time since the start.
set -euo pipefail
cd "$(dirname "$0")/.."
stage() { echo "== [$((SECONDS / 60)) min $((SECONDS % 60)) s] $*"; }
# Octave (about 1 min of apt-get on a fresh machine) installs in the background while Rust compiles;
# the Octave stage waits for it (and installs itself if this failed).
mkdir -p target
scripts/test_octave.sh --install-only >target/octave-install.log 2>&1 &
octave_install=$!
stage "cargo fmt --check"
cargo fmt --all -- --check
stage "cargo clippy"
cargo clippy --all-targets -- -D warnings
stage "cargo doc (broken links are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet
stage "cargo test"
cargo test --workspace
wait "$octave_install" || { echo "background Octave install failed:"; tail -5 target/octave-install.log; }
stage "FMI unit, checked with FMPy (scripts/test_fmi.sh, reusing the cargo test build)"
FMU_PROFILE=test scripts/test_fmi.sh
stage "MATLAB/Octave MEX gateway and rotor example (scripts/test_octave.sh; installs Octave if missing)"
scripts/test_octave.sh
# The Slurm stage mostly waits for its local cluster's jobs, the Python stage mostly compiles: they
# run side by side (the Slurm stage on the binary cargo test built, so it takes no cargo lock), its
# output printed when both are done.
stage "Slurm route (scripts/test_slurm.sh; SKIPPED without root or Debian's slurm-wlm/munge), in the background"
EHL_BEARING_BIN="$PWD/target/debug/ehl-bearing" scripts/test_slurm.sh >target/slurm-stage.log 2>&1 &
slurm=$!
stage "python package (scripts/test_python.sh)"
if ! scripts/test_python.sh; then
    wait "$slurm" || true
    exit 1
fi
stage "Slurm route: its output"
slurm_rc=0
wait "$slurm" || slurm_rc=$?
cat target/slurm-stage.log
if [ "$slurm_rc" != 0 ]; then
    echo "FAILED: Slurm stage (exit $slurm_rc)"
    exit 1
fi
stage "all stages passed"
