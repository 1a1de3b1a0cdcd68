"""Benchmark (timed script, not a test): 1 s of simulated time of the worked example's rotor
(examples/python/rotor_7006.py) on two fitted-law 7006 bearings (harmonic method, 5000 rpm,
with each contact's damping) at 5000 rpm, unbalance 100 g·mm, implicit coupling, cages held,
time step 2e-5 s (50 000 steps). Prints the wall time, the time per step and the integrator's
own breakdown (bearing evaluations, factorizations, the rest: Newton updates and recording).

    python examples/python/bench_rotor.py [--out docs/python] [--step 2e-5]

Uses the worked example's cached characterization (`<out>/cache/harmonic_5000.json`), computing
it if missing. The integrator is single-threaded (one core).
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import rotor_7006 as ex

import ehl_bearing as eb
from ehl_bearing import ross as er


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=pathlib.Path, default=ex.REPO / "docs" / "python")
    ap.add_argument("--step", type=float, default=2e-5, help="time step, s")
    ap.add_argument("--duration", type=float, default=1.0, help="simulated time, s")
    args = ap.parse_args()
    rpm = 5000.0
    case = eb.Case.from_file(str(ex.REPO / "examples" / "7006.toml"))
    c = case.with_inner_speed_rpm(rpm)
    el = ex.fitted_element(case, rpm, args.out / "cache")
    co = eb.coefficients(c, [rpm], element=el)
    rotor = er.two_disk_rotor(er.EhlBearingElement(0, co), er.EhlBearingElement(6, co, mounting=-1))
    sites, unb, extra = ex.nonlinear_setup(rotor, el, c, unbalance=True)
    model = er.rotor_model(rotor, sites, unb, extra_force_n=extra)
    w = rpm * math.pi / 30
    t0 = time.perf_counter()
    r = model.simulate(
        step_s=args.step,
        duration_s=args.duration,
        speed_rad_s=w,
        cage_angle_rad=0.0,
        record_every=10,
    )
    wall = time.perf_counter() - t0
    bd = r["breakdown"]
    steps = r["steps"]
    rest = bd["total_s"] - bd["bearing_s"] - bd["factorization_s"]
    print(f"rotor: {rotor.ndof} DOFs, 2 fitted-law bearings (22 contacts each), {rpm:.0f} rpm")
    print(f"simulated {args.duration} s at h = {args.step:g} s: {steps} steps")
    print(f"wall {wall:.3f} s (Python call), integrator total {bd['total_s']:.3f} s")
    print(f"per step {1e6 * bd['total_s'] / steps:.1f} µs")
    print(
        f"  bearing evaluations {bd['bearing_s']:.3f} s "
        f"({100 * bd['bearing_s'] / bd['total_s']:.0f} %, "
        f"{r['newton_iterations']} Newton iterations = "
        f"{r['newton_iterations'] / steps:.2f} per step, "
        f"{1e6 * bd['bearing_s'] / (2 * r['newton_iterations']):.1f} µs per element call)"
    )
    print(f"  factorizations {bd['factorization_s']:.4f} s")
    print(f"  rest (condensed Newton solves, Newmark updates, recording) {rest:.3f} s")
    print(f"  steps with a contact outside its fitted range: {r['steps_outside_range']}")


if __name__ == "__main__":
    main()
