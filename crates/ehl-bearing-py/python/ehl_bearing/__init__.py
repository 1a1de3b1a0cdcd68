"""ehl_bearing: lubricated angular-contact ball bearings for rotor dynamics (Python bindings).

The Rust library ``ehl-bearing`` (quasi-static 5-DOF bearing equilibrium, EHL point contacts,
fitted contact laws Q = K·δ^d + ΔF (+ c·δ̇), coupled characterization, load × speed studies,
the bearing as a force element, linearized coefficients over speed, and a rotor time integrator)
from Python. SI units throughout; our axes: x axial, y and z radial, θy and θz tilts.

- :class:`Case` — a bearing case (``Case.from_file``, ``Case.from_toml``, ``Case.from_dict``).
- :func:`equilibrium`, :func:`ehl`, :func:`contact`, :func:`characterize`, :func:`study`,
  :func:`coefficients`, :func:`ross_table_csv` — the library's computations; results with many
  fields come back as dicts (the library's JSON, SI), matrices as numpy arrays.
- :class:`LawElement`, :class:`TrendForceElement` — the bearing as a force element: numpy
  displacement (5,) in, reaction (5,), stiffness (5, 5), damping (5, 5) out.
- :class:`RotorModel` — the Rust time integrator for rotors on our force elements.
- :mod:`ehl_bearing.ross` — the ROSS bridge (optional dependency ``ross-rotordynamics``).
- :mod:`ehl_bearing.plots` — orbits, spectra, waterfalls (matplotlib) and CSV time histories.

Library errors raise :class:`EhlBearingError` (a ``ValueError``) with the library's message.
Long computations release the GIL; progress callbacks receive one dict per event.
"""

from __future__ import annotations

import sys
from typing import Any

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
    ross_table_csv,
    study,
)

__all__ = [
    "Case",
    "Characterization",
    "EhlBearingError",
    "LawElement",
    "RotorModel",
    "TrendForceElement",
    "characterize",
    "coefficients",
    "contact",
    "ehl",
    "equilibrium",
    "print_progress",
    "read_case",
    "ross_table_csv",
    "study",
]

__version__ = "0.1.0"


def read_case(path: str) -> Case:
    """Read and validate a case file (TOML); same as :meth:`Case.from_file`."""
    return Case.from_file(path)


def print_progress(event: dict[str, Any]) -> None:
    """A progress callback for :func:`characterize`, :func:`coefficients` and :func:`study` that
    prints one line per iteration or point to stderr (contact events are skipped)."""
    kind = event.get("event")
    point = ""
    if kind == "loop":
        # A study's points may run concurrently: name the point of the loop event.
        if "index" in event:
            point = f"point {event['index'] + 1}, "
        event = event.get("progress", {})
        kind = event.get("event")
    if kind == "iteration_started":
        print(
            f"{point}iteration {event['iteration']}: {event['contacts']} contacts",
            file=sys.stderr,
            flush=True,
        )
    elif kind == "point_started":
        print(
            f"point {event['index'] + 1}: {event['inner_speed_rpm']} rpm × {event['load_scale']}",
            file=sys.stderr,
            flush=True,
        )
    elif kind == "point_done":
        state = event["error"] or ("converged" if event["converged"] else "NOT converged")
        print(
            f"point {event['index'] + 1}: {state} in {event['seconds']:.1f} s",
            file=sys.stderr,
            flush=True,
        )
