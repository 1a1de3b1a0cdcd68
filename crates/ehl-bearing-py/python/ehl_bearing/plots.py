"""Outputs a rotordynamicist expects from a time response: orbits, displacement spectra, a
waterfall over a run-up (matplotlib; saved as PNG and SVG) and time histories as CSV.

All functions take the dict of :meth:`ehl_bearing.RotorModel.simulate` (or
:func:`ehl_bearing.ross.time_response`): ``time_s``, ``speed_rad_s``, ``record_dofs`` and
``displacement`` (records × recorded DOFs, SI). DOFs are given as global rotor indices (e.g.
:func:`ehl_bearing.ross.node_dofs`). Needs matplotlib (``pip install 'ehl_bearing[plot]'``).
"""

from __future__ import annotations

import csv
import math
import pathlib
from collections.abc import Sequence
from typing import Any, Optional

import numpy as np

__all__ = [
    "amplitude_spectrum",
    "column",
    "orbit",
    "save",
    "spectrum",
    "synchronous_orbit",
    "time_history_csv",
    "waterfall",
    "whole_periods",
]


def _positive(name: str, value: Any) -> float:
    """``value`` as a finite float > 0, or a ValueError naming ``name``, the value and the range."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} = {value!r}: expected a finite number > 0") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} = {value!r}: expected a finite number > 0")
    return v


def _dof(value: Any) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"dof = {value!r}: expected a global DOF index (an integer ≥ 0)")
    return int(value)


def _response(response: Any, *keys: str) -> dict:
    if not isinstance(response, dict):
        kind = type(response).__name__
        raise TypeError(f"response: expected the dict RotorModel.simulate returns, got {kind}")
    missing = [k for k in keys if k not in response]
    if missing:
        raise ValueError(
            f"response: no {missing[0]!r} (expected the dict RotorModel.simulate returns; "
            f"keys: {sorted(response)[:8]})"
        )
    return response


def column(response: dict, dof: int) -> np.ndarray:
    """The recorded displacement history of global DOF ``dof`` (m or rad)."""
    dof = _dof(dof)
    _response(response, "record_dofs", "displacement")
    dofs = list(response["record_dofs"])
    if dof not in dofs:
        raise ValueError(f"DOF {dof} was not recorded (recorded: {dofs[:8]}…)")
    return np.asarray(response["displacement"])[:, dofs.index(dof)]


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig: Any, path_stem: pathlib.Path) -> list[pathlib.Path]:
    """Save ``fig`` as ``<stem>.png`` (150 dpi) and ``<stem>.svg``; returns the paths."""
    path_stem = pathlib.Path(path_stem)
    path_stem.parent.mkdir(parents=True, exist_ok=True)
    out = []
    for ext in ("png", "svg"):
        p = path_stem.with_suffix(f".{ext}")
        fig.savefig(p, dpi=150, bbox_inches="tight")
        out.append(p)
    _plt().close(fig)
    return out


def synchronous_orbit(
    response: dict, dofs: tuple[int, int], since_s: float = 0.0
) -> tuple[float, complex, complex]:
    """The 1× (shaft-synchronous) component of the orbit of the node whose lateral DOFs are
    ``dofs``, from ``since_s`` on at constant speed: (semi-major axis in m, complex amplitudes
    X, Y with x(t) ≈ Re(X·e^{iΩt})). Removes the free vibration at the natural frequencies that
    a start from rest leaves in a lightly damped rotor (use a whole number of revolutions)."""
    t = np.asarray(response["time_s"])
    keep = t >= since_s
    w = float(np.mean(np.asarray(response["speed_rad_s"])[keep]))
    e = np.exp(-1j * w * t[keep])
    xs = [column(response, d)[keep] for d in dofs]
    amp = [2.0 * np.mean((x - x.mean()) * e) for x in xs]
    ph = np.linspace(0.0, 2 * np.pi, 721)
    r = np.hypot(np.real(amp[0] * np.exp(1j * ph)), np.real(amp[1] * np.exp(1j * ph)))
    return float(r.max()), complex(amp[0]), complex(amp[1])


def orbit(
    responses: dict[str, dict],
    dofs: tuple[int, int],
    title: str = "",
    since_s: float = 0.0,
    about_mean: bool = True,
) -> Any:
    """Orbit plot (µm) of the node whose lateral DOFs are ``dofs`` (ROSS x, y) for each labelled
    response in ``responses``, from ``since_s`` on; ``about_mean`` subtracts each orbit's mean
    (the static deflection). Returns the matplotlib figure."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5, 5))
    for label, r in responses.items():
        keep = np.asarray(r["time_s"]) >= since_s
        x = column(r, dofs[0])[keep]
        y = column(r, dofs[1])[keep]
        if about_mean:
            x, y = x - x.mean(), y - y.mean()
        ax.plot(1e6 * x, 1e6 * y, lw=0.8, label=label)
    ax.set_xlabel("x (ROSS), µm")
    ax.set_ylabel("y (ROSS, vertical), µm")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return fig


