#!/usr/bin/env python3
"""Times the seed case (examples/7006.toml) characterized by the law map against the quasi-static
EHL method, side by side in one run: `ehl-bearing characterize … --json` as a whole process (start,
case, loop, output), best and median of N runs, at 3000, 4000 and 5000 rpm — the map (with the
quasi-static fallback for contacts outside its envelope), the quasi-static method at the map's grid
(65²) and at its default grid (129²).

    cargo build --release -p ehl-bearing-cli
    python3 scripts/bench_law_map.py [--runs N]      # N for the map (default 20); EHL runs 3 times
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
BIN = ROOT / "target" / "release" / "ehl-bearing"


def timed(args: list[str], runs: int) -> tuple[float, float]:
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        r = subprocess.run(args, capture_output=True, check=False)
        times.append(time.perf_counter() - t0)
        if r.returncode != 0:
            raise SystemExit(f"{' '.join(args)} failed: {r.stderr.decode()[-400:]}")
    return min(times), statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=20, help="runs of the map (EHL: 3)")
    a = ap.parse_args()
    seed = (ROOT / "examples" / "7006.toml").read_text()
    print("| rpm | method | best s | median s | runs |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for rpm in (3000, 4000, 5000):
            text = seed.replace("inner_speed_rpm = 5000.0", f"inner_speed_rpm = {rpm}.0")
            map_opts = "\n[method_options]\nfallback = true\n"
            grid_opts = "\n[method_options]\ngrid = 65\n"
            variants = {
                "map (fallback on)": ('method = "map"\n', map_opts, a.runs),
                "quasi-static, 65²": ('method = "quasi-static"\n', grid_opts, 3),
                "quasi-static, 129² (default)": ("", "", 3),
            }
            for name, (head, tail, runs) in variants.items():
                path = pathlib.Path(tmp) / f"seed_{rpm}_{len(head)}_{len(tail)}.toml"
                path.write_text(head + text + tail)
                best, median = timed([str(BIN), "characterize", str(path), "--json"], runs)
                print(f"| {rpm} | {name} | {best:.4f} | {median:.4f} | {runs} |", flush=True)


if __name__ == "__main__":
    main()
