"""Worked example: a two-disk rotor on two 7006 angular-contact ball bearings at 3000–5000 rpm,
with three bearing models — ROSS's Friswell ball bearing, our dry Hertz bearing, our fitted EHL
bearing (harmonic method: stiffness and damping from the lubricated contacts).

    python examples/python/rotor_7006.py [--out DIR]

Needs `pip install ./crates/ehl-bearing-py[ross]`. Writes figures (PNG + SVG), CSV time
histories and `rotor_7006.md` (the summary) into the output folder DIR (created if needed;
default `rotor_7006_out` in the current folder; `scripts/figures.sh` passes `--out docs/python`
to regenerate the repository's copy). The EHL characterizations (harmonic method, 20–25 s per
speed on 2 cores) are cached there (`cache/harmonic_<rpm>.json`): delete the folder to recompute.

Setup. Shaft: steel, Ø 30 mm (the 7006's bore), 0.5 m, 6 Timoshenko elements; disks Ø 150 × 30 mm
at nodes 2 and 4; bearings at nodes 0 and 6, a back-to-back pair (the second mirrored), each
preloaded axially to the seed case's axial approach (≈ 907 N axial load at the rotor's
equilibrium; 1000 N in the case alone), and carrying the seed case's radial
load (1000 N along our y and z = ROSS x and y: e.g. a belt pull) plus the rotor's weight.
Friswell's bearing uses the same radial load (|F| = 1414 N).
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys
import time

import numpy as np

import ehl_bearing as eb
from ehl_bearing import plots
from ehl_bearing import ross as er

REPO = pathlib.Path(__file__).resolve().parents[2]
SPEEDS_RPM = [3000.0, 4000.0, 5000.0]
UNBALANCE_KG_M = 1e-4  # 100 g·mm on disk 1 (node 2)
DISK_NODE = 2
STEP_S = 2e-5


def fitted_element(case: eb.Case, rpm: float, cache: pathlib.Path) -> eb.LawElement:
    """The fitted-law element at `rpm` (harmonic method), from the cache or characterized."""
    path = cache / f"harmonic_{int(rpm)}.json"
    c = case.with_inner_speed_rpm(rpm)
    if path.exists():
        report = json.loads(path.read_text())
    else:
        print(
            f"characterizing at {rpm:.0f} rpm (harmonic method; minutes)…",
            file=sys.stderr,
        )
        ch = eb.characterize(c, method="harmonic", progress=eb.print_progress)
        report = ch.report()
        cache.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(report))
    return eb.LawElement.from_report(c, report)


def modal_table(rotor, speed_rad_s: float, modes: int = 4):
    """(damped natural frequency Hz, damping ratio, whirl) of the first `modes` modes."""
    m = rotor.run_modal(speed=speed_rad_s, num_modes=2 * modes + 6, sparse=False)
    wd = np.asarray(m.wd)
    ld = np.asarray(m.log_dec)
    zeta = ld / np.sqrt(4 * math.pi**2 + ld**2)
    whirl = list(m.whirl_direction())
    rows = [(wd[i] / (2 * math.pi), zeta[i], whirl[i]) for i in range(len(wd)) if wd[i] > 1.0]
    return rows[:modes]


def critical_speeds(rotor, max_rpm: float = 15000.0, count: int = 2) -> list[float]:
    """Forward-whirl critical speeds (rpm) below `max_rpm`: where a forward mode's damped
    frequency equals the shaft speed (bearing coefficients held at their nearest tabulated speed
    outside 3000–5000 rpm)."""
    grid = np.linspace(500.0, max_rpm, 30)
    fwd = []
    for rpm in grid:
        m = rotor.run_modal(speed=rpm * math.pi / 30, num_modes=16, sparse=False)
        wd = np.asarray(m.wd) / (2 * math.pi)
        whirl = np.asarray(m.whirl_direction())
        f = sorted(wd[(whirl == "Forward") & (wd > 1.0)])
        fwd.append(f[:count] + [np.nan] * (count - len(f[:count])))
    fwd = np.array(fwd)
    out = []
    for k in range(count):
        g = fwd[:, k] - grid / 60.0
        for i in range(len(grid) - 1):
            if np.isfinite(g[i]) and np.isfinite(g[i + 1]) and g[i] > 0 >= g[i + 1]:
                s = g[i] / (g[i] - g[i + 1])
                out.append(float(grid[i] + s * (grid[i + 1] - grid[i])))
                break
    return out


def steady_unbalance(m, k, c, g, speed_rad_s: float, disk_dofs) -> np.ndarray:
    """Complex steady-state response X (x(t) = Re(X·e^{iΩt})) of the linear rotor (mass m,
    stiffness k, damping c, gyroscopic g; torsion DOFs left out) to the unbalance on disk 1:
    (K − Ω²M + iΩ(C + ΩG))·X = m·e·Ω²·(1, −i) on the disk's x, y."""
    w = speed_rad_s
    n = m.shape[0]
    free = [i for i in range(n) if i % 6 != 5]  # ROSS: 6 DOFs per node, θ (torsion) last
    z = k - w**2 * m + 1j * w * (c + w * g)
    f = np.zeros(n, dtype=complex)
    f[disk_dofs[0]] = UNBALANCE_KG_M * w**2
    f[disk_dofs[1]] = -1j * UNBALANCE_KG_M * w**2
    x = np.zeros(n, dtype=complex)
    x[free] = np.linalg.solve(z[np.ix_(free, free)], f[free])
    return x