def amplitude_spectrum(signal: np.ndarray, step_s: float) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum (periodic Hann window, amplitude-corrected) of a uniformly
    sampled signal with its mean removed: (frequency Hz, amplitude in the signal's unit). A
    component with a whole number of periods in the record (see :func:`whole_periods`) falls on
    its bin and the two next to it, with no leakage beyond; any other leaks with the window's
    sidelobes (−31 dB, falling 18 dB per octave)."""
    step_s = _positive("step_s", step_s)
    try:
        s = np.asarray(signal, dtype=float)
    except (TypeError, ValueError):
        raise TypeError("signal: expected a 1-D array of real numbers") from None
    if s.ndim != 1 or s.size < 2:
        raise ValueError(f"signal: expected a 1-D array of at least 2 samples, got shape {s.shape}")
    if not np.all(np.isfinite(s)):
        raise ValueError(f"signal[{int(np.argmin(np.isfinite(s)))}] is not finite")
    s = s - s.mean()
    n = len(s)
    w = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)
    a = 2.0 * np.abs(np.fft.rfft(s * w)) / w.sum()
    return np.fft.rfftfreq(n, step_s), a


def whole_periods(n: int, step_s: float, frequency_hz: float) -> int:
    """The largest number of samples, at most ``n``, that spans a whole number of periods of
    ``frequency_hz`` (to the nearest sample); ``n`` when not even one period fits."""
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n = {n!r}: expected a number of samples (an integer ≥ 0)")
    step_s = _positive("step_s", step_s)
    frequency_hz = _positive("frequency_hz", frequency_hz)
    cycles_per_sample = frequency_hz * step_s
    if cycles_per_sample == 0.0 or not math.isfinite(1.0 / cycles_per_sample):
        return n  # not even one period fits (the product underflowed)
    per = 1.0 / cycles_per_sample  # samples per period
    periods = n // per
    return min(n, round(periods * per)) if periods >= 1 else n


def spectrum(
    responses: dict[str, dict],
    dof: int,
    title: str = "",
    since_s: float = 0.0,
    marks_hz: Optional[dict[str, float]] = None,
    max_hz: Optional[float] = None,
    periods_of_hz: Optional[float] = None,
    dynamic_range: float = 1e6,
) -> Any:
    """Displacement spectrum (µm, log scale) of global DOF ``dof`` for each labelled response,
    from ``since_s`` on, with vertical marks at ``marks_hz`` (label → Hz, e.g. 1× and Z·f_cage).

    ``periods_of_hz``: analyse the last whole number of periods of this frequency (e.g. the shaft
    speed) of the record, so that a steady component at it and its harmonics does not leak.
    ``dynamic_range``: the amplitude axis spans this ratio below the largest amplitude shown
    (default 1e6: amplitudes a millionth of the peak are at the level of the integrator's
    tolerances and the window's leakage, not of the rotor's response)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4))
    top = 0.0
    for label, r in responses.items():
        t = np.asarray(r["time_s"])
        h = t[1] - t[0]
        x = column(r, dof)[t >= since_s]
        if periods_of_hz:
            x = x[len(x) - whole_periods(len(x), h, periods_of_hz) :]
        f, a = amplitude_spectrum(x, h)
        shown = (f > 0) & (f <= max_hz) if max_hz else f > 0
        top = max(top, float((1e6 * a[shown]).max(initial=0.0)))
        ax.semilogy(f[1:], 1e6 * a[1:], lw=0.8, label=label)
    if top > 0.0:
        ax.set_ylim(top / dynamic_range, 3.0 * top)
    for name, fm in (marks_hz or {}).items():
        ax.axvline(fm, color="k", ls=":", lw=0.8)
        ax.text(fm, ax.get_ylim()[1], f" {name}", rotation=90, va="top", fontsize=7)
    if max_hz:
        ax.set_xlim(0, max_hz)
    ax.set_xlabel("frequency, Hz")
    ax.set_ylabel("amplitude, µm")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return fig


