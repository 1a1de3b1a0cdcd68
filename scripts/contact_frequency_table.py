#!/usr/bin/env python3
"""Tables of docs/contact.md, "Contact dynamics over frequency", from the sweep's CSV.

Standard library only. Usage: scripts/contact_frequency_table.py [docs/figures/contact_frequency/sweep.csv]

Prints (1) per contact and speed the table of K, d, ΔF, c, k' and c_eq against Ω/ω_n with the
quasi-static row; (2) the rotor band 100–400 Hz (shaft and whirl; the ball-pass frequencies
0.4·Z·f_shaft, Z = 11, fall inside it at 3000–5000 rpm) in Ω/ω_n and the change of c_eq and k'
across it, log-linearly interpolated between the sweep's frequencies; (3) a one-branch Maxwell
(standard linear solid) fit k*(Ω) = k_0 + k_1·iΩτ/(1 + iΩτ) to k' and c_eq over Ω/ω_n ≤ 0.2 and
its largest relative errors there.
"""
import csv
import math
import sys

BAND_HZ = (100.0, 400.0)
path = sys.argv[1] if len(sys.argv) > 1 else "docs/figures/contact_frequency/sweep.csv"
rows = list(csv.DictReader(open(path)))
keys = []
for r in rows:
    k = (r["rpm"], r["ball"], r["race"])
    if k not in keys:
        keys.append(k)


def f(x):
    try:
        return float(x)
    except ValueError:
        return float("nan")


def interp(pts, x):
    """Log-x linear interpolation of (x, y) points sorted by x."""
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1:
            t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return y0 + t * (y1 - y0)
    return float("nan")


