#!/usr/bin/env bash
# The FMU route (docs/fmi.md), checked with FMPy: builds the seed bearing's FMU three ways (dry
# Hertz; fitted laws with damping terms from a harmonic characterization; a study's trends), runs
# `fmpy validate` on each, simulates each with FMPy driving its 13 inputs from a table
# (displacements and rates oscillating about the equilibrium, speed ramp, turning cage), and
# compares all 61 outputs at every time point with the library's numbers for the same inputs
# (`ehl-bearing-fmu reference`): bit-identical with warm_start = false, within the solvers'
# tolerances with warm starts. Then times calls through FMPy's API and through the C functions.
# Makes its own virtual environment (target/fmi-venv) with a pinned FMPy from PyPI.
# Run time on the 2-core machine: 4.5-6 min from a clean clone (pip download and the release
# build, the two cores shared with other builds), 15-35 s again; with FMU_PROFILE=test after
# `cargo test --workspace`, the build takes seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
FMPY_VERSION=0.3.32
PYTHON=${PYTHON:-python3}
stage() { echo "== [$SECONDS s] fmi: $*"; }
venv=target/fmi-venv
if [ ! -x "$venv/bin/python" ]; then
    stage "venv $venv"
    if ! "$PYTHON" -m venv "$venv" 2>/dev/null; then
        # Debian's python3 makes virtual environments only with its python3-venv package.
        rm -rf "$venv"
        if command -v apt-get >/dev/null; then
            sudo=""
            [ "$(id -u)" = 0 ] || sudo=sudo
            echo "== fmi: apt-get install python3-venv (python3 -m venv needs it on Debian)"
            $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq python3-venv >/dev/null
        fi
        "$PYTHON" -m venv "$venv"
    fi
fi
if ! "$venv/bin/python" -c "import fmpy, sys; sys.exit(fmpy.__version__ != '$FMPY_VERSION')" 2>/dev/null; then
    stage "pip install fmpy==$FMPY_VERSION"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "fmpy==$FMPY_VERSION"
fi
# FMU_PROFILE=test reuses the optimized build of `cargo test --workspace` (seconds instead of the
# release build's minutes); the unit and the reference helper always share the profile.
export FMU_PROFILE=${FMU_PROFILE:-release}
case $FMU_PROFILE in dev | test) profile_dir=debug ;; *) profile_dir=$FMU_PROFILE ;; esac
if [ "$FMU_PROFILE" = test ]; then
    # The feature set of `cargo test --workspace` (dev-dependencies included): after the cargo
    # test stage of scripts/test.sh this compiles only the unit's cdylib and helper binary
    # (`-p ehl-bearing-fmi` alone resolves other features and rebuilds the library: minutes).
    stage "cargo build --profile test --workspace (the cargo test feature set)"
    cargo build --profile test --quiet --workspace --lib --bins --tests --examples
else
    stage "cargo build --profile $FMU_PROFILE -p ehl-bearing-fmi"
    cargo build --profile "$FMU_PROFILE" --quiet -p ehl-bearing-fmi
fi
export FMU_BUILT=1
helper=$CARGO_TARGET_DIR/$profile_dir/ehl-bearing-fmu
out=target/fmi-test
rm -rf "$out"
mkdir -p "$out"
case_file=examples/7006.toml
fitted=crates/ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json
trends=docs/figures/study_7006_quasi_static_trends.json
stage "build the FMUs (scripts/build_fmu.sh)"
scripts/build_fmu.sh "$case_file" - "$out/7006_hertz.fmu"
scripts/build_fmu.sh "$case_file" "$fitted" "$out/7006_fitted.fmu"
scripts/build_fmu.sh "$case_file" "$trends" "$out/7006_trends.fmu"
stage "fmpy validate"
for f in "$out"/*.fmu; do
    "$venv/bin/fmpy" validate "$f"
    echo "  $f: valid"
done
stage "FMPy simulations against the library"
# 200 steps of 0.1 ms: one period of the displacement oscillation, inner speed 5000 → 6000 rpm.
"$helper" inputs "$case_file" 200 1e-4 "$out/inputs.csv"
check() { "$venv/bin/python" scripts/fmi_check.py simulate "$1" "$out/inputs.csv" "$helper" "$out" "$2" ${3:-}; }
for f in hertz fitted trends; do
    # From scratch every call: the library's numbers to the bit.
    check "$out/7006_$f.fmu" 0 --cold
    # Warm starts (the default): the same within the solvers' tolerances.
    check "$out/7006_$f.fmu" 1e-9
done
stage "errors through FMPy's logger"
"$venv/bin/python" scripts/fmi_check.py errors "$out/7006_fitted.fmu"
stage "per-call cost"
"$venv/bin/python" scripts/fmi_check.py time "$out/7006_fitted.fmu" "$out/inputs.csv" 20000
for f in fitted trends; do
    "$venv/bin/python" -m zipfile -e "$out/7006_$f.fmu" "$out/${f}_unzipped"
    echo "  $f, through the C functions (Rust caller, in-process) and the library: $("$helper" bench "$out/${f}_unzipped/resources" 20000)"
done
stage "all FMU checks passed"
