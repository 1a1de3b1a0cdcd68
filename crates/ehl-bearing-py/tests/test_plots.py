"""The plots of ehl_bearing.plots on synthetic responses (no solver): spectra without leakage
skirts, waterfall labels inside the plot; and the worked example's output folder."""

from __future__ import annotations

import pathlib
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from ehl_bearing import plots

REPO = pathlib.Path(__file__).resolve().parents[3]
STEP_S = 2e-5


def response(x: np.ndarray, speed_rad_s: float = 0.0, step_s: float = STEP_S) -> dict:
    """A recorded response of one DOF (index 7), in the layout of RotorModel.simulate."""
    t = step_s * np.arange(len(x))
    return {
        "time_s": t,
        "speed_rad_s": np.full(len(x), speed_rad_s) if np.isscalar(speed_rad_s) else speed_rad_s,
        "record_dofs": [7],
        "displacement": np.asarray(x, dtype=float)[:, None],
    }


def test_whole_periods_counts_samples_of_whole_periods():
    # 5000 rpm = 83.33 Hz: 600 samples of 2e-5 s per period.
    assert plots.whole_periods(5000, STEP_S, 5000 / 60) == 4800
    assert plots.whole_periods(599, STEP_S, 5000 / 60) == 599  # not one period
    # 384.6 Hz: 130.0 samples per period; 7 periods = 910 samples.
    assert plots.whole_periods(1000, STEP_S, 1 / (130 * STEP_S)) == 910


def test_a_steady_component_over_whole_periods_does_not_leak():
    """10 µm at 83.33 Hz over 0.1 s (8.33 periods): trimmed to 8 whole periods, the periodic
    Hann window puts it on its bin and the two next to it, exactly; the record as given leaks
    over the whole band."""
    f0 = 5000 / 60
    t = STEP_S * np.arange(5000)
    x = 10e-6 * np.cos(2 * np.pi * f0 * t + 0.3)
    n = plots.whole_periods(len(x), STEP_S, f0)
    f, a = plots.amplitude_spectrum(x[len(x) - n :], STEP_S)
    k = int(np.argmax(a))
    assert f[k] == pytest.approx(f0, rel=1e-12)
    assert a[k] == pytest.approx(10e-6, rel=1e-9)
    far = np.abs(np.arange(len(a)) - k) > 1
    assert a[far].max() < 1e-12 * a[k]
    f_all, leaky = plots.amplitude_spectrum(x, STEP_S)
    assert leaky[f_all > 400].max() > 1e-6 * a[k]


def test_spectrum_axis_spans_the_dynamic_range_below_the_peak():
    f0 = 5000 / 60
    t = STEP_S * np.arange(10000)
    x = 10e-6 * np.sin(2 * np.pi * f0 * t) + 1e-9 * np.sin(2 * np.pi * 860 * t)
    fig = plots.spectrum(
        {"run": response(x)}, 7, since_s=0.1, max_hz=1500, periods_of_hz=f0, dynamic_range=1e6
    )
    lo, hi = fig.axes[0].get_ylim()
    assert hi == pytest.approx(30.0, rel=1e-6)  # 3 × the 10 µm peak
    assert lo == pytest.approx(1e-5, rel=1e-6)  # a millionth of it
    plots._plt().close(fig)


def test_waterfall_order_labels_lie_inside_the_plot():
    """Run-up 3000 → 5000 rpm in 1 s: the labels of the order lines (1× ends at 83 Hz, the
    ball-pass order 4.62× at 385 Hz, a 20× order beyond max_hz) are drawn inside the axes."""
    h = 5e-5
    t = h * np.arange(20000)
    w = (3000 + 2000 * t) * np.pi / 30
    phase = np.cumsum(w) * h
    x = 1e-6 * np.sin(phase) + 1e-8 * np.sin(4.62 * phase)
    fig = plots.waterfall(
        response(x, speed_rad_s=w, step_s=h),
        7,
        window_s=0.05,
        max_hz=1200,
        orders=(1.0, 4.62, 20.0),
        order_labels=("1×", "Z·f_cage (4.62×)", "20×"),
    )
    ax = fig.axes[0]
    lo, hi = ax.collections[0].get_clim()
    assert hi - lo == pytest.approx(6.0)  # the default dynamic range, 1e6
    fig.canvas.draw()
    box = ax.get_window_extent()
    labels = [c for c in ax.texts if c.get_text() in ("1×", "Z·f_cage (4.62×)", "20×")]
    assert len(labels) == 3
    for text in labels:
        b = text.get_window_extent()
        assert box.x0 <= b.x0 and b.x1 <= box.x1 and box.y0 <= b.y0 and b.y1 <= box.y1, (
            text.get_text(),
            b,
            box,
        )
    plots._plt().close(fig)


def test_worked_example_writes_to_a_folder_outside_docs_by_default():
    out = subprocess.run(
        [sys.executable, str(REPO / "examples" / "python" / "rotor_7006.py"), "--help"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert "--out OUT" in out.stdout and "rotor_7006_out" in out.stdout, out.stdout
    assert "docs" not in out.stdout.split("--out OUT", 1)[1].split("\n\n")[0]
