#!/usr/bin/env python3
"""Times the law map against the quasi-static EHL method, side by side in one run, as whole
`ehl-bearing` processes (start, case, loop, output), best and median of N runs:

- the seed case (examples/7006.toml) at 3000, 4000 and 5000 rpm by `characterize … --json`;
- the two bearings with other oils (examples/7205_vg68.toml, examples/7210_vg22.toml), and the
  7210 at 7500 rpm (a slow large bearing);
- the seed study (examples/study_7006.toml: 3 speeds × 4 load scales, 12 points) by `study`.

Each by the map (with the quasi-static fallback for contacts outside its envelope) and the
quasi-static method at its default grid (129², the grid of the maps these cases use) and, for the
seed case and the study, also on 65² (the coarse grid's time, for scale).

    cargo build --release -p ehl-bearing-cli
    python3 scripts/bench_law_map.py [--runs N] [--ehl-runs E] [--bin PATH]
    # N: runs of the map (default 20, the map's study N/4); E of the EHL cases (3); EHL study once
"""

from __future__ import annotations

import argparse
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
TARGET = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
BIN = TARGET / "release" / "ehl-bearing"
MAP_OPTS = "\n[method_options]\nfallback = true\n"
GRID_OPTS = "\n[method_options]\ngrid = 65\n"


def timed(make_args, runs: int) -> tuple[float, float]:
    """make_args(k) gives the command of run k (a fresh output folder per run for studies)."""
    times = []
    for k in range(runs):
        args = make_args(k)
        t0 = time.perf_counter()
        r = subprocess.run(args, capture_output=True, check=False)
        times.append(time.perf_counter() - t0)
        if r.returncode != 0:
            raise SystemExit(f"{' '.join(args)} failed: {r.stderr.decode()[-400:]}")
    return min(times), statistics.median(times)


def row(label: str, name: str, best: float, median: float, runs: int) -> None:
    print(f"| {label} | {name} | {best:.4f} | {median:.4f} | {runs} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=20, help="runs of the map (EHL: 3, study: 1)")
    ap.add_argument("--ehl-runs", type=int, default=3, help="runs of the EHL method's cases")
    ap.add_argument("--bin", default=str(BIN), help="the ehl-bearing binary")
    a = ap.parse_args()
    binary = a.bin
    print("| case | method | best s | median s | runs |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        tmpdir = pathlib.Path(tmp)

        def case_variants(label: str, text: str, coarse: bool) -> None:
            variants = {
                "map (fallback on)": ('method = "map"\n', MAP_OPTS, a.runs),
                "quasi-static, 129² (default)": ("", "", a.ehl_runs),
            }
            if coarse:
                variants["quasi-static, 65²"] = ('method = "quasi-static"\n', GRID_OPTS, a.ehl_runs)
            for name, (head, tail, runs) in variants.items():
                path = tmpdir / f"{label.replace(' ', '_')}_{len(head)}_{len(tail)}.toml"
                path.write_text(head + text + tail)
                best, median = timed(
                    lambda _k, p=path: [binary, "characterize", str(p), "--json"], runs
                )
                row(label, name, best, median, runs)

        seed = (ROOT / "examples" / "7006.toml").read_text()
        for rpm in (3000, 4000, 5000):
            text = seed.replace("inner_speed_rpm = 5000.0", f"inner_speed_rpm = {rpm}.0")
            case_variants(f"seed {rpm} rpm", text, True)
        for name in ("7205_vg68", "7210_vg22"):
            case_variants(name, (ROOT / "examples" / f"{name}.toml").read_text(), False)
        # A slow large bearing: the 7210 at 7500 rpm lies in the eighth map (L 8–12.5).
        slow = (ROOT / "examples" / "7210_vg22.toml").read_text()
        assert "inner_speed_rpm = 12000.0" in slow
        slow = slow.replace("inner_speed_rpm = 12000.0", "inner_speed_rpm = 7500.0")
        case_variants("7210_vg22 at 7500 rpm", slow, False)

        study = (ROOT / "examples" / "study_7006.toml").read_text()
        study = study.replace('case = "7006.toml"', f'case = "{ROOT / "examples" / "7006.toml"}"')
        variants = {
            "map (fallback on)": ('method = "map"', MAP_OPTS, max(a.runs // 4, 1)),
            "quasi-static, 65²": ('method = "quasi-static"', GRID_OPTS, 1),
            "quasi-static, 129² (default)": ('method = "quasi-static"', "", 1),
        }
        for name, (method, tail, runs) in variants.items():
            text = study.replace('method = "quasi-static"', method, 1) + tail
            path = tmpdir / f"study_{len(method)}_{len(tail)}.toml"
            path.write_text(text)
            best, median = timed(
                lambda k, p=path: [
                    binary,
                    "study",
                    str(p),
                    "-o",
                    str(tmpdir / f"out_{p.stem}_{k}"),
                ],
                runs,
            )
            row("seed study (12 points)", name, best, median, runs)


if __name__ == "__main__":
    main()
