#!/usr/bin/env bash
# All the project's tests: the README's test command, run by CI (.ci/run).
# Formatting, lints, docs and the Rust tests (the C interface's test program among them), then the FMI
# unit with FMPy (scripts/test_fmi.sh), the MATLAB/Octave MEX gateway (scripts/test_octave.sh), the
# Slurm route (scripts/test_slurm.sh) and the Python package (scripts/test_python.sh). Each stage line
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
stage "Slurm route (scripts/test_slurm.sh; SKIPPED without root or Debian's slurm-wlm/munge)"
scripts/test_slurm.sh
stage "python package (scripts/test_python.sh)"
scripts/test_python.sh
stage "all stages passed"
