"""The ROSS bridge's linear part: our 5×5 block in ROSS rotors, Friswell's bearing beside it."""

from __future__ import annotations

import numpy as np
import pytest

import ehl_bearing as eb

rs = pytest.importorskip("ross")
er = pytest.importorskip("ehl_bearing.ross")

# These tests check the block placement of coefficients at the case's loads (on purpose).
pytestmark = pytest.mark.filterwarnings("ignore::ehl_bearing.ross.CaseLoadsWarning")


@pytest.fixture(scope="module")
def dry(case):
    """Dry Hertz coefficients of the seed case at 3000 and 5000 rpm, and its element."""
    el = eb.LawElement.hertz(case)
    return el, eb.coefficients(case, [3000.0, 5000.0], element=el)


def _ours_to_ross_by_hand(m):
    """Our (x, y, z, θy, θz) matrix in ROSS order (x, y, z, α, β), written out entry by entry:
    ROSS x ← our y, y ← our z, z ← our x, α ← θy, β ← θz."""
    ours = {"x": 1, "y": 2, "z": 0, "a": 3, "b": 4}
    names = ["x", "y", "z", "a", "b"]
    return np.array([[m[ours[r]][ours[c]] for c in names] for r in names])


def test_rotor_matrices_contain_the_block_at_the_node(case, dry):
    _, co = dry
    b0 = er.EhlBearingElement(0, co, mounting=1)
    b1 = er.EhlBearingElement(6, co, mounting=-1)
    rotor = er.two_disk_rotor(b0, b1)
    w = co[1]["inner_speed_rad_s"]
    k = rotor.K(w) - rotor.K0
    c = rotor.C(w) - rotor.C0
    want0 = _ours_to_ross_by_hand(co[1]["stiffness"])
    s = np.array([1, 1, -1, -1, -1.0])  # mirrored: our x (ROSS z), θy (α), θz (β) negated
    want1 = s[:, None] * _ours_to_ross_by_hand(co[1]["stiffness"]) * s[None, :]
    d0, d1 = er.node_dofs(rotor, 0), er.node_dofs(rotor, 6)
    np.testing.assert_allclose(k[np.ix_(d0, d0)], want0, rtol=1e-12)
    np.testing.assert_allclose(k[np.ix_(d1, d1)], want1, rtol=1e-12)
    assert np.count_nonzero(k) == np.count_nonzero(want0) + np.count_nonzero(want1)
    assert np.all(c == 0)  # dry Hertz: no damping
    # Speed dependence: midway between the two speeds the block is the mean (linear).
    mid = 0.5 * (co[0]["inner_speed_rad_s"] + w)
    mean = 0.5 * (_ours_to_ross_by_hand(co[0]["stiffness"]) + want0)
    np.testing.assert_allclose(b0.K5(mid), mean, rtol=1e-12)
    # ROSS's own 3×3 part equals our y/z/x terms (kxx = K_yy, kyy = K_zz, kzz = K_xx).
    k3 = b0.K(w)
    np.testing.assert_allclose(
        [k3[0, 0], k3[1, 1], k3[2, 2], k3[0, 1]],
        [
            co[1]["stiffness"][1][1],
            co[1]["stiffness"][2][2],
            co[1]["stiffness"][0][0],
            co[1]["stiffness"][1][2],
        ],
        rtol=1e-12,
    )


def test_rigid_rotor_under_a_moment_deflects_as_the_closed_form(case, dry):
    """One bearing at node 0 of a rigid shaft; a moment M about ROSS α at the free end (node
    3, L = 0.3 m). The shaft transmits the pure moment, so the bearing's ring displacement is
    K⁻¹·(0, 0, 0, M, 0) in our axes, and the free end follows as a rigid body: x₃ = x₀ + L·β₀,
    y₃ = y₀ − L·α₀ (rotations about x and y, right-handed, z axial)."""
    _, co = dry
    b = er.EhlBearingElement(0, co[1:], mounting=1)
    steel = rs.Material(name="rigid", rho=7810.0, E=211e15, G_s=81e15)  # 1e6 × steel: rigid
    length = 0.3
    shaft = [rs.ShaftElement(L=length / 3, idl=0.0, odl=0.03, material=steel) for _ in range(3)]
    rotor = er.EhlRotor(shaft, [], [b])
    w = co[1]["inner_speed_rad_s"]
    k = rotor.K(w)
    moment = 5.0  # N·m
    f = np.zeros(rotor.ndof)
    f[er.node_dofs(rotor, 3)[3]] = moment
    free = [i for i in range(rotor.ndof) if i % rotor.number_dof != 5]  # no torsion (θ)
    q = np.zeros(rotor.ndof)
    q[free] = np.linalg.solve(k[np.ix_(free, free)], f[free])
    k_ours = np.array(co[1]["stiffness"])
    qo = np.linalg.solve(k_ours, [0, 0, 0, moment, 0])  # x, y, z, θy, θz
    x0, y0, z0, a0, b0 = q[er.node_dofs(rotor, 0)]
    # Tolerance 1e-6: the shaft is 1e6 times stiffer than steel.
    np.testing.assert_allclose(
        [x0, y0, z0, a0, b0],
        [qo[1], qo[2], qo[0], qo[3], qo[4]],
        rtol=1e-5,
        atol=1e-6 * np.abs(qo).max(),
    )
    x3, y3, _, a3, b3 = q[er.node_dofs(rotor, 3)]
    assert a3 == pytest.approx(a0, rel=1e-5) and b3 == pytest.approx(b0, rel=1e-5)
    assert x3 == pytest.approx(x0 + length * b0, rel=1e-5, abs=1e-6 * abs(length * a0))
    assert y3 == pytest.approx(y0 - length * a0, rel=1e-5)
    # The radial/tilt cross terms matter: the tilt is several times M/K_θyθy (without them).
    assert abs(a0) > 2 * moment / k_ours[3][3]


def test_friswell_bearing(case):
    fr = er.friswell_bearing(0, case, radial_load_n=1414.0)
    k = fr.K(0)
    # ROSS's Friswell formula: kyy (vertical) = 1.0e6·n^(2/3)·d^(1/3)·Fs^(1/3)·cos(α)^(5/3)
    # (d in m) — the larger lateral value; c = 1.25e-5·k.
    assert k[1, 1] > k[0, 0] > 0
    np.testing.assert_allclose(fr.C(0)[1, 1], 1.25e-5 * k[1, 1], rtol=1e-9)