print("| rpm | contact | w0 N | Ω/ω_n | Ω/2π Hz | K N/m^d | d | ΔF N | c N·s/m | k' N/m | k'/k_qs | c_eq N·s/m | periodicity | s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
summary = []
for key in keys:
    rs = [r for r in rows if (r["rpm"], r["ball"], r["race"]) == key]
    qs = next(r for r in rs if r["method"] == "quasi-static")
    k_qs = f(qs["k_law_n_m"])
    name = f"ball {key[1]} {key[2]}"
    print(f"| {key[0]} | {name} | {f(qs['load_n']):.1f} | quasi-static | 0 | {f(qs['k']):.4e} | {f(qs['d']):.4f} | "
          f"{f(qs['delta_f_n']):.2f} | — | {k_qs:.4e} | 1 | — | — | {f(qs['seconds']):.1f} |")
    h = [r for r in rs if r["method"] == "harmonic"]
    for r in h:
        if r["error"]:
            print(f"| {key[0]} | {name} | | {r['ratio']} | | error: {r['error'][:60]} | | | | | | | | |")
            continue
        print(f"| {key[0]} | {name} | | {r['ratio']} | {f(r['omega_rad_s']) / 2 / math.pi:.0f} | {f(r['k']):.4e} | "
              f"{f(r['d']):.4f} | {f(r['delta_f_n']):.2f} | {f(r['c_n_s_m']):.1f} | {f(r['k_dyn_n_m']):.4e} | "
              f"{f(r['k_dyn_n_m']) / k_qs:.4f} | {f(r['c_eq_n_s_m']):.1f} | {f(r['periodicity']):.1e} | {f(r['seconds']):.1f} |")
    ok = [r for r in h if not r["error"]]
    wn = f(ok[0]["omega_n_rad_s"])
    band = [2 * math.pi * b / wn for b in BAND_HZ]
    c_pts = [(f(r["ratio"]), f(r["c_eq_n_s_m"])) for r in ok]
    k_pts = [(f(r["ratio"]), f(r["k_dyn_n_m"])) for r in ok]
    c_lo, c_hi = interp(c_pts, band[0]), interp(c_pts, band[1])
    k_lo, k_hi = interp(k_pts, band[0]), interp(k_pts, band[1])
    c_default = interp(c_pts, 0.1)
    # Maxwell fit on Ω/ω_n ≤ 0.2: grid search of τ, then k_0, k_1 by linear least squares on the
    # relative residuals of k' and Ω·c_eq (both in units of k_qs).
    fit_pts = [r for r in ok if f(r["ratio"]) <= 0.2]
    best = None
    for i in range(2001):
        tau = 10 ** (-7 + 4 * i / 2000)
        # unknowns k0, k1: k' = k0 + k1·x²/(1+x²), Ω·c_eq = k1·x/(1+x²), x = Ωτ
        a11 = a12 = a22 = b1 = b2 = 0.0
        for r in fit_pts:
            om = f(r["omega_rad_s"])
            x = om * tau
            g = x * x / (1 + x * x)
            q = x / (1 + x * x)
            kp, wc = f(r["k_dyn_n_m"]) / k_qs, om * f(r["c_eq_n_s_m"]) / k_qs
            # rows: [1, g]·[k0,k1] = kp ; [0, q]·[k0,k1] = wc
            a11 += 1
            a12 += g
            a22 += g * g + q * q
            b1 += kp
            b2 += g * kp + q * wc
        det = a11 * a22 - a12 * a12
        k0 = (a22 * b1 - a12 * b2) / det
        k1 = (a11 * b2 - a12 * b1) / det
        err_k = max(abs(k0 + k1 * (f(r["omega_rad_s"]) * tau) ** 2 / (1 + (f(r["omega_rad_s"]) * tau) ** 2)
                        - f(r["k_dyn_n_m"]) / k_qs) / (f(r["k_dyn_n_m"]) / k_qs) for r in fit_pts)
        err_c = max(abs(k1 * k_qs * tau / (1 + (f(r["omega_rad_s"]) * tau) ** 2) - f(r["c_eq_n_s_m"]))
                    / f(r["c_eq_n_s_m"]) for r in fit_pts)
        cost = max(err_k, err_c)
        if best is None or cost < best[0]:
            best = (cost, tau, k0 * k_qs, k1 * k_qs, err_k, err_c)
    summary.append((key, wn, band, c_lo, c_hi, k_lo, k_hi, c_default, best, f(qs["delta_f_n"]),
                    interp([(f(r["ratio"]), f(r["delta_f_n"])) for r in ok], band[0]),
                    interp([(f(r["ratio"]), f(r["delta_f_n"])) for r in ok], 0.1)))

print()
print("| rpm | contact | ω_n/2π kHz | band Ω/ω_n | c_eq at band ends N·s/m | change of c_eq | change of k' | c_eq at 0.1·ω_n / band mean | ΔF qs / band / 0.1·ω_n N |")
print("|---|---|---|---|---|---|---|---|---|")
for key, wn, band, c_lo, c_hi, k_lo, k_hi, c_def, best, dfq, dfb, dfd in summary:
    cm = 0.5 * (c_lo + c_hi)
    print(f"| {key[0]} | ball {key[1]} {key[2]} | {wn / 2 / math.pi / 1e3:.1f} | {band[0]:.4f}–{band[1]:.4f} | "
          f"{c_lo:.1f} → {c_hi:.1f} | {100 * (c_hi - c_lo) / cm:+.2f} % | {100 * (k_hi - k_lo) / (0.5 * (k_lo + k_hi)):+.3f} % | "
          f"{c_def / cm:.3f} | {dfq:.1f} / {dfb:.1f} / {dfd:.1f} |")
print()
print("| rpm | contact | τ µs | k_0 N/m | k_1 N/m | k_1·τ N·s/m | largest error k' | largest error c_eq (Ω/ω_n ≤ 0.2) |")
print("|---|---|---|---|---|---|---|---|")
for key, wn, band, c_lo, c_hi, k_lo, k_hi, c_def, best, *_ in summary:
    cost, tau, k0, k1, ek, ec = best
    print(f"| {key[0]} | ball {key[1]} {key[2]} | {tau * 1e6:.2f} | {k0:.4e} | {k1:.3e} | {k1 * tau:.1f} | "
          f"{100 * ek:.2f} % | {100 * ec:.1f} % |")

print()
print("| rpm | contact | w0 N | ω_n/2π kHz | rotor band Ω/ω_n | d: qs / 0.005 / 0.1 | ΔF N: qs / 0.005 / 0.1 | c_eq N·s/m: 0.005 / 0.1 | k'/k_qs: 0.005 / 0.1 |")
print("|---|---|---|---|---|---|---|---|---|")
for key, wn, band, *_ in summary:
    rs = [r for r in rows if (r["rpm"], r["ball"], r["race"]) == key]
    qs = next(r for r in rs if r["method"] == "quasi-static")
    at = {r["ratio"]: r for r in rs if r["method"] == "harmonic" and not r["error"]}
    a, b = at["0.005"], at["0.1"]
    kq = f(qs["k_law_n_m"])
    print(f"| {key[0]} | ball {key[1]} {key[2]} | {f(qs['load_n']):.1f} | {wn / 2 / math.pi / 1e3:.1f} | "
          f"{band[0]:.4f}–{band[1]:.4f} | {f(qs['d']):.4f} / {f(a['d']):.4f} / {f(b['d']):.4f} | "
          f"{f(qs['delta_f_n']):.1f} / {f(a['delta_f_n']):.1f} / {f(b['delta_f_n']):.1f} | "
          f"{f(a['c_eq_n_s_m']):.1f} / {f(b['c_eq_n_s_m']):.1f} | "
          f"{f(a['k_dyn_n_m']) / kq:.4f} / {f(b['k_dyn_n_m']) / kq:.4f} |")
