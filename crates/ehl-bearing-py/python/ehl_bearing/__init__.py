"""ehl_bearing: lubricated angular-contact ball bearings for rotor dynamics (Python bindings).

The Rust library ``ehl-bearing`` (quasi-static 5-DOF bearing equilibrium, EHL point contacts,
fitted contact laws Q = K·δ^d + ΔF (+ c·δ̇), coupled characterization, load × speed studies,
the bearing as a force element, linearized coefficients over speed, and a rotor time integrator)
from Python. SI units throughout; our axes: x axial, y and z radial, θy and θz tilts.

- :class:`Case` — a bearing case (``Case.from_file``, ``Case.from_toml``, ``Case.from_dict``).
- :func:`equilibrium`, :func:`ehl`, :func:`contact`, :func:`characterize`, :func:`study`,
  :func:`coefficients`, :func:`ross_table_csv` — the library's computations; results with many
  fields come back as dicts (the library's JSON, SI), matrices as numpy arrays.
- :func:`law_maps` — the shipped law maps of ``method="map"`` (their envelopes and settings).
- :class:`LawElement`, :class:`TrendForceElement` — the bearing as a force element: numpy
  displacement (5,) in, reaction (5,), stiffness (5, 5), damping (5, 5) out.
- :class:`RotorModel` — the Rust time integrator for rotors on our force elements.
- :mod:`ehl_bearing.ross` — the ROSS bridge (optional dependency ``ross-rotordynamics``).
- :mod:`ehl_bearing.plots` — orbits, spectra, waterfalls (matplotlib) and CSV time histories.

Library errors raise :class:`EhlBearingError` (a ``ValueError``) with the library's message.
Long computations release the GIL; progress callbacks receive one dict per event.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from typing import Any, Callable, Optional, TextIO

from ._native import (
    Case,
    Characterization,
    EhlBearingError,
    LawElement,
    RotorModel,
    TrendForceElement,
    characterize,
    coefficients,
    contact,
    ehl,
    equilibrium,
    law_maps,
    result_keys,
    ross_table_csv,
    study,
)

__all__ = [
    "Case",
    "Characterization",
    "EhlBearingError",
    "LawElement",
    "ProgressPrinter",
    "RotorModel",
    "TrendForceElement",
    "characterize",
    "coefficients",
    "contact",
    "ehl",
    "equilibrium",
    "law_maps",
    "print_progress",
    "read_case",
    "result_keys",
    "ross_table_csv",
    "study",
]

__version__ = "0.1.0"


def read_case(path: str) -> Case:
    """Read and validate a case file (TOML); same as :meth:`Case.from_file`."""
    return Case.from_file(path)


class ProgressPrinter:
    """A progress callback for :func:`characterize`, :func:`coefficients` and :func:`study` that
    prints one line per iteration or point to ``file`` (default stderr), each starting with the
    time elapsed since the run began, ``[  12.3 s]`` (contact events are skipped). Finished
    iterations and points also give their own time: the iteration's wall time with the contacts
    it characterized and reused, the point's wall time.

    The clock starts when the printer is made and restarts at the event that begins a run: a
    study's ``planned`` event, or a loop's first iteration (the load prediction, iteration 0, or
    iteration 1 when it is not preceded by the prediction). ``clock`` (seconds, monotonic) is for
    tests. Events may arrive from worker threads: lines are printed whole."""

    def __init__(
        self, file: Optional[TextIO] = None, clock: Callable[[], float] = time.monotonic
    ) -> None:
        self._file = file
        self._clock = clock
        self._t0 = clock()
        self._last_iteration: Optional[int] = None
        self._lock = threading.Lock()

    def _print(self, text: str) -> None:
        out = self._file if self._file is not None else sys.stderr
        print(f"[{self._clock() - self._t0:6.1f} s] {text}", file=out, flush=True)

    def __call__(self, event: dict[str, Any]) -> None:
        with self._lock:
            self._handle(event)

    def _handle(self, event: dict[str, Any]) -> None:
        kind = event.get("event")
        point = ""
        if kind == "planned":
            self._t0 = self._clock()
            self._print(
                f"study: {event['points']} points, {event['to_compute']} to compute"
                + (f" ({event['redone']} redone)" if event.get("redone") else "")
            )
            return
        if kind == "loop":
            # A study's points may run concurrently: name the point of the loop event.
            if "index" in event:
                point = f"point {event['index'] + 1}, "
            event = event.get("progress", {})
            kind = event.get("event")
        elif kind == "iteration_started":
            # A loop of its own (characterize, coefficients): its first iteration starts the clock.
            it = event["iteration"]
            if it == 0 or (it == 1 and self._last_iteration != 0):
                self._t0 = self._clock()
            self._last_iteration = it
        if kind == "iteration_started":
            it = event["iteration"]
            name = "load prediction" if it == 0 else f"iteration {it}"
            self._print(f"{point}{name}: {event['contacts']} contacts")
        elif kind == "iteration_done":
            r = event.get("record") or {}
            seconds = r.get("seconds", math.nan)
            change = r.get("max_load_change", math.nan)
            self._print(
                f"{point}iteration {r.get('iteration', '?')} done in {seconds:.1f} s "
                f"({r.get('characterized', '?')} contacts characterized, {r.get('reused', '?')} "
                f"reused): largest relative load change {change:.2e}"
            )
        elif kind == "point_started":
            rpm, scale = event["inner_speed_rpm"], event["load_scale"]
            self._print(f"point {event['index'] + 1}: {rpm} rpm × {scale}")
        elif kind == "point_done":
            state = event["error"] or ("converged" if event["converged"] else "NOT converged")
            self._print(f"point {event['index'] + 1}: {state} in {event['seconds']:.1f} s")


_default_printer = ProgressPrinter()


def print_progress(event: dict[str, Any]) -> None:
    """A progress callback for :func:`characterize`, :func:`coefficients` and :func:`study` that
    prints one line per iteration or point to stderr with the time elapsed since the run began
    and each finished iteration's and point's own time (a shared :class:`ProgressPrinter`; make
    one per run to choose the file)."""
    _default_printer(event)
