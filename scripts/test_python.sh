#!/usr/bin/env bash
# The Python package's stage of scripts/test.sh: format and lint its Rust crate, build the wheel
# into a virtual environment (target/py-venv) with the `ross` and `test` extras, lint the Python
# code (ruff check, ruff format --check) and run pytest (fast tests; the slow ones:
# `target/py-venv/bin/python -m pytest crates/ehl-bearing-py/tests -m slow`).
# The wheel builds with CARGO_TARGET_DIR=target, sharing the workspace's compiled dependencies.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
crate=crates/ehl-bearing-py
export CARGO_TARGET_DIR="$root/target"
PYTHON=${PYTHON:-python3}
echo "== python: cargo fmt --check ($crate)"
cargo fmt --manifest-path "$crate/Cargo.toml" -- --check
echo "== python: cargo clippy ($crate)"
cargo clippy --manifest-path "$crate/Cargo.toml" --all-targets -- -D warnings
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    echo "== python: venv $venv"
    if ! "$PYTHON" -m venv "$venv" 2>/dev/null; then
        # Debian's python3 makes virtual environments only with its python3-venv package.
        rm -rf "$venv"
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
            echo "== python: apt-get install python3-venv (python3 -m venv needs it on Debian)"
            apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv >/dev/null
        else
            echo "python3 -m venv failed: install Debian's python3-venv (sudo apt-get install python3-venv)" >&2
        fi
        "$PYTHON" -m venv "$venv"
    fi
    "$venv/bin/python" -m pip install --quiet --upgrade pip
fi
echo "== python: pip install ./$crate[ross,test]"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./$crate[ross,test]"
echo "== python: ruff"
py_sources=("$crate/python" "$crate/tests" examples/python)
"$venv/bin/ruff" check --config "$crate/pyproject.toml" "${py_sources[@]}"
"$venv/bin/ruff" format --check --config "$crate/pyproject.toml" "${py_sources[@]}"
echo "== python: pytest"
cd "$crate"
MPLBACKEND=Agg "$root/$venv/bin/python" -m pytest -q -p no:cacheprovider tests
