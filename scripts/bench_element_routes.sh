#!/usr/bin/env bash
# Per-call cost of one force-element call by route: Rust (examples/bench_element.rs), C
# (tests/c/test_ehl.c's timed loop against the release library), MATLAB/Octave MEX
# (matlab/tests/bench_ehl_mex.m; needs Octave: scripts/test_octave.sh installs it) and, if
# PYTHON names an interpreter with the ehl_bearing package (e.g. target/py-venv/bin/python after
# scripts/test_python.sh), Python. The same loop everywhere: the harmonic method's fitted laws
# with damping (7006 at 3000 rpm), warm state, the position moving by 10 nm and the cage turning
# each call. CALLS (default 100000; MEX and Python a fifth of it) sets the loop length.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
calls=${CALLS:-100000}
lib="$CARGO_TARGET_DIR/release"
work="$CARGO_TARGET_DIR/octave"
mkdir -p "$work"
echo "== $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
cargo build --release --quiet -p ehl-bearing-c --lib --examples
"$lib/examples/bench_element" "$calls"
"$lib/examples/write_reference" "$work/reference.txt"
cc -std=c99 -O2 -I crates/ehl-bearing-c/include crates/ehl-bearing-c/tests/c/test_ehl.c \
    -L "$lib" -Wl,-rpath,"$lib" -lehl_bearing_c -lm -o "$work/test_ehl_release"
EHL_BENCH_CALLS=$calls "$work/test_ehl_release" "$root" "$work/reference.txt" | grep "per call"
if command -v octave >/dev/null; then
    matlab="$root/crates/ehl-bearing-c/matlab"
    octave --no-gui --no-window-system --norc --quiet --eval \
        "addpath('$matlab'); addpath('$matlab/tests'); ehl_build_mex('$lib'); bench_ehl_mex('$root', $((calls / 5)))" \
        2> >(grep -v "ignoring const execution_exception" >&2)
fi
if [ -n "${PYTHON:-}" ]; then
    "$PYTHON" - "$root" "$((calls / 5))" <<'PY'
import json, math, pathlib, sys, time
import numpy as np
import ehl_bearing as eb
root, calls = pathlib.Path(sys.argv[1]), int(sys.argv[2])
case = eb.Case.from_file(str(root / "examples/7006.toml")).with_inner_speed_rpm(3000.0)
report = json.loads((root / "crates/ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json").read_text())
e = eb.LawElement.from_report(case, report)
q0, _, _ = e.equilibrium(case)
ws = case.inner_speed_rad_s
wc = e.cage_speed(ws, 0.0)
v = np.array([1e-4, -2e-4, 1e-4, 1e-3, -1e-3])
q = np.array(q0, dtype=float)
e.evaluate(q, v, inner_speed_rad_s=ws)
t0 = time.perf_counter()
for i in range(1, calls + 1):
    t = i * 1e-5
    q[1] = q0[1] + 1e-8 * math.sin(1e3 * t)
    e.evaluate(q, v, inner_speed_rad_s=ws, cage_angle_rad=wc * t)
dt = time.perf_counter() - t0
print(f"force element through Python (LawElement.evaluate): {calls} calls, {1e6 * dt / calls:.2f} us per call")
PY
fi
echo "== load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
