"""Your own rotor on ehl-bearing bearings, in ROSS: a short template to copy.

    python examples/python/your_own_rotor.py

Needs `pip install ./crates/ehl-bearing-py[ross]`. The rotor is built from ROSS primitives (a steel
shaft Ø 30 mm × 0.4 m in 8 Timoshenko elements, one disk Ø 150 × 25 mm at mid-span); two 7006
bearings from the seed case sit at its ends, back to back (the second mirrored), preloaded by the
case's axial load (the offset comes from the element's own equilibrium). The bearings are dry Hertz
elements (no EHL run, milliseconds): for the lubricated bearing put in a fitted element
(`eb.characterize(case, method="harmonic").law_element()`, minutes per speed).

Steps: linearize the bearings at the rotor's own static equilibrium (gravity + preload; the table
printed says at which loads), ROSS's modal analysis and Campbell diagram, ROSS's unbalance response,
and the nonlinear time response on the bearings' force elements, started on ROSS's orbit: in the
linear limit (a small unbalance) it stays there. The first ROSS modal analysis of a session
compiles ROSS's mode-shape code (numba; up to a minute).
"""

from __future__ import annotations

import math
import pathlib

import numpy as np
import ross as rs

import ehl_bearing as eb
from ehl_bearing import ross as er

REPO = pathlib.Path(__file__).resolve().parents[2]
RPM = 4000.0
ELEMENTS = 8
DISK_NODE = 4
UNBALANCE_KG_M = 1e-5  # 10 g·mm on the disk


def build(case_file: pathlib.Path = REPO / "examples" / "7006.toml"):
    """The bare ROSS rotor (no bearings), our bearing sites, and the rotor linearized at its own
    static equilibrium over 1000–6000 rpm (an EhlRotor: ROSS analyses see the full 5×5 blocks)."""
    steel = rs.Material(name="steel_own_rotor", rho=7810.0, E=211e9, G_s=81.2e9)
    shaft = [
        rs.ShaftElement(L=0.4 / ELEMENTS, idl=0.0, odl=0.030, material=steel, gyroscopic=True)
        for _ in range(ELEMENTS)
    ]
    disk = rs.DiskElement.from_geometry(
        n=DISK_NODE, material=steel, width=0.025, i_d=0.030, o_d=0.150
    )
    bare = rs.Rotor(shaft, [disk])  # the rotor without our bearings

    case = eb.Case.from_file(str(case_file))
    element = eb.LawElement.hertz(case)  # or a fitted LawElement
    sites = [
        er.BearingSite(element, node=0, mounting=1),  # preload offset: the element's equilibrium
        er.BearingSite(element, node=ELEMENTS, mounting=-1),  # back to back: mirrored
    ]
    speeds = np.linspace(1000.0, 6000.0, 6) * math.pi / 30
    rotor = er.linearize_at_equilibrium(bare, sites, speeds)
    return bare, sites, rotor


def unbalance_orbits(bare, sites, rotor, rpm: float = RPM, duration_s: float = 0.02):
    """ROSS's unbalance response of the linearized rotor at `rpm` (complex amplitudes X,
    x(t) = Re(X·e^{iΩt})) and the nonlinear time response on the bearings' force elements
    started on that orbit (implicit Newmark, h = 2e-5 s, cages held). Returns (ROSS's orbit
    radius at the disk, m; the largest nonlinear radius about the static position, m; the
    nonlinear response)."""
    w = rpm * math.pi / 30
    resp = rotor.run_unbalance_response(DISK_NODE, UNBALANCE_KG_M, 0.0, frequency=[w])
    x = np.asarray(resp.forced_resp)[:, 0]
    dx, dy = er.node_dofs(rotor, DISK_NODE)[:2]
    static = er.rotor_model(bare, sites).static_equilibrium(w)["displacement"]
    out = er.time_response(
        bare,
        sites,
        [er.Unbalance(DISK_NODE, UNBALANCE_KG_M)],
        speed_rad_s=w,
        step_s=2e-5,
        duration_s=duration_s,
        cage_angle_rad=0.0,
        start_displacement=static + np.real(x),
        start_velocity=np.real(1j * w * x),
    )
    phase = np.linspace(0.0, 2 * math.pi, 361)
    ross_radius = np.hypot(
        np.real(x[dx] * np.exp(1j * phase)), np.real(x[dy] * np.exp(1j * phase))
    ).max()
    d = out["displacement"]
    radius = np.hypot(d[:, dx] - static[dx], d[:, dy] - static[dy]).max()
    return float(ross_radius), float(radius), out


def main() -> None:
    bare, sites, rotor = build()
    print("Bearings linearized at the rotor's own static equilibrium (bearing axes):")
    print(rotor.linearization_table())
    w = RPM * math.pi / 30
    modal = rotor.run_modal(w, num_modes=16, sparse=False)
    wd = np.asarray(modal.wd)
    print(
        f"\nDamped natural frequencies at {RPM:.0f} rpm, Hz:", np.round(wd[wd > 1] / 2 / math.pi, 1)
    )
    speeds = np.linspace(1000.0, 6000.0, 11) * math.pi / 30
    campbell = rotor.run_campbell(speeds, frequencies=6)
    print(
        "Campbell: first two damped frequencies, Hz, over",
        f"{speeds[0] * 30 / math.pi:.0f}–{speeds[-1] * 30 / math.pi:.0f} rpm:",
    )
    for s, f in zip(speeds, np.asarray(campbell.wd)):
        print(f"  {s * 30 / math.pi:5.0f} rpm: {f[0] / 2 / math.pi:7.1f} {f[1] / 2 / math.pi:7.1f}")
    ross_r, ours_r, out = unbalance_orbits(bare, sites, rotor)
    print(
        f"\nUnbalance {UNBALANCE_KG_M * 1e6:.0f} g·mm at node {DISK_NODE}, {RPM:.0f} rpm: "
        f"orbit radius {1e6 * ross_r:.4f} µm (ROSS, linear) vs {1e6 * ours_r:.4f} µm "
        f"(nonlinear bearings, {out['steps']} steps in {out['breakdown']['total_s']:.2f} s)"
    )


if __name__ == "__main__":
    main()
