#!/usr/bin/env bash
# Build the bearing force element as an FMI 2.0 model-exchange FMU (docs/fmi.md).
#
#   scripts/build_fmu.sh CASE.toml [ELEMENT.json|-] [OUT.fmu]
#
# CASE.toml: the bearing (geometry, materials, race control, kinematics model).
# ELEMENT.json: a characterization report (`ehl-bearing characterize CASE --json`,
#   characterization.json, a study point's `result` record) → fitted laws; or a study's trends.json →
#   trend element; omitted or `-` → dry Hertz laws. The files go into the FMU's resources/ as
#   case.toml and characterization.json or trends.json; the unit reads them at fmi2Instantiate.
# OUT.fmu: default ehl_bearing.fmu.
#
# Builds crates/ehl-bearing-fmi in release (cargo, CARGO_TARGET_DIR or target/; FMU_PROFILE=test
# builds with the test profile instead, reusing what `cargo test` compiled), writes
# modelDescription.xml from the crate's variable table and zips it with
# binaries/linux64/ehl_bearing_fmi.so and resources/ (Python's zipfile: no zip tool needed).
# Platform: x86_64 Linux (binaries/linux64).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
usage="usage: scripts/build_fmu.sh CASE.toml [characterization.json|trends.json|-] [OUT.fmu]"
case_file=${1:?$usage}
element=${2:--}
out=${3:-ehl_bearing.fmu}
[ -f "$case_file" ] || { echo "build_fmu.sh: no case file $case_file" >&2; exit 1; }
if [ "$(uname -sm)" != "Linux x86_64" ]; then
    echo "build_fmu.sh: builds binaries/linux64 only (this is $(uname -sm))" >&2
    exit 1
fi
kind=hertz
if [ "$element" != - ]; then
    [ -f "$element" ] || { echo "build_fmu.sh: no element file $element" >&2; exit 1; }
    # A characterization report has per-contact laws ("contacts"); a trend model has "inner" and
    # "outer" race trends.
    kind=$(python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
print("characterization" if "contacts" in d else "trends" if "inner" in d and "outer" in d else "unknown")' "$element")
    if [ "$kind" = unknown ]; then
        echo "build_fmu.sh: $element is neither a characterization report (\"contacts\") nor a trend model (\"inner\", \"outer\")" >&2
        exit 1
    fi
fi
profile=${FMU_PROFILE:-release}
case $profile in dev | test) profile_dir=debug ;; *) profile_dir=$profile ;; esac
# scripts/test_fmi.sh builds first (FMU_BUILT=1), with the feature set it needs.
if [ -z "${FMU_BUILT:-}" ]; then
    (cd "$root" && cargo build --profile "$profile" --quiet -p ehl-bearing-fmi)
fi
release=$CARGO_TARGET_DIR/$profile_dir
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/binaries/linux64" "$stage/resources"
"$release/ehl-bearing-fmu" model-description "$stage/modelDescription.xml"
cp "$release/libehl_bearing_fmi.so" "$stage/binaries/linux64/ehl_bearing_fmi.so"
# The profiles keep line tables (debug = 1): drop them from the unit if strip is there.
if command -v strip >/dev/null; then strip --strip-debug "$stage/binaries/linux64/ehl_bearing_fmi.so"; fi
cp "$case_file" "$stage/resources/case.toml"
case $kind in
    characterization) cp "$element" "$stage/resources/characterization.json" ;;
    trends) cp "$element" "$stage/resources/trends.json" ;;
esac
mkdir -p "$(dirname "$out")"
out_abs=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
python3 - "$stage" "$out_abs" <<'EOF'
import os, sys, zipfile
stage, out = sys.argv[1:3]
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for d, dirs, files in sorted(os.walk(stage)):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(d, f)
            z.write(p, os.path.relpath(p, stage))
EOF
echo "$out ($kind element, $(du -k "$out_abs" | cut -f1) kB)"
