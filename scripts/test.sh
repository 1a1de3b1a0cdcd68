#!/usr/bin/env bash
# All the project's tests: the README's test command, run by CI (.ci/run).
# Formatting, lints and the Rust tests, then the Python package (scripts/test_python.sh); further stages are added below as they land.
set -euo pipefail
cd "$(dirname "$0")/.."
echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --all-targets -- -D warnings
echo "== cargo doc (broken links are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet
echo "== cargo test"
cargo test --workspace
echo "== Slurm route (scripts/test_slurm.sh; SKIPPED without root or Debian's slurm-wlm/munge)"
scripts/test_slurm.sh
echo "== python package (scripts/test_python.sh)"
scripts/test_python.sh
