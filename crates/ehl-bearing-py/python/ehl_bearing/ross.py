"""ROSS bridge: our bearings in ROSS rotors (optional dependency ``ross-rotordynamics``).

Axes. Ours: x axial, y and z radial, θy and θz tilts about +y and +z. ROSS (per node): x and y
lateral (y vertical, gravity along −y), z axial, α and β rotations about x and y, θ torsion. The
map (as ``ehl_bearing.coefficients`` uses for its ROSS table; both frames right-handed):

    ROSS x ← our y,  ROSS y ← our z,  ROSS z ← our x,  ROSS α ← θy,  ROSS β ← θz.

A bearing mounted the other way round (its axial direction along −ROSS z, e.g. the second bearing
of a back-to-back pair) is the mirror image: our x, θy and θz change sign (``mounting=-1``).

Linear analyses: ROSS rotors accept only 3-DOF bearings (x, y, z). :class:`EhlBearingElement` is
a ROSS ``BearingElement`` with those terms from our coefficients (speed-dependent) that also
carries our whole 5×5 block; :class:`EhlRotor` is a ``ross.Rotor`` whose ``K(speed)`` and
``C(speed)`` add the rest of each such block (tilt stiffness and damping, x–y/tilt and
axial/radial cross terms) at the node's x, y, z, α, β — so ``run_modal``, ``run_campbell``,
``run_unbalance_response`` and ROSS's linear time response all see them. A plain ``ross.Rotor``
would keep only the 3-DOF part: it refuses an :class:`EhlBearingElement` (``TypeError``).

Where to linearize: :func:`linearize_at_equilibrium` solves the static equilibrium of the rotor on
its bearings (preload offsets, gravity, shaft loads, tilts; the nonlinear bearing forces, so the
loads and the coefficients are consistent) and returns an :class:`EhlRotor` whose bearings are
linearized there, with the loads each bearing carries (``rotor.linearization``,
``rotor.linearization_table()``). An :class:`EhlBearingElement` built from
:func:`ehl_bearing.coefficients` is linearized at its case's loads instead; an :class:`EhlRotor`
with such bearings warns (:class:`CaseLoadsWarning`). :func:`read_ross_table` reads the
``ross_bearing.csv`` table into a plain (3-DOF) ROSS ``BearingElement``.

Nonlinear time response (:func:`time_response`): the rotor's M, C, G, K without bearings (ROSS's
``M0``, ``C0``, ``G0``, ``K0``) go to the Rust integrator (``ehl_bearing.RotorModel``) with our
force elements at the bearing nodes, unbalances, gravity and the cage angle advancing with the
cage speed. ROSS's equation of motion is ``M q̈ + (C + Ω G) q̇ + K q = F``; the integrator uses
the same ``D(Ω) = C + Ω·G``. ROSS's run-up term ``Ω̇·Ksdt·q`` is not included (small for the
run-ups here: Ω̇ ≈ 20 rad/s²).
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
import sys
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Callable, Optional, Union

import numpy as np

from . import _native

try:  # ROSS is optional: pip install ./crates/ehl-bearing-py[ross]
    import ross as rs
except ImportError as _e:  # pragma: no cover - exercised only without ROSS
    raise ImportError(
        "ehl_bearing.ross needs ROSS: pip install 'ehl_bearing[ross]' "
        "(ross-rotordynamics and plotly<7)"
    ) from _e

try:
    from ross.units import check_units as _check_units
except ImportError:  # pragma: no cover - older ROSS layouts

    def _check_units(func: Any) -> Any:
        return func


__all__ = [
    "OURS_TO_ROSS",
    "ROSS_DOFS",
    "ROSS_TABLE_COLUMNS",
    "BearingSite",
    "CaseLoadsWarning",
    "EhlBearingElement",
    "EhlRotor",
    "Unbalance",
    "damping_ratios",
    "friswell_bearing",
    "linearize_at_equilibrium",
    "node_dofs",
    "preload_offset",
    "read_ross_table",
    "rotor_model",
    "time_response",
    "to_ross_block",
    "two_disk_rotor",
    "unbalance_force",
]

#: Local ROSS index (x, y, z, α, β) of each of our DOFs x, y, z, θy, θz.
OURS_TO_ROSS = (2, 0, 1, 3, 4)
#: ROSS's local DOF names a bearing block covers, in its local order.
ROSS_DOFS = ("x", "y", "z", "alpha", "beta")

#: ROSS's names of a node's DOFs, in its order (``number_dof`` = 6).
ROSS_NODE_DOFS = ("x", "y", "z", "alpha", "beta", "theta")

Element = Union[_native.LawElement, _native.TrendForceElement]


class CaseLoadsWarning(UserWarning):
    """An :class:`EhlRotor` bearing whose coefficients are linearized at its case's loads (the
    characterization's operating point), not at the loads it carries in the rotor: use
    :func:`linearize_at_equilibrium`, or silence with
    ``warnings.simplefilter("ignore", CaseLoadsWarning)`` when the case's loads are the rotor's."""


def _calling_rotor(max_depth: int = 8) -> Any:
    """The first ROSS rotor (a ``self`` that is a ``ross.Rotor``) among the callers' frames, or
    None (called from user code)."""
    frame = sys._getframe(2) if hasattr(sys, "_getframe") else None
    depth = 0
    while frame is not None and depth < max_depth:
        obj = frame.f_locals.get("self")
        if isinstance(obj, rs.Rotor):
            return obj
        frame = frame.f_back
        depth += 1
    return None


def _refuse_plain_rotor(element: Any, rotor: Any) -> None:
    """Raise if ``rotor`` (a ROSS rotor assembling ``element``) is not an :class:`EhlRotor`."""
    if rotor is None or isinstance(rotor, EhlRotor):
        return
    raise TypeError(
        f"{type(rotor).__module__}.{type(rotor).__name__} given an EhlBearingElement (node "
        f"{element.n}, tag {element.tag!r}): a plain ROSS rotor keeps only the bearing's kxx, "
        "kxy, kyx, kyy, kzz and cxx, cxy, cyx, cyy, czz and would silently drop the rest of its "
        "5×5 block (the tilt stiffness and damping, the radial/tilt and axial/radial cross "
        "terms), which lowers or raises the natural frequencies. Build the rotor as "
        "ehl_bearing.ross.EhlRotor(shaft_elements, disk_elements, bearing_elements, ...) (same "
        "arguments), or with ehl_bearing.ross.linearize_at_equilibrium(...) to linearize the "
        "bearings at the rotor's own loads; for a deliberately 3-DOF bearing use "
        "element.ross_3dof() (a plain ross.BearingElement)."
    )


def mounting_signs(mounting: int) -> np.ndarray:
    """Signs of our x, y, z, θy, θz for ``mounting`` +1 (axial along +ROSS z) or −1 (mirrored)."""
    if mounting not in (1, -1):
        raise ValueError(f"mounting = {mounting}: expected +1 or -1")
    return np.array([1.0, 1.0, 1.0, 1.0, 1.0]) if mounting == 1 else np.array([-1.0, 1, 1, -1, -1])


def to_ross_block(matrix: Any, mounting: int = 1) -> np.ndarray:
    """Our 5×5 matrix (x, y, z, θy, θz; SI) as the 5×5 block in ROSS's local order
    (x, y, z, α, β) for a bearing with ``mounting`` (+1 or −1, see the module docstring)."""
    m = np.asarray(matrix, dtype=float)
    if m.shape != (5, 5):
        raise ValueError(f"expected a 5×5 matrix, got shape {m.shape}")
    s = mounting_signs(mounting)
    m = (s[:, None] * m) * s[None, :]
    out = np.zeros((5, 5))
    idx = np.array(OURS_TO_ROSS)
    out[np.ix_(idx, idx)] = m
    return out


def node_dofs(rotor: Any, node: int) -> list[int]:
    """Global indices of ROSS's x, y, z, α, β at ``node`` of ``rotor`` (ROSS numbers
    ``number_dof`` DOFs per node: x, y, z, α, β, θ)."""
    base = rotor.number_dof * node
    return [base + k for k in range(5)]


def _three_dof_terms(k5: np.ndarray, c5: np.ndarray) -> dict[str, Any]:
    """ROSS's 3-DOF bearing coefficients (kxx … czz, one value per speed) of our 5×5 blocks in
    ROSS axes, stacked over speeds (S, 5, 5)."""
    return dict(
        kxx=k5[:, 0, 0],
        kxy=k5[:, 0, 1],
        kyx=k5[:, 1, 0],
        kyy=k5[:, 1, 1],
        kzz=k5[:, 2, 2],
        cxx=c5[:, 0, 0],
        cxy=c5[:, 0, 1],
        cyx=c5[:, 1, 0],
        cyy=c5[:, 1, 1],
        czz=c5[:, 2, 2],
    )


class EhlBearingElement(rs.BearingElement):
    """A ROSS bearing element from our coefficients at node ``n``, with the full 5×5 block.

    Parameters
    ----------
    n : int
        Rotor node.
    coefficients : list of dict
        The output of :func:`ehl_bearing.coefficients` (one dict per speed; ``stiffness`` and
        ``damping`` in our order and SI, ``inner_speed_rad_s`` the rotor speed they belong to).
    mounting : int
        +1: our axial x along +ROSS z; −1: mirrored (x, θy, θz negated).
    use_dry : bool
        Use the dry Hertz stiffness of the coefficients (``dry_stiffness``, no damping) instead.
    tag : str, optional
        ROSS tag.

    As a ROSS ``BearingElement`` it carries ROSS's x, y, z terms (kxx, kxy, kyx, kyy, kzz, cxx,
    …, speed-dependent through ``frequency=`` when several speeds are given); ROSS rotors accept
    only 3-DOF bearings. The rest of the 5×5 block — tilt stiffness and damping (α, β), the
    x–y/tilt and axial/radial cross terms — is :meth:`K_extra`/:meth:`C_extra`, which
    :class:`EhlRotor` adds to the rotor's ``K(speed)``/``C(speed)`` at the node's x, y, z, α, β.
    :meth:`K5`/:meth:`C5` give the whole block. Between the given speeds the block is linearly
    interpolated in the rotor speed (ROSS's ``frequency``, rad/s), outside them held constant
    (:meth:`K`/:meth:`C`, ROSS's 3-DOF part, follow the same interpolation).

    Only an :class:`EhlRotor` may hold it: a plain ``ross.Rotor`` (which would drop the tilt and
    cross terms) raises ``TypeError`` when built with it or when it assembles it.

    ``linearized_at`` says where the coefficients were taken: ``"case loads"`` (the default:
    :func:`ehl_bearing.coefficients`, the equilibrium under the case's loads — an
    :class:`EhlRotor` warns, :class:`CaseLoadsWarning`) or ``"rotor equilibrium"`` (set by
    :func:`linearize_at_equilibrium`, which also sets ``operating_points``: per speed the
    bearing's displacement and reaction there).
    """

    def __init__(
        self,
        n: int,
        coefficients: Sequence[dict],
        mounting: int = 1,
        use_dry: bool = False,
        tag: Optional[str] = None,
        scale_factor: float = 1.0,
        color: str = "#355d7a",
        linearized_at: str = "case loads",
    ) -> None:
        if linearized_at not in ("case loads", "rotor equilibrium"):
            raise ValueError(
                f"linearized_at = {linearized_at!r}: expected 'case loads' or 'rotor equilibrium'"
            )
        rows = sorted(coefficients, key=lambda c: c["inner_speed_rad_s"])
        if not rows:
            raise ValueError("coefficients: at least one speed needed")
        self.linearized_at = linearized_at
        self.operating_points: Optional[list[dict]] = None
        freq = np.array([c["inner_speed_rad_s"] for c in rows], dtype=float)
        ks, cs = [], []
        for c in rows:
            k = c["dry_stiffness"] if use_dry else c["stiffness"]
            d = np.zeros((5, 5)) if use_dry else c["damping"]
            ks.append(to_ross_block(k, mounting))
            cs.append(to_ross_block(d, mounting))
        self._freq = freq
        self._k5 = np.array(ks)
        self._c5 = np.array(cs)
        self.mounting = mounting
        k5, c5 = self._k5, self._c5
        kw = _three_dof_terms(k5, c5)
        if len(freq) == 1:
            kw = {k: float(v[0]) for k, v in kw.items()}
            frequency = None
        else:
            frequency = freq
        super().__init__(
            n=n, frequency=frequency, tag=tag, scale_factor=scale_factor, color=color, **kw
        )

    # ROSS's Rotor sets ``dof_global_index`` on each element it is built with: the moment a
    # plain ross.Rotor takes this element, refused (it would drop the tilt and cross terms).
    @property
    def dof_global_index(self) -> Any:
        return self.__dict__.get("_dof_global_index")

    @dof_global_index.setter
    def dof_global_index(self, value: Any) -> None:
        if value is not None:
            _refuse_plain_rotor(self, _calling_rotor())
        self.__dict__["_dof_global_index"] = value

    @_check_units
    def K(self, frequency: Any) -> np.ndarray:
        """ROSS's 3-DOF stiffness [[kxx, kxy, 0], [kyx, kyy, 0], [0, 0, kzz]] at rotor speed
        ``frequency`` (rad/s), from :meth:`K5`. Assembled by a plain ``ross.Rotor``: raises
        ``TypeError`` (that rotor would drop the rest of the block)."""
        _refuse_plain_rotor(self, _calling_rotor())
        return _ross_3x3(self.K5(frequency))

    @_check_units
    def C(self, frequency: Any) -> np.ndarray:
        """ROSS's 3-DOF damping at rotor speed ``frequency`` (rad/s), from :meth:`C5`;
        refused by a plain ``ross.Rotor`` as :meth:`K`."""
        _refuse_plain_rotor(self, _calling_rotor())
        return _ross_3x3(self.C5(frequency))

    def ross_3dof(self, tag: Optional[str] = None) -> Any:
        """A plain ROSS ``BearingElement`` with only this bearing's 3-DOF terms (kxx, kxy, kyx,
        kyy, kzz, cxx, cxy, cyx, cyy, czz at the same speeds): for a deliberately 3-DOF model in
        a plain ``ross.Rotor`` (no tilt stiffness, no cross terms)."""
        k5, c5 = self._k5, self._c5
        kw = _three_dof_terms(k5, c5)
        if len(self._freq) == 1:
            return rs.BearingElement(n=self.n, tag=tag, **{k: float(v[0]) for k, v in kw.items()})
        return rs.BearingElement(n=self.n, frequency=self._freq, tag=tag, **kw)

    def _interp(self, table: np.ndarray, frequency: Any) -> np.ndarray:
        f = 0.0 if frequency is None else float(np.asarray(frequency, dtype=float).reshape(-1)[0])
        if len(self._freq) == 1:
            return table[0].copy()
        out = np.empty((5, 5))
        for i in range(5):
            for j in range(5):
                out[i, j] = np.interp(f, self._freq, table[:, i, j])
        return out

    def K5(self, frequency: Any = None) -> np.ndarray:
        """Whole stiffness block (5×5, ROSS order x, y, z, α, β; SI) at rotor speed
        ``frequency`` (rad/s)."""
        return self._interp(self._k5, frequency)

    def C5(self, frequency: Any = None) -> np.ndarray:
        """Whole damping block (5×5, ROSS order; SI) at rotor speed ``frequency`` (rad/s)."""
        return self._interp(self._c5, frequency)

    def K_extra(self, frequency: Any = None) -> np.ndarray:
        """:meth:`K5` minus the part ROSS's ``BearingElement.K`` places (kxx, kxy, kyx, kyy,
        kzz): what :class:`EhlRotor` adds at the node's x, y, z, α, β."""
        k = self.K5(frequency)
        k[:3, :3] -= _ross_3x3(k)
        return k

    def C_extra(self, frequency: Any = None) -> np.ndarray:
        """:meth:`C5` minus the part ROSS's ``BearingElement.C`` places."""
        c = self.C5(frequency)
        c[:3, :3] -= _ross_3x3(c)
        return c


def _ross_3x3(block: np.ndarray) -> np.ndarray:
    """The entries of a 5×5 block that ROSS's 3-DOF bearing matrix holds: [[xx, xy, 0],
    [yx, yy, 0], [0, 0, zz]]."""
    out = np.zeros((3, 3))
    out[:2, :2] = block[:2, :2]
    out[2, 2] = block[2, 2]
    return out


class EhlRotor(rs.Rotor):
    """A ROSS ``Rotor`` whose ``K(speed)`` and ``C(speed)`` include the full 5×5 blocks of its
    :class:`EhlBearingElement` bearings (ROSS's 3-DOF part plus ``K_extra``/``C_extra`` at the
    node's x, y, z, α, β). ROSS's analyses that assemble through ``rotor.K``/``rotor.C`` —
    ``run_modal``, ``run_critical_speed``, ``run_campbell``, ``run_unbalance_response``,
    ``run_freq_response``, ``run_time_response`` — then include the tilt terms. Built like a
    ``ross.Rotor`` (``EhlRotor(shaft_elements, disk_elements, bearing_elements)``), or by
    :func:`linearize_at_equilibrium` (bearings linearized at the rotor's own static equilibrium;
    ``linearization`` then holds, per speed, each bearing's loads and displacements there, and
    :meth:`linearization_table` prints them). Bearings linearized at their case's loads
    (``linearized_at == "case loads"``) raise a :class:`CaseLoadsWarning`.

    ROSS methods that build a new plain ``Rotor`` from this one's elements (``add_nodes``,
    ``convergence``) raise ``TypeError``: that rotor would drop the tilt and cross terms."""

    #: Per speed, where the bearings were linearized (set by :func:`linearize_at_equilibrium`).
    linearization: Optional[list] = None

    def __init__(self, shaft_elements: Any, *args: Any, **kwargs: Any) -> None:
        try:
            super().__init__(shaft_elements, *args, **kwargs)
        except ValueError as e:
            if "outside shaft" not in str(e):
                raise
            bearings = kwargs.get("bearing_elements", args[1] if len(args) > 1 else None) or []
            disks = kwargs.get("disk_elements", args[0] if args else None) or []
            shafts = list(_flatten(shaft_elements))
            last = max((sh.n if sh.n is not None else i) for i, sh in enumerate(shafts)) + 1
            bad = [
                f"{type(el).__name__} tag {el.tag!r} at node {el.n}"
                for el in [*bearings, *disks]
                if el.n > last
            ]
            raise ValueError(
                f"{'; '.join(bad) or 'an element'}: node outside the shaft, whose nodes are "
                f"0..{last} ({len(shafts)} shaft elements); ROSS: {e}"
            ) from e
        at_case = [
            f"node {b.n} ({b.tag})"
            for b in self.bearing_elements
            if isinstance(b, EhlBearingElement) and b.linearized_at == "case loads"
        ]
        if at_case:
            warnings.warn(
                "bearings at "
                + ", ".join(at_case)
                + ": their coefficients are linearized at their case's loads (the "
                "characterization's operating point), not at the loads they carry in this rotor "
                "(preload, gravity, shaft loads and tilts change them); "
                "ehl_bearing.ross.linearize_at_equilibrium linearizes them at the rotor's own "
                "static equilibrium",
                CaseLoadsWarning,
                stacklevel=2,
            )

    def linearization_table(self) -> str:
        """Where the bearings were linearized (after :func:`linearize_at_equilibrium`): per speed
        and bearing, the loads it carries (axial and radial force, N; moment, N·m) and its
        displacement (axial and radial, µm; tilt, mrad), in the bearing's own axes."""
        if not self.linearization:
            return "(not linearized at the rotor's equilibrium: no linearization record)"
        lines = [
            "| rpm | bearing (node, mounting) | axial load N | radial load N | moment N·m "
            "| axial µm | radial µm | tilt mrad |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for point in self.linearization:
            rpm = point["speed_rad_s"] * 30 / math.pi
            for b in point["bearings"]:
                r, q = b["reaction"], b["displacement"]
                lines.append(
                    f"| {rpm:.0f} | {b['node']}, {b['mounting']:+d} | {r[0]:.1f} "
                    f"| {math.hypot(r[1], r[2]):.1f} | {math.hypot(r[3], r[4]):.3f} "
                    f"| {1e6 * q[0]:.3f} | {1e6 * math.hypot(q[1], q[2]):.3f} "
                    f"| {1e3 * math.hypot(q[3], q[4]):.4f} |"
                )
        return "\n".join(lines)

    def _extra(self, which: str, frequency: Any) -> np.ndarray:
        n = self.ndof
        out = np.zeros((n, n))
        for elm in self.bearing_elements:
            if isinstance(elm, EhlBearingElement):
                d = node_dofs(self, elm.n)
                m = elm.K_extra(frequency) if which == "K" else elm.C_extra(frequency)
                out[np.ix_(d, d)] += m
        return out

    def K(self, frequency: Any) -> np.ndarray:
        """Stiffness matrix at ``frequency`` (rotor speed, rad/s) with the bearings' tilt terms."""
        return super().K(frequency) + self._extra("K", frequency)

    def C(self, frequency: Any) -> np.ndarray:
        """Damping matrix at ``frequency`` (rad/s) with the bearings' tilt terms."""
        return super().C(frequency) + self._extra("C", frequency)


def _flatten(items: Any) -> Any:
    for el in items:
        if isinstance(el, (list, tuple)):
            yield from _flatten(el)
        else:
            yield el


def friswell_bearing(
    n: int, case: _native.Case, radial_load_n: float, tag: Optional[str] = None
) -> Any:
    """ROSS's Friswell ball bearing (``ross.BallBearingElement``) for the bearing of ``case``
    under radial load ``radial_load_n`` (N): k from load, ball count, ball diameter and contact
    angle; c = 1.25e-5·k; no speed dependence, no tilt terms."""
    return rs.BallBearingElement(
        n=n,
        n_balls=case.ball_count,
        d_balls=case.ball_diameter_m,
        fs=radial_load_n,
        alpha=case.contact_angle_rad,
        tag=tag,
    )


def two_disk_rotor(
    bearing_0: Any,
    bearing_1: Any,
    shaft_diameter_m: float = 0.030,
    length_m: float = 0.5,
    elements: int = 6,
    disk_nodes: Sequence[int] = (2, 4),
    disk_outer_diameter_m: float = 0.15,
    disk_width_m: float = 0.03,
    young_pa: float = 211e9,
) -> Any:
    """The example rotor: a steel shaft (diameter ``shaft_diameter_m`` — the 7006's bore —,
    length ``length_m``, ``elements`` Timoshenko elements with gyroscopic terms) with two steel
    disks (``disk_outer_diameter_m`` × ``disk_width_m``) at ``disk_nodes`` and the bearing elements
    ``bearing_0``/``bearing_1`` (already built for nodes 0 and ``elements``). ``young_pa`` sets the
    shaft's modulus (a very large value makes it rigid, for tests)."""
    steel = rs.Material(name="steel_ehl", rho=7810.0, E=young_pa, G_s=young_pa / 2.6)
    disk_steel = rs.Material(name="steel_disk", rho=7810.0, E=211e9, G_s=81.2e9)
    le = length_m / elements
    shaft = [
        rs.ShaftElement(
            L=le,
            idl=0.0,
            odl=shaft_diameter_m,
            material=steel,
            shear_effects=True,
            rotary_inertia=True,
            gyroscopic=True,
        )
        for _ in range(elements)
    ]
    disks = [
        rs.DiskElement.from_geometry(
            n=k,
            material=disk_steel,
            width=disk_width_m,
            i_d=shaft_diameter_m,
            o_d=disk_outer_diameter_m,
        )
        for k in disk_nodes
    ]
    return EhlRotor(shaft, disks, [bearing_0, bearing_1])


@dataclass
class BearingSite:
    """One of our force elements at a rotor node, for :func:`time_response`,
    :func:`rotor_model` and :func:`linearize_at_equilibrium`.

    ``offset_m`` is the bearing's ring displacement (our x, y, z in m, θy, θz in rad, in the
    bearing's own frame) when the rotor DOFs are zero: the mounted preload. None (the default)
    takes it from the element's equilibrium (:func:`preload_offset`: ``(x0, 0, 0, 0, 0)``, x0
    the axial approach of the element under the loads of ``case``, default the element's own
    case); give ``(0, 0, 0, 0, 0)`` for bearings without preload. ``mounting``: +1 or −1
    (module docstring).
    """

    element: Element
    node: int
    mounting: int = 1
    offset_m: Optional[Sequence[float]] = None
    case: Optional[_native.Case] = None

    def offset(self) -> tuple:
        """The offset used (m, m, m, rad, rad): ``offset_m``, or the preload from the element's
        equilibrium (:func:`preload_offset`)."""
        if self.offset_m is not None:
            o = tuple(float(x) for x in self.offset_m)
            if len(o) != 5:
                raise ValueError(
                    f"BearingSite at node {self.node}: offset_m has {len(o)} values; 5 expected "
                    "(x, y, z in m, θy, θz in rad)"
                )
            return o
        return preload_offset(self.element, self.case)


def preload_offset(element: Element, case: Optional[_native.Case] = None) -> tuple:
    """The mounted preload of ``element`` as a ring offset ``(x0, 0, 0, 0, 0)`` (m): x0 is the
    axial approach of the element's equilibrium under the loads of ``case`` (default: the case
    the element was built for, ``element.case``; a ``TrendForceElement`` has none — pass one).
    With the bearings of a back-to-back pair each given this offset in its own frame, the pair
    clamps the shaft with about the case's axial load (less where the radial loads and tilts of
    the rotor unload it; :func:`linearize_at_equilibrium` reports the loads it carries)."""
    if case is None:
        case = getattr(element, "case", None)
    if case is None:
        raise ValueError(
            f"{element!r} carries no case to take the preload offset from: give the "
            "BearingSite offset_m=(x0, 0, 0, 0, 0) (m; e.g. x0 = element.equilibrium(case)[0][0]) "
            "or case=... (a Case whose loads set the preload)"
        )
    q, _, _ = element.equilibrium(case)
    return (float(q[0]), 0.0, 0.0, 0.0, 0.0)


@dataclass
class Unbalance:
    """Unbalance ``mass_eccentricity_kg_m`` (kg·m) at ``node``, phase ``phase_rad`` (rad) from
    ROSS x toward ROSS y at rotation angle zero."""

    node: int
    mass_eccentricity_kg_m: float
    phase_rad: float = 0.0


def rotor_model(
    rotor: Any,
    bearings: Sequence[BearingSite],
    unbalances: Sequence[Unbalance] = (),
    gravity: bool = True,
    extra_force_n: Optional[np.ndarray] = None,
) -> Any:
    """The native ``RotorModel`` of ``rotor`` (ROSS's M0, C0, G0, K0: the matrices without any
    bearing element) with our force elements at the bearing sites, the unbalances and the
    constant force (gravity along −ROSS y from ROSS's ``gravitational_force`` with the rotor's
    mass matrix, plus ``extra_force_n``). Each site's offset is :meth:`BearingSite.offset` (the
    element's preload unless ``offset_m`` is given); a site or unbalance at a node the rotor does
    not have raises ``ValueError`` naming it and the node range. ROSS bearing elements of
    ``rotor`` other than ours are not part of M0, C0, K0: a ``UserWarning`` names them
    (:func:`linearize_at_equilibrium` includes them at each speed)."""
    return _rotor_model(rotor, bearings, unbalances, gravity, extra_force_n)


def _check_node(rotor: Any, node: Any, what: str) -> None:
    nodes = list(rotor.nodes)
    if not isinstance(node, (int, np.integer)) or int(node) not in nodes:
        raise ValueError(
            f"{what}: node = {node!r}; the rotor's nodes are {nodes[0]}..{nodes[-1]} "
            f"({len(rotor.shaft_elements)} shaft elements)"
        )


def _rotor_model(
    rotor: Any,
    bearings: Sequence[BearingSite],
    unbalances: Sequence[Unbalance],
    gravity: bool,
    extra_force_n: Optional[np.ndarray],
    speed_rad_s: Optional[float] = None,
) -> Any:
    """:func:`rotor_model`; with ``speed_rad_s`` the matrices include the rotor's own ROSS
    bearing elements (``rotor.M/K/C`` at that speed) instead of ROSS's M0, C0, K0."""
    for i, b in enumerate(bearings):
        what = f"bearing {i} ({b.element!r}, mounting {b.mounting})"
        _check_node(rotor, b.node, what)
        if b.mounting not in (1, -1):
            raise ValueError(f"{what}: mounting = {b.mounting}; expected +1 or -1")
    for i, u in enumerate(unbalances):
        _check_node(rotor, u.node, f"unbalance {i} ({u.mass_eccentricity_kg_m} kg·m)")
    if speed_rad_s is None:
        m, c, k = rotor.M0, rotor.C0, rotor.K0
        others = [b for b in rotor.bearing_elements if not isinstance(b, EhlBearingElement)]
        if others:
            warnings.warn(
                "the rotor's ROSS bearing elements "
                + ", ".join(f"{b.tag!r} (node {b.n})" for b in others)
                + " are not in this nonlinear model (ROSS's M0, C0, K0 leave all bearing "
                "elements out): only the BearingSite force elements hold the rotor",
                UserWarning,
                stacklevel=3,
            )
    else:
        m, c, k = rotor.M(speed_rad_s), rotor.C(speed_rad_s), rotor.K(speed_rad_s)
    m = np.asarray(m, dtype=float)
    n = m.shape[0]
    force = np.zeros(n)
    if gravity:
        force += np.asarray(
            rotor.gravitational_force(M=np.asarray(rotor.M0), num_dof=rotor.number_dof),
            dtype=float,
        )
    if extra_force_n is not None:
        extra = np.asarray(extra_force_n, dtype=float)
        if extra.shape != (n,):
            raise ValueError(
                f"extra_force_n: shape {extra.shape}; ({n},) expected (one force per rotor DOF, "
                "N or N·m; node_dofs(rotor, node) gives a node's x, y, z, α, β)"
            )
        force += extra
    model = _native.RotorModel(
        mass=m,
        damping=np.asarray(c, dtype=float),
        gyroscopic=np.asarray(rotor.G0, dtype=float),
        stiffness=np.asarray(k, dtype=float),
        constant_force=force,
    )
    for b in bearings:
        d = node_dofs(rotor, b.node)
        dofs = [d[OURS_TO_ROSS[k]] for k in range(5)]
        model.add_bearing(
            b.element,
            dofs=list(dofs),
            signs=list(mounting_signs(b.mounting)),
            offset=list(b.offset()),
        )
    for u in unbalances:
        d = node_dofs(rotor, u.node)
        model.add_unbalance(
            dofs=(d[0], d[1]),
            mass_eccentricity_kg_m=u.mass_eccentricity_kg_m,
            phase_rad=u.phase_rad,
        )
    return model


def time_response(
    rotor: Any,
    bearings: Sequence[BearingSite],
    unbalances: Sequence[Unbalance] = (),
    *,
    speed_rad_s: Optional[float] = None,
    ramp_rad_s: Optional[tuple[float, float, float]] = None,
    step_s: float,
    duration_s: float,
    record_every: int = 1,
    record_dofs: Optional[Sequence[int]] = None,
    coupling: str = "implicit",
    cage_angle_rad: Optional[float] = None,
    gravity: bool = True,
    extra_force_n: Optional[np.ndarray] = None,
    progress: Optional[Callable[[int, int, float], Any]] = None,
    start_displacement: Optional[np.ndarray] = None,
    start_velocity: Optional[np.ndarray] = None,
) -> dict:
    """Nonlinear time response of ``rotor`` on our bearings (the Rust integrator).

    Constant speed ``speed_rad_s`` or a run-up ``ramp_rad_s = (start, end, duration_s)``
    (rad/s, rad/s, s; then constant). ``coupling``: ``"implicit"`` (bearing forces at the new
    time, Newton on the bearing DOFs) or ``"lagged"`` (the previous step's forces, as ROSS's
    ``add_to_RHS``). ``cage_angle_rad``: None lets the cages roll (ball passes at Z·f_cage), a
    number holds them. Each rolling cage turns at its bearing's operating cage speed (the
    load-weighted mean orbital speed of its balls; recorded as ``cage_speed_rad_s``). A
    ``LawElement`` with laws per contact (``law_element()``) keeps each ball's law, fitted at that
    ball's position in the case: a rolling cage would carry the laws around and excite the cage
    frequency, an artifact — hold its cages, or build it by load (``law_element(by_load=True)``:
    every ball takes the law of the load it carries), which rolls correctly, as do dry Hertz and
    a ``TrendForceElement``. Starts from the static equilibrium at the initial speed, or
    from ``start_displacement`` and ``start_velocity`` ((ndof,), ROSS's global DOFs, SI; e.g.
    the static equilibrium plus a linear steady orbit). Constant loads: gravity
    (``gravity=True``) and ``extra_force_n`` (n,).

    Returns :meth:`ehl_bearing.RotorModel.simulate`'s dict (``time_s``, ``speed_rad_s``,
    ``displacement`` over ROSS's global DOFs ``record_dofs``, ``bearing_reaction``,
    ``breakdown``, …) with the ``model`` added.
    """
    if speed_rad_s is None and ramp_rad_s is None:
        raise ValueError(
            "time_response: no shaft speed given: pass speed_rad_s (constant speed, rad/s) or "
            "ramp_rad_s = (start_rad_s, end_rad_s, duration_s) (a run-up)"
        )
    if speed_rad_s is not None and ramp_rad_s is not None:
        raise ValueError(
            f"time_response: both speed_rad_s = {speed_rad_s} and ramp_rad_s = {ramp_rad_s} "
            "given: pass one of them (speed_rad_s for a constant speed, ramp_rad_s for a run-up)"
        )
    _check_supported(rotor, bearings)
    model = rotor_model(rotor, bearings, unbalances, gravity=gravity, extra_force_n=extra_force_n)
    try:
        out = model.simulate(
            step_s=step_s,
            duration_s=duration_s,
            speed_rad_s=speed_rad_s,
            ramp=ramp_rad_s,
            record_every=record_every,
            record_dofs=None if record_dofs is None else list(record_dofs),
            coupling=coupling,
            cage_angle_rad=cage_angle_rad,
            start_displacement=_real_vector(start_displacement),
            start_velocity=_real_vector(start_velocity),
            progress=progress,
        )
    except _native.EhlBearingError as e:
        raise _native.EhlBearingError(_name_dofs(rotor, bearings, str(e))) from e
    out["model"] = model
    return out


def _real_vector(v: Optional[np.ndarray]) -> Optional[np.ndarray]:
    return None if v is None else np.ascontiguousarray(np.real(v), dtype=float)


def _check_supported(rotor: Any, bearings: Sequence[BearingSite]) -> None:
    """A rotor needs bearings: refuse none, naming the cause."""
    if not bearings:
        raise ValueError(
            "no bearing sites: nothing holds the rotor (gravity and the loads would move it "
            "as a rigid body, so it has no static equilibrium); give BearingSite(element, node, "
            f"mounting) for its bearings (nodes {rotor.nodes[0]}..{rotor.nodes[-1]})"
        )


def _name_dofs(rotor: Any, bearings: Sequence[BearingSite], message: str) -> str:
    """``message`` with the rotor DOF indices it lists named as ROSS node DOFs, and the bearing
    nodes."""
    nd = rotor.number_dof

    def name(i: int) -> str:
        return f"node {i // nd} {ROSS_NODE_DOFS[i % nd] if nd == 6 else i % nd}"

    named = re.sub(
        r"rotor DOFs \[([0-9, ]*)\]",
        lambda m: (
            "rotor DOFs "
            + ", ".join(f"{i.strip()} = {name(int(i))}" for i in m.group(1).split(",") if i.strip())
        ),
        message,
    )
    if named != message:
        where = ", ".join(f"node {b.node} (mounting {b.mounting:+d})" for b in bearings)
        named += f" [bearings at: {where or 'none'}]"
    return named


def unbalance_force(
    rotor: Any, unbalances: Sequence[Unbalance], time_s: np.ndarray, speed_rad_s: float
) -> np.ndarray:
    """The unbalance forces at constant speed over ``time_s`` as ROSS's force array
    (len(time_s), ndof): m·e·Ω²·(cos φ, sin φ) on the node's x and y, φ = Ω·t + phase — the
    same convention as :class:`Unbalance` in the Rust integrator."""
    f = np.zeros((len(time_s), rotor.ndof))
    for u in unbalances:
        d = node_dofs(rotor, u.node)
        phi = speed_rad_s * np.asarray(time_s) + u.phase_rad
        amp = u.mass_eccentricity_kg_m * speed_rad_s**2
        f[:, d[0]] += amp * np.cos(phi)
        f[:, d[1]] += amp * np.sin(phi)
    return f


def damping_ratios(rotor: Any, speed_rad_s: float, modes: int = 6) -> tuple:
    """Natural frequencies (Hz, damped) and damping ratios of the first ``modes`` modes of
    ``rotor`` at ``speed_rad_s`` from ROSS's ``run_modal`` (rigid-body torsion excluded)."""
    modal = rotor.run_modal(speed=speed_rad_s, num_modes=2 * modes + 4)
    wd = np.asarray(modal.wd, dtype=float)
    zeta = np.asarray(modal.log_dec, dtype=float) / np.sqrt(
        4 * math.pi**2 + np.asarray(modal.log_dec, dtype=float) ** 2
    )
    keep = wd > 1.0
    return wd[keep][:modes] / (2 * math.pi), zeta[keep][:modes]


def linearize_at_equilibrium(
    rotor: Any,
    sites: Union[Sequence[BearingSite], Callable[[float], Sequence[BearingSite]]],
    speeds_rad_s: Union[float, Sequence[float]],
    *,
    gravity: bool = True,
    extra_force_n: Optional[np.ndarray] = None,
) -> EhlRotor:
    """``rotor`` on our bearings ``sites``, linearized at its own static equilibrium.

    ``rotor``: a ROSS rotor without our bearings (``ross.Rotor(shaft_elements, disk_elements)``;
    other ROSS bearing or seal elements it holds stay and count in the equilibrium). ``sites``:
    our force elements at their nodes (:class:`BearingSite`; the preload offset defaults to the
    element's equilibrium), or a function of the speed (rad/s) returning them (e.g. fitted laws
    per speed). At each speed in ``speeds_rad_s`` (rad/s) the native ``RotorModel`` solves the
    static equilibrium of the rotor on the bearings' nonlinear forces under the preloads, gravity
    (``gravity=True``) and ``extra_force_n`` ((ndof,), N and N·m at ROSS's global DOFs), and takes
    each bearing's 5×5 stiffness and damping there: the loads, tilts and coefficients are
    consistent (Newton to a relative force residual of 1e-10, no fixed-point iteration left).

    Returns an :class:`EhlRotor` with the same shaft, disks and point masses and one
    :class:`EhlBearingElement` per site (``linearized_at = "rotor equilibrium"``; between speeds
    linearly interpolated). ``rotor.linearization``: per speed a dict with ``speed_rad_s``,
    ``iterations``, ``residual_n`` and ``bearings`` (per site: ``node``, ``mounting``,
    ``offset_m``, ``displacement`` and ``reaction`` in the bearing's axes — m, rad, N, N·m —,
    ``stiffness``, ``damping``); ``rotor.linearization_table()`` prints them. Raises
    ``EhlBearingError`` (with the cause) if there is no equilibrium.
    """
    if any(isinstance(b, EhlBearingElement) for b in rotor.bearing_elements):
        raise ValueError(
            "linearize_at_equilibrium: rotor already holds EhlBearingElement(s) at nodes "
            + ", ".join(
                str(b.n) for b in rotor.bearing_elements if isinstance(b, EhlBearingElement)
            )
            + "; pass the rotor without our bearings (they come from sites)"
        )
    speeds = [float(w) for w in np.atleast_1d(np.asarray(speeds_rad_s, dtype=float))]
    if not speeds or any(not math.isfinite(w) or w < 0 for w in speeds):
        raise ValueError(f"speeds_rad_s = {speeds_rad_s!r}: expected finite speeds ≥ 0 (rad/s)")
    record: list[dict] = []
    per_site: Optional[list[list[dict]]] = None
    first_sites: Optional[Sequence[BearingSite]] = None
    for w in sorted(speeds):
        at_w = list(sites(w) if callable(sites) else sites)
        _check_supported(rotor, at_w)
        if first_sites is None:
            first_sites = at_w
            per_site = [[] for _ in at_w]
        elif [(b.node, b.mounting) for b in at_w] != [(b.node, b.mounting) for b in first_sites]:
            raise ValueError(
                f"sites at {w} rad/s: nodes and mountings "
                f"{[(b.node, b.mounting) for b in at_w]} differ from those at the first speed "
                f"{[(b.node, b.mounting) for b in first_sites]}"
            )
        model = _rotor_model(rotor, at_w, (), gravity, extra_force_n, speed_rad_s=w)
        try:
            st = model.static_equilibrium(w)
        except _native.EhlBearingError as e:
            raise _native.EhlBearingError(_name_dofs(rotor, at_w, str(e))) from e
        bearings = []
        assert per_site is not None
        for i, b in enumerate(at_w):
            k = np.asarray(st["bearing_stiffness"][i])
            c = np.asarray(st["bearing_damping"][i])
            per_site[i].append(
                {"inner_speed_rad_s": w, "stiffness": k, "damping": c, "dry_stiffness": k}
            )
            bearings.append(
                {
                    "node": b.node,
                    "mounting": b.mounting,
                    "offset_m": b.offset(),
                    "displacement": np.asarray(st["bearing_displacement"][i]),
                    "reaction": np.asarray(st["reactions"][i]),
                    "stiffness": k,
                    "damping": c,
                }
            )
        record.append(
            {
                "speed_rad_s": w,
                "iterations": st["iterations"],
                "residual_n": st["residual_n"],
                "bearings": bearings,
            }
        )
    assert first_sites is not None and per_site is not None
    elements = []
    for i, b in enumerate(first_sites):
        el = EhlBearingElement(
            b.node,
            per_site[i],
            mounting=b.mounting,
            tag=f"EHL bearing {i} (node {b.node})",
            linearized_at="rotor equilibrium",
        )
        el.operating_points = [
            {"speed_rad_s": p["speed_rad_s"], **p["bearings"][i]} for p in record
        ]
        elements.append(el)
    out = EhlRotor(
        rotor.shaft_elements,
        rotor.disk_elements,
        [*rotor.bearing_elements, *elements],
        rotor.point_mass_elements,
        min_w=rotor.min_w,
        max_w=rotor.max_w,
        rated_w=rotor.rated_w,
        tag=rotor.tag,
    )
    out.linearization = record
    return out


#: The columns of ``ross_bearing.csv`` (:func:`ehl_bearing.ross_table_csv`, the CLI's
#: ``coefficients -o DIR``): rotor speed ``frequency`` in rad/s, then stiffness (N/m) and damping
#: (N·s/m) in ROSS's axes.
ROSS_TABLE_COLUMNS = (
    "frequency",
    "kxx",
    "kxy",
    "kyx",
    "kyy",
    "cxx",
    "cxy",
    "cyx",
    "cyy",
    "kzz",
    "czz",
)


def read_ross_table(
    path_or_text: Union[str, os.PathLike],
    n: int,
    tag: Optional[str] = None,
    **kwargs: Any,
) -> Any:
    """A ROSS ``BearingElement`` at node ``n`` from a ``ross_bearing.csv`` table (path, or the
    CSV text as :func:`ehl_bearing.ross_table_csv` returns it; ROSS's own
    ``BearingElement.from_table`` reads Excel files only). Columns :data:`ROSS_TABLE_COLUMNS`,
    any order, a row per rotor speed (``frequency``, rad/s, increasing); ``kwargs`` go to
    ``ross.BearingElement`` (e.g. ``n_link``, ``scale_factor``).

    The table holds ROSS's 3-DOF terms only (x, y, z): the element is a plain
    ``ross.BearingElement``, without the tilt stiffness and the cross terms of our 5×5 block
    (those are in ``coefficients.json``; :class:`EhlBearingElement` carries them).
    """
    if isinstance(path_or_text, str) and "\n" in path_or_text:
        source, content = "<text>", path_or_text
    else:
        source = os.fspath(path_or_text)
        with open(source, newline="") as fh:
            content = fh.read()
    rows = list(csv.reader(io.StringIO(content)))
    rows = [r for r in rows if any(cell.strip() for cell in r)]
    if not rows:
        raise ValueError(f"{source}: empty; expected a header {','.join(ROSS_TABLE_COLUMNS)}")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in ROSS_TABLE_COLUMNS if c not in header]
    if missing:
        raise ValueError(
            f"{source}: header {header} lacks column(s) {missing}; expected "
            f"{','.join(ROSS_TABLE_COLUMNS)} (the ross_bearing.csv of `ehl-bearing coefficients "
            "-o DIR` or ehl_bearing.ross_table_csv)"
        )
    if len(rows) < 2:
        raise ValueError(f"{source}: no data rows below the header")
    cols: dict[str, list[float]] = {c: [] for c in ROSS_TABLE_COLUMNS}
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise ValueError(f"{source}, row {line}: {len(row)} cells; {len(header)} expected")
        for c in ROSS_TABLE_COLUMNS:
            cell = row[header.index(c)].strip()
            try:
                v = float(cell)
            except ValueError:
                v = math.nan
            if not math.isfinite(v):
                raise ValueError(f"{source}, row {line}: {c} = {cell!r}; expected a finite number")
            cols[c].append(v)
    freq = np.array(cols["frequency"])
    if np.any(freq < 0) or np.any(np.diff(freq) <= 0):
        raise ValueError(
            f"{source}: frequency = {freq.tolist()} rad/s; expected speeds ≥ 0, increasing"
        )
    coef = {c: np.array(cols[c]) for c in ROSS_TABLE_COLUMNS if c != "frequency"}
    if len(freq) == 1:
        return rs.BearingElement(
            n=n, tag=tag, **{c: float(v[0]) for c, v in coef.items()}, **kwargs
        )
    return rs.BearingElement(n=n, frequency=freq, tag=tag, **coef, **kwargs)
