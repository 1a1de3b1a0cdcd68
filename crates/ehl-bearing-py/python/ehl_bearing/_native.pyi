"""Type stubs of the native module ``ehl_bearing._native`` (PyO3). SI units throughout."""

from collections.abc import Sequence
from os import PathLike
from typing import Any, Callable, Optional, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import TypeAlias

_Path: TypeAlias = Union[str, PathLike]
_Array: TypeAlias = npt.NDArray[np.float64]
_Progress: TypeAlias = Optional[Callable[[dict[str, Any]], Any]]

class EhlBearingError(ValueError):
    """An error of the ehl-bearing library, with the library's message."""

class Case:
    """A validated bearing case (geometry, materials, lubricant, operating point, settings)."""

    @staticmethod
    def from_file(path: _Path) -> Case: ...
    @staticmethod
    def from_toml(text: str, origin: str = "<string>") -> Case: ...
    @staticmethod
    def from_dict(values: dict[str, Any]) -> Case: ...
    @property
    def name(self) -> Optional[str]: ...
    @property
    def inner_speed_rad_s(self) -> float: ...
    @property
    def outer_speed_rad_s(self) -> float: ...
    @property
    def ball_count(self) -> int: ...
    @property
    def pitch_diameter_m(self) -> float: ...
    @property
    def ball_diameter_m(self) -> float: ...
    @property
    def contact_angle_rad(self) -> float: ...
    def with_inner_speed_rpm(self, rpm: float) -> Case: ...

class _Element:
    def evaluate(
        self,
        displacement: npt.ArrayLike,
        velocity: Optional[npt.ArrayLike] = None,
        inner_speed_rad_s: float = 0.0,
        outer_speed_rad_s: float = 0.0,
        cage_angle_rad: float = 0.0,
        full: bool = False,
    ) -> Any:
        """(reaction (5,), stiffness (5, 5), damping (5, 5)), or a dict with ``full=True``."""
    def cage_speed(self, inner_speed_rad_s: float, outer_speed_rad_s: float = 0.0) -> float: ...
    def cage_speed_at(
        self,
        displacement: npt.ArrayLike,
        inner_speed_rad_s: float,
        outer_speed_rad_s: float = 0.0,
        cage_angle_rad: float = 0.0,
    ) -> float: ...
    @property
    def ball_count(self) -> int: ...
    @property
    def pitch_diameter_m(self) -> float: ...
    def equilibrium(self, case: Case) -> tuple[_Array, _Array, _Array]: ...

class LawElement(_Element):
    """Fixed contact laws: dry Hertz or the fitted laws of a characterization."""

    @property
    def dry(self) -> bool: ...
    @property
    def case(self) -> Case:
        """The case the element was built for (its equilibrium gives the default preload)."""
    @staticmethod
    def hertz(case: Case) -> LawElement: ...
    @staticmethod
    def from_report(case: Case, report: dict[str, Any], by_load: bool = False) -> LawElement: ...

class TrendForceElement(_Element):
    """Contact laws from a study's trend curves."""

    @staticmethod
    def from_json(text: str) -> TrendForceElement: ...
    @staticmethod
    def from_file(path: _Path) -> TrendForceElement: ...

class Characterization:
    """The coupled characterization of a case."""

    def report(self, timing: bool = False) -> dict[str, Any]: ...
    @property
    def converged(self) -> bool: ...
    @property
    def displacement(self) -> _Array: ...
    @property
    def stiffness(self) -> _Array: ...
    @property
    def dry_stiffness(self) -> _Array: ...
    def law_element(self, by_load: bool = False) -> LawElement: ...

class RotorModel:
    """A rotor (M, C, G, K without bearings) with our force elements, integrated in Rust."""

    def __init__(
        self,
        mass: _Array,
        damping: _Array,
        gyroscopic: _Array,
        stiffness: _Array,
        constant_force: Optional[_Array] = None,
    ) -> None: ...
    @property
    def dofs(self) -> int: ...
    def add_bearing(
        self,
        element: _Element,
        dofs: Sequence[Optional[int]],
        signs: Optional[Sequence[float]] = None,
        offset: Optional[Sequence[float]] = None,
    ) -> None: ...
    def add_unbalance(
        self, dofs: tuple[int, int], mass_eccentricity_kg_m: float, phase_rad: float = 0.0
    ) -> None: ...
    @property
    def bearing_count(self) -> int: ...
    def static_equilibrium(self, speed_rad_s: float) -> dict[str, Any]: ...
    def linearized(self, speed_rad_s: float) -> dict[str, Any]: ...
    def simulate(
        self,
        step_s: float,
        duration_s: float,
        speed_rad_s: Optional[float] = None,
        ramp: Optional[tuple[float, float, float]] = None,
        record_every: int = 1,
        record_dofs: Optional[Sequence[int]] = None,
        coupling: str = "implicit",
        cage_angle_rad: Optional[float] = None,
        start_displacement: Optional[_Array] = None,
        start_velocity: Optional[_Array] = None,
        progress: Optional[Callable[[int, int, float], Any]] = None,
        time_limit_s: Optional[float] = None,
    ) -> dict[str, Any]: ...

def equilibrium(case: Case) -> dict[str, Any]: ...
def ehl(contact_toml: str, grid: Optional[int] = None, fields: bool = False) -> dict[str, Any]: ...
def contact(
    contact_toml: str,
    method: str = "quasi-static",
    film_extrapolation: bool = True,
    grid: Optional[int] = None,
    method_options: Optional[dict[str, Any]] = None,
) -> dict[str, Any]: ...
def characterize(
    case: Case,
    method: Optional[str] = None,
    progress: _Progress = None,
    time_limit_s: Optional[float] = None,
) -> Characterization: ...
def study(
    study_file: _Path, output_dir: _Path, method: Optional[str] = None, progress: _Progress = None
) -> dict[str, Any]: ...
def coefficients(
    case: Case,
    speeds_rpm: Sequence[float],
    method: Optional[str] = None,
    element: Optional[_Element] = None,
    progress: _Progress = None,
) -> list[dict[str, Any]]: ...
def ross_table_csv(coefficients: list[dict[str, Any]]) -> str: ...
def result_keys(kind: str) -> list[str]: ...
def law_maps() -> list[dict[str, Any]]: ...