def semi_major(xc: complex, yc: complex) -> float:
    """Semi-major axis of the orbit (Re(xc·e^{iφ}), Re(yc·e^{iφ}))."""
    ph = np.linspace(0, 2 * math.pi, 721)
    return float(np.hypot(np.real(xc * np.exp(1j * ph)), np.real(yc * np.exp(1j * ph))).max())


def loads(element, case):
    """Axial preload approach and the case's radial reactions (our y, z) of `element`."""
    q, _, _ = element.equilibrium(case)
    r, _, _ = element.evaluate(q, inner_speed_rad_s=case.inner_speed_rad_s)
    return q[0], r[1], r[2]


def nonlinear_setup(rotor, element, case, unbalance: bool):
    x0, fy, fz = loads(element, case)
    offset = (x0, 0.0, 0.0, 0.0, 0.0)
    sites = [
        er.BearingSite(element, 0, 1, offset),
        er.BearingSite(element, 6, -1, offset),
    ]
    extra = np.zeros(rotor.ndof)
    for node in (0, 6):
        d = er.node_dofs(rotor, node)
        extra[d[0]] += fy
        extra[d[1]] += fz
    unb = [er.Unbalance(DISK_NODE, UNBALANCE_KG_M)] if unbalance else []
    return sites, unb, extra


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--out",
        type=pathlib.Path,
        default=pathlib.Path("rotor_7006_out"),
        help="output folder (default: rotor_7006_out in the current folder)",
    )
    args = ap.parse_args()
    out: pathlib.Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.time()
    case = eb.Case.from_file(str(REPO / "examples" / "7006.toml"))

    # Bearing models and their linear coefficients per speed.
    dry = eb.LawElement.hertz(case)
    ehl = {rpm: fitted_element(case, rpm, out / "cache") for rpm in SPEEDS_RPM}
    _, fy, fz = loads(dry, case)
    radial = math.hypot(fy, fz)  # 1414 N: the seed case's radial load
    friswell = er.two_disk_rotor(
        er.friswell_bearing(0, case, radial), er.friswell_bearing(6, case, radial)
    )
    bare = er.rs.Rotor(friswell.shaft_elements, friswell.disk_elements)
    _, _, extra = nonlinear_setup(bare, dry, case, unbalance=False)

    def at_equilibrium(element_at):
        """Our bearings linearized at the rotor's own static equilibrium at each speed (the
        loads they carry in this rotor: preload, radial load, weight), not at the case's."""

        def sites(w):
            rpm = round(w * 30 / math.pi)
            c = case.with_inner_speed_rpm(rpm)
            return nonlinear_setup(bare, element_at(rpm), c, unbalance=False)[0]

        speeds = [rpm * math.pi / 30 for rpm in SPEEDS_RPM]
        return er.linearize_at_equilibrium(bare, sites, speeds, extra_force_n=extra)

    rotors = {
        "Friswell (ROSS)": friswell,
        "dry Hertz": at_equilibrium(lambda rpm: dry),
        "fitted EHL": at_equilibrium(lambda rpm: ehl[float(rpm)]),
    }

    md = ["# Worked example: two-disk rotor on two 7006 bearings (3000–5000 rpm)", ""]
    md += [
        f"Generated by `python examples/python/rotor_7006.py --out {out.as_posix()}` "
        "(`ehl_bearing` + ROSS " + er.rs.__version__ + "). Setup in the script's docstring: "
        "steel shaft Ø 30 mm × 0.5 m, two disks Ø 150 × 30 mm at nodes 2 and 4, a back-to-back "
        "pair of 7006 bearings at nodes 0 and 6, each preloaded to the case's axial approach "
        "(≈ 907 N axial load at the rotor's equilibrium) and carrying the seed case's radial "
        "load (1000 N along ROSS x and y) plus the rotor's weight. Our bearings are linearized "
        "at the rotor's own static equilibrium at each speed "
        "(`ehl_bearing.ross.linearize_at_equilibrium`); the loads they carry there:",
        "",
        rotors["fitted EHL"].linearization_table(),
        "",
        "## Bearing stiffness and damping (one bearing, ROSS axes, SI)",
        "",
        "| model | rpm | kxx N/m | kyy N/m | kzz N/m | kαα N·m/rad | kxβ N/rad | cxx N·s/m "
        "| cαα N·m·s/rad |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    radial_c = {}  # model → radial damping cxx per speed, N·s/m
    for rpm in SPEEDS_RPM:
        w = rpm * math.pi / 30
        for name, r in rotors.items():
            b = r.bearing_elements[0]
            if isinstance(b, er.EhlBearingElement):
                k, c = b.K5(w), b.C5(w)
                radial_c.setdefault(name, []).append(c[0, 0])
                md.append(
                    f"| {name} | {rpm:.0f} | {k[0, 0]:.3e} | {k[1, 1]:.3e} | {k[2, 2]:.3e} | "
                    f"{k[3, 3]:.3e} | {k[0, 4]:.3e} | {c[0, 0]:.3e} | {c[3, 3]:.3e} |"
                )
            else:
                k, c = b.K(w), b.C(w)
                radial_c.setdefault(name, []).append(c[0, 0])
                md.append(
                    f"| {name} | {rpm:.0f} | {k[0, 0]:.3e} | {k[1, 1]:.3e} | {k[2, 2]:.3e} | — "
                    f"(none) | — | {c[0, 0]:.3e} | — |"
                )

    # Modes and critical speeds.
    md += ["", "## Critical speeds (forward whirl, rpm)", ""]
    md += ["| model | 1st | 2nd |", "|---|---|---|"]
    crit = {}
    for name, r in rotors.items():
        crit[name] = critical_speeds(r)
        cs = [f"{c:.0f}" for c in crit[name]] + ["> 15000"] * (2 - len(crit[name]))
        md.append(f"| {name} | {cs[0]} | {cs[1]} |")
        print(f"{name}: critical speeds {crit[name]}", file=sys.stderr)
    first = {k: v[0] for k, v in crit.items() if v}
    if len(first) == 3:
        fr, dr, eh = first["Friswell (ROSS)"], first["dry Hertz"], first["fitted EHL"]
        md += [
            "",
            f"First forward critical speed: {eh:.0f} rpm on the fitted EHL bearings, "
            f"{100 * (eh / dr - 1):+.1f} % against dry Hertz ({dr:.0f} rpm) and "
            f"{100 * (eh / fr - 1):+.1f} % against ROSS's Friswell bearing ({fr:.0f} rpm): all "
            "above the 3000–5000 rpm range. The bearings are far stiffer radially than the "
            "shaft, so the first bending mode hardly depends on the bearing model; the bearings "
            "differ in damping (below) and in the tilt and axial terms Friswell's model lacks.",
        ]
    md += [
        "",
        "## First modes: damped natural frequency and damping ratio",
        "",
        "| model | rpm | mode 1 | mode 2 | mode 3 | mode 4 |",
        "|---|---|---|---|---|---|",
    ]
    zeta1 = {}

    def c_range(name: str) -> str:
        lo, hi = min(radial_c[name]), max(radial_c[name])
        return f"{lo:.0f}" if round(lo) == round(hi) else f"{lo:.0f}–{hi:.0f}"

    for rpm in SPEEDS_RPM:
        for name, r in rotors.items():
            rows = modal_table(r, rpm * math.pi / 30)
            cells = [f"{f:.1f} Hz, ζ = {z:.2e} ({wh[0]})" for f, z, wh in rows]
            md.append(f"| {name} | {rpm:.0f} | " + " | ".join(cells) + " |")
            zeta1.setdefault(name, []).append(rows[1][1])
    md += [
        "",
        "(B backward, F forward, M mixed whirl.) Damping ratio of the first forward mode over "
        "3000–5000 rpm: "
        + ", ".join(f"{k} {min(v):.1e}–{max(v):.1e}" for k, v in zeta1.items())
        + ". The dry Hertz bearing has no damping (ζ at round-off); the fitted EHL bearing's "
        "damping is the harmonic method's squeeze-film term c·δ̇ of each contact "
        f"({c_range('fitted EHL')} N·s/m radially per bearing), Friswell's is the rule "
        f"c = 1.25e-5·k ({c_range('Friswell (ROSS)')} N·s/m): "
        "both leave the rotor almost undamped, so free vibration rings for seconds (visible in "
        "the run-up waterfalls).",
    ]

    # Unbalance response: linear steady state (all three) and nonlinear time response (ours).
    md += [
        "",
        f"## Unbalance response at disk 1 (node {DISK_NODE}), {UNBALANCE_KG_M * 1e6:.0f} g·mm",
        "",
        "Orbit semi-major axis, µm. Linear: steady state of the rotor with the bearings' "
        "linear coefficients (ROSS's `rotor.K`, `rotor.C`). Nonlinear: time response with our "
        f"force elements (implicit, h = {STEP_S:g} s, 0.2 s, cages held: the fitted laws are "
        "per ball) started on the linearized steady orbit: its 1× component over the last "
        "0.1 s (whole revolutions) and the largest radius about the mean there.",
        "",
        "| model | rpm | linear | nonlinear 1× | nonlinear peak |",
        "|---|---|---|---|---|",
    ]
    responses: dict[float, dict[str, dict]] = {}
    elements = {"dry Hertz": lambda rpm: dry, "fitted EHL": lambda rpm: ehl[rpm]}
    dx, dy = er.node_dofs(rotors["dry Hertz"], DISK_NODE)[:2]
    bench = {}
    for rpm in SPEEDS_RPM:
        w = rpm * math.pi / 30
        c_rpm = case.with_inner_speed_rpm(rpm)
        responses[rpm] = {}
        for name, r in rotors.items():
            xr = steady_unbalance(r.M(), r.K(w), r.C(w), r.G(), w, (dx, dy))
            lin = semi_major(xr[dx], xr[dy])
            nl, peak = "—", "—"
            if name in elements:
                el = elements[name](rpm)
                sites, unb, extra = nonlinear_setup(r, el, c_rpm, unbalance=True)
                model = er.rotor_model(r, sites, unb, extra_force_n=extra)
                # Start on the linearized steady orbit about the static equilibrium, so that the
                # almost undamped rotor is not left ringing at its natural frequencies.
                li = model.linearized(w)
                x0 = steady_unbalance(
                    li["mass"], li["stiffness"], li["damping"], li["gyroscopic"], w, (dx, dy)
                )
                t0 = time.time()
                resp = model.simulate(
                    step_s=STEP_S,
                    duration_s=0.2,
                    speed_rad_s=w,
                    cage_angle_rad=0.0,
                    start_displacement=li["static"]["displacement"] + np.real(x0),
                    start_velocity=np.real(1j * w * x0),
                )
                bench[(name, rpm)] = (
                    time.time() - t0,
                    resp["steps"],
                    resp["breakdown"],
                )
                responses[rpm][name] = resp
                keep = resp["time_s"] >= 0.1
                x = plots.column(resp, dx)[keep]
                y = plots.column(resp, dy)[keep]
                peak = f"{1e6 * np.hypot(x - x.mean(), y - y.mean()).max():.3f}"
                t_last = 0.2 - 0.1 // (2 * math.pi / w) * (2 * math.pi / w)  # whole revolutions
                nl = f"{1e6 * plots.synchronous_orbit(resp, (dx, dy), since_s=t_last)[0]:.3f}"
                tag = name.replace(" ", "_").lower()
                plots.time_history_csv(
                    resp,
                    out / "csv" / f"unbalance_{tag}_{rpm:.0f}rpm.csv",
                    [dx, dy],
                    ["disk1_x_m", "disk1_y_m"],
                    every=10,
                )
            md.append(f"| {name} | {rpm:.0f} | {1e6 * lin:.3f} | {nl} | {peak} |")
        fig = plots.orbit(
            responses[rpm],
            (dx, dy),
            title=f"Disk 1 orbit at {rpm:.0f} rpm, unbalance {UNBALANCE_KG_M * 1e6:.0f} g·mm",
            since_s=0.1,
        )
        plots.save(fig, out / f"orbit_{rpm:.0f}rpm")
        f_shaft = rpm / 60
        fig = plots.spectrum(
            responses[rpm],
            dx,
            title=f"Disk 1 x displacement spectrum at {rpm:.0f} rpm (cages held)",
            since_s=0.1,
            marks_hz={"1×": f_shaft, "2×": 2 * f_shaft},
            max_hz=1500,
            periods_of_hz=f_shaft,
        )
        plots.save(fig, out / f"spectrum_{rpm:.0f}rpm")

    # Varying compliance: rolling cages, no unbalance, dry Hertz (identical balls), 5000 rpm.
    w5 = 5000 * math.pi / 30
    r = rotors["dry Hertz"]
    sites, _, extra = nonlinear_setup(r, dry, case, unbalance=False)
    vc = er.time_response(
        r, sites, [], speed_rad_s=w5, step_s=STEP_S, duration_s=0.2, extra_force_n=extra
    )
    # Z·f_cage at the operating cage speed the cages turned at (the bearing model's orbital speeds).
    f_bp = dry.ball_count * vc["cage_speed_rad_s"][:, 0].mean() / (2 * math.pi)
    b0 = er.node_dofs(r, 0)
    fig = plots.spectrum(
        {"dry Hertz, rolling cages": vc},
        b0[1],
        title="Bearing 1 (node 0) vertical displacement, 5000 rpm, no unbalance",
        since_s=0.05,
        marks_hz={"Z·f_cage": f_bp, "2·Z·f_cage": 2 * f_bp, "3·Z·f_cage": 3 * f_bp},
        max_hz=1500,
        periods_of_hz=f_bp,
    )
    plots.save(fig, out / "ball_pass_spectrum_5000rpm")
    plots.time_history_csv(
        vc,
        out / "csv" / "ball_pass_dry_5000rpm.csv",
        b0[:2],
        ["node0_x_m", "node0_y_m"],
        every=5,
    )

    # Run-up 3000 → 5000 rpm in 1 s: waterfall (dry Hertz, rolling cages, with unbalance).
    sites, unb, extra = nonlinear_setup(r, dry, case, unbalance=True)
    t0 = time.time()
    ru = er.time_response(
        r,
        sites,
        unb,
        ramp_rad_s=(3000 * math.pi / 30, w5, 1.0),
        step_s=5e-5,
        duration_s=1.0,
        extra_force_n=extra,
        record_dofs=[b0[0], b0[1], dx, dy],
    )
    t_runup = time.time() - t0
    bp_order = dry.ball_count * np.mean(ru["cage_speed_rad_s"][:, 0] / ru["speed_rad_s"])
    for node_name, dof in (("bearing1", b0[1]), ("disk1", dx)):
        fig = plots.waterfall(
            ru,
            dof,
            window_s=0.05,
            title=f"Run-up 3000→5000 rpm in 1 s, {node_name} (dry Hertz, rolling cages)",
            max_hz=1200,
            orders=(1.0, bp_order),
            order_labels=("1×", f"Z·f_cage ({bp_order:.2f}×)"),
        )
        plots.save(fig, out / f"waterfall_runup_{node_name}")
    plots.time_history_csv(
        ru,
        out / "csv" / "runup_dry.csv",
        [b0[0], b0[1], dx, dy],
        ["node0_x_m", "node0_y_m", "disk1_x_m", "disk1_y_m"],
        every=20,
    )

    md += [
        "",
        "## Figures",
        "",
        *[f"- Orbit at {rpm:.0f} rpm: ![](orbit_{rpm:.0f}rpm.png)" for rpm in SPEEDS_RPM],
        *[f"- Spectrum at {rpm:.0f} rpm: ![](spectrum_{rpm:.0f}rpm.png)" for rpm in SPEEDS_RPM],
        f"- Varying compliance, Z·f_cage = {f_bp:.1f} Hz at 5000 rpm: "
        "![](ball_pass_spectrum_5000rpm.png)",
        "- Run-up waterfalls: ![](waterfall_runup_bearing1.png) ![](waterfall_runup_disk1.png)",
        "",
        "Time histories (CSV, SI): `csv/`.",
        "",
        "## Run times (this machine)",
        "",
        "| run | wall s | steps | time per step µs | bearing evaluations s | factorization s |",
        "|---|---|---|---|---|---|",
    ]
    for (name, rpm), (wall, steps, bd) in bench.items():
        md.append(
            f"| {name}, {rpm:.0f} rpm, 0.2 s | {wall:.2f} | {steps} | {1e6 * wall / steps:.1f} "
            f"| {bd['bearing_s']:.2f} | {bd['factorization_s']:.4f} |"
        )
    md.append(
        f"| run-up, dry, 1 s, h = 5e-5 s | {t_runup:.2f} | {ru['steps']} | "
        f"{1e6 * t_runup / ru['steps']:.1f} | {ru['breakdown']['bearing_s']:.2f} | "
        f"{ru['breakdown']['factorization_s']:.4f} |"
    )
    md += ["", f"Whole script: {time.time() - t_start:.0f} s.", ""]
    (out / "rotor_7006.md").write_text("\n".join(md))
    print(f"wrote {out / 'rotor_7006.md'}", file=sys.stderr)


if __name__ == "__main__":
    main()
