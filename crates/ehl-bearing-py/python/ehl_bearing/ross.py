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
``run_unbalance_response`` and ROSS's linear time response all see them.

Nonlinear time response (:func:`time_response`): the rotor's M, C, G, K without bearings (ROSS's
``M0``, ``C0``, ``G0``, ``K0``) go to the Rust integrator (``ehl_bearing.RotorModel``) with our
force elements at the bearing nodes, unbalances, gravity and the cage angle advancing with the
cage speed. ROSS's equation of motion is ``M q̈ + (C + Ω G) q̇ + K q = F``; the integrator uses
the same ``D(Ω) = C + Ω·G``. ROSS's run-up term ``Ω̇·Ksdt·q`` is not included (small for the
run-ups here: Ω̇ ≈ 20 rad/s²).
"""

from __future__ import annotations

import math
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

__all__ = [
    "OURS_TO_ROSS",
    "ROSS_DOFS",
    "BearingSite",
    "EhlBearingElement",
    "EhlRotor",
    "Unbalance",
    "damping_ratios",
    "friswell_bearing",
    "node_dofs",
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

Element = Union[_native.LawElement, _native.TrendForceElement]


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
    interpolated in the rotor speed (ROSS's ``frequency``, rad/s), outside them held constant.
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
    ) -> None:
        rows = sorted(coefficients, key=lambda c: c["inner_speed_rad_s"])
        if not rows:
            raise ValueError("coefficients: at least one speed needed")
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
        kw: dict[str, Any] = dict(
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
        if len(freq) == 1:
            kw = {k: float(v[0]) for k, v in kw.items()}
            frequency = None
        else:
            frequency = freq
        super().__init__(
            n=n, frequency=frequency, tag=tag, scale_factor=scale_factor, color=color, **kw
        )

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
    ``ross.Rotor`` (``EhlRotor(shaft_elements, disk_elements, bearing_elements)``)."""

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
    """One of our force elements at a rotor node, for :func:`time_response`.

    ``offset_m`` is the bearing's ring displacement (our x, y, z in m, θy, θz in rad, in the
    bearing's own frame) when the rotor DOFs are zero: e.g. the axial preload approach
    ``[x0, 0, 0, 0, 0]``. ``mounting``: +1 or −1 (module docstring).
    """

    element: Element
    node: int
    mounting: int = 1
    offset_m: Sequence[float] = (0.0, 0.0, 0.0, 0.0, 0.0)


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
    mass matrix, plus ``extra_force_n``)."""
    m = np.asarray(rotor.M0, dtype=float)
    n = m.shape[0]
    force = np.zeros(n)
    if gravity:
        force += np.asarray(rotor.gravitational_force(M=m, num_dof=rotor.number_dof), dtype=float)
    if extra_force_n is not None:
        force += np.asarray(extra_force_n, dtype=float)
    model = _native.RotorModel(
        mass=m,
        damping=np.asarray(rotor.C0, dtype=float),
        gyroscopic=np.asarray(rotor.G0, dtype=float),
        stiffness=np.asarray(rotor.K0, dtype=float),
        constant_force=force,
    )
    for b in bearings:
        d = node_dofs(rotor, b.node)
        dofs = [d[OURS_TO_ROSS[k]] for k in range(5)]
        model.add_bearing(
            b.element,
            dofs=list(dofs),
            signs=list(mounting_signs(b.mounting)),
            offset=[float(x) for x in b.offset_m],
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
) -> dict:
    """Nonlinear time response of ``rotor`` on our bearings (the Rust integrator).

    Constant speed ``speed_rad_s`` or a run-up ``ramp_rad_s = (start, end, duration_s)``
    (rad/s, rad/s, s; then constant). ``coupling``: ``"implicit"`` (bearing forces at the new
    time, Newton on the bearing DOFs) or ``"lagged"`` (the previous step's forces, as ROSS's
    ``add_to_RHS``). ``cage_angle_rad``: None lets the cages roll (ball passes at Z·f_cage), a
    number holds them — hold them with fitted laws (a ``LawElement`` from a characterization
    keeps each ball's law, fitted at that ball's position in the case: a rolling cage would carry
    the laws around and excite the cage frequency, an artifact); ball-pass studies with dry Hertz
    or a ``TrendForceElement``. Starts from the static equilibrium at the initial speed.
    Constant loads: gravity (``gravity=True``) and ``extra_force_n`` (n,).

    Returns :meth:`ehl_bearing.RotorModel.simulate`'s dict (``time_s``, ``speed_rad_s``,
    ``displacement`` over ROSS's global DOFs ``record_dofs``, ``bearing_reaction``,
    ``breakdown``, …) with the ``model`` added.
    """
    model = rotor_model(rotor, bearings, unbalances, gravity=gravity, extra_force_n=extra_force_n)
    out = model.simulate(
        step_s=step_s,
        duration_s=duration_s,
        speed_rad_s=speed_rad_s,
        ramp=ramp_rad_s,
        record_every=record_every,
        record_dofs=None if record_dofs is None else list(record_dofs),
        coupling=coupling,
        cage_angle_rad=cage_angle_rad,
        progress=progress,
    )
    out["model"] = model
    return out


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
