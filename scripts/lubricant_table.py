#!/usr/bin/env python3
"""The docs/lubricant.md table: the seed bearing (examples/7006_vg46.toml: ISO VG, VI 100,
885 kg/m³ at 15 °C, mineral; roughness 0.02/0.06 µm) at 3000/4000/5000 rpm for ISO VG 22, 32 and
68 at 40, 60 and 80 °C, characterized with the default method; per point the smallest central
and minimum film, the smallest Λ, κ, the largest thermal film reduction and the warnings.

Usage: cargo build --release -p ehl-bearing-cli && python3 scripts/lubricant_table.py [BINARY]
Prints a Markdown table on stdout (about 10-20 s per point on one core).
"""
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

root = Path(__file__).resolve().parent.parent
binary = sys.argv[1] if len(sys.argv) > 1 else str(root / "target/release/ehl-bearing")
template = (root / "examples/7006_vg46.toml").read_text()

print("| ISO VG | T °C | n rpm | ν mm²/s | κ | h_c µm | h_min µm | Λ min | thermal max | warnings |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for vg in (22, 32, 68):
    for t in (40, 60, 80):
        for n in (3000, 4000, 5000):
            text = re.sub(r"(?m)^iso_vg = .*$", f"iso_vg = {vg}", template)
            text = re.sub(r"(?m)^temperature_c = .*$", f"temperature_c = {t}.0", text)
            text = re.sub(r"(?m)^inner_speed_rpm = .*$", f"inner_speed_rpm = {n}.0", text)
            with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
                f.write(text)
            out = subprocess.run(
                [binary, "characterize", f.name, "--json", "--time-limit", "600"],
                capture_output=True, text=True)
            Path(f.name).unlink()
            if out.returncode != 0:
                print(f"| {vg} | {t} | {n} | failed: {out.stderr.strip().splitlines()[-1]} |||||||")
                continue
            lub = json.loads(out.stdout)["lubrication"]
            rows = [c for c in lub["contacts"] if c["min_film_m"] is not None]
            hc = min(c["central_film_m"] for c in rows) * 1e6
            hm = min(c["min_film_m"] for c in rows) * 1e6
            lam = lub["min_lambda"]
            th = lub["max_thermal_reduction"]
            flags = []
            if lam is not None and lam < 1.5:
                flags.append("Λ < 1.5")
            if th is not None and th > 0.10:
                flags.append("thermal > 10 %")
            if lub["kappa"] is not None and lub["kappa"] < 1.0:
                flags.append("κ < 1")
            print(f"| {vg} | {t} | {n} | {lub['kinematic_viscosity_mm2_s']:.2f} | "
                  f"{lub['kappa']:.2f} | {hc:.3f} | {hm:.3f} | {lam:.2f} | {100 * th:.1f} % | "
                  f"{', '.join(flags) or '-'} |", flush=True)