def waterfall(
    response: dict,
    dof: int,
    window_s: float,
    title: str = "",
    max_hz: Optional[float] = None,
    orders: Sequence[float] = (1.0,),
    order_labels: Optional[Sequence[str]] = None,
    dynamic_range: float = 1e6,
) -> Any:
    """Waterfall of a run-up: amplitude spectra (µm) of global DOF ``dof`` over consecutive
    windows of ``window_s`` against the mean shaft speed of each window (rpm), as a colour map
    (frequency × speed) over ``dynamic_range`` below the largest amplitude, with order lines
    (multiples of the shaft speed, e.g. 1× and the ball-pass order Z·f_cage/f_shaft) labelled
    inside the plot."""
    plt = _plt()
    t = np.asarray(response["time_s"])
    h = t[1] - t[0]
    n = max(round(window_s / h), 8)
    x = column(response, dof)
    speed = np.asarray(response["speed_rad_s"])
    rows, rpm = [], []
    for k in range(0, len(x) - n + 1, n):
        f, a = amplitude_spectrum(x[k : k + n], h)
        rows.append(1e6 * a)
        rpm.append(speed[k : k + n].mean() * 30 / np.pi)
    amp = np.array(rows)
    # Colours over `dynamic_range` below the largest amplitude (lower ones at the bottom colour).
    top = float(np.log10(max(amp.max(), 1e-300)))
    bottom = top - np.log10(dynamic_range)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    mesh = ax.pcolormesh(
        f,
        rpm,
        np.log10(np.maximum(amp, 10.0**bottom)),
        shading="nearest",
        cmap="viridis",
        vmin=bottom,
        vmax=top,
        rasterized=True,
    )
    fig.colorbar(mesh, ax=ax, label="log10 amplitude, µm")
    labels = order_labels or [f"{o:g}×" for o in orders]
    right = max_hz or float(f[-1])
    for o, lab in zip(orders, labels):
        ax.plot(np.array(rpm) / 60 * o, rpm, "w--", lw=0.7)
        # Inside the plot, just below the top end of the order line (or at the right edge
        # where the line leaves the plot there), on a dark box so it reads on any colour.
        x_end = min(rpm[-1] / 60 * o, right)
        ax.annotate(
            lab,
            (x_end, rpm[-1]),
            xytext=(-3 if x_end >= 0.8 * right else 3, -3),
            textcoords="offset points",
            ha="right" if x_end >= 0.8 * right else "left",
            va="top",
            color="w",
            fontsize=7,
            bbox={"facecolor": "black", "alpha": 0.5, "pad": 1.5, "edgecolor": "none"},
        )
    if max_hz:
        ax.set_xlim(0, max_hz)
    ax.set_xlabel("frequency, Hz")
    ax.set_ylabel("shaft speed, rpm")
    ax.set_title(title, fontsize=9)
    return fig


def time_history_csv(
    response: dict,
    path: pathlib.Path,
    dofs: Sequence[int],
    names: Sequence[str],
    every: int = 1,
) -> pathlib.Path:
    """Write ``time_s``, ``speed_rad_s`` and the displacement of each of ``dofs`` (SI; column
    names ``names``) and every bearing's reaction (N, N·m; ours) as CSV, every ``every``-th
    record."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    cols = [column(response, d) for d in dofs]
    reac = np.asarray(response.get("bearing_reaction", np.zeros((len(response["time_s"]), 0, 5))))
    rnames = [
        f"bearing{b}_{c}"
        for b in range(reac.shape[1])
        for c in ("fx_n", "fy_n", "fz_n", "my_n_m", "mz_n_m")
    ]
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time_s", "speed_rad_s", *names, *rnames])
        for i in range(0, len(response["time_s"]), every):
            t = response["time_s"][i]
            w.writerow(
                [
                    repr(float(t)),
                    repr(float(response["speed_rad_s"][i])),
                    *(repr(float(c[i])) for c in cols),
                    *(repr(float(v)) for v in reac[i].reshape(-1)),
                ]
            )
    return path
