"""Nonlinear time response of a ROSS rotor on our bearings (the Rust integrator through Python):
the linear limit against ROSS's own linear time response, the ball-pass excitation of rolling
cages, the stability of implicit against lagged bearing forces, and the bindings' checks."""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np
import pytest

import ehl_bearing as eb

rs = pytest.importorskip("ross")
er = pytest.importorskip("ehl_bearing.ross")

# The rotors here carry coefficients at the case's loads on purpose (the nonlinear model carries
# the same loads; the linear limit is taken at the model's own equilibrium).
pytestmark = pytest.mark.filterwarnings("ignore::ehl_bearing.ross.CaseLoadsWarning")

DATA = pathlib.Path(__file__).parent / "data"
RPM = 3000.0


@pytest.fixture(scope="module")
def case3000(case):
    return case.with_inner_speed_rpm(RPM)


@pytest.fixture(scope="module")
def fitted(case3000):
    """The seed bearing's fitted laws at 3000 rpm by the harmonic method (with each contact's
    damping c·δ̇; a lightly damped contact: c ≈ 100 N·s/m per contact): the characterization
    report of `ehl_bearing.characterize(case, method="harmonic")`, stored (8 min to compute)."""
    report = json.loads((DATA / "fitted_7006_3000rpm_harmonic.json").read_text())
    return eb.LawElement.from_report(case3000, report)


def setup(case3000, element, unbalance_kg_m=0.0):
    """The example rotor on a mirrored pair of `element` (preloaded axially to the case's axial
    approach) carrying the case's radial loads at the bearing nodes, plus gravity."""
    w = case3000.inner_speed_rad_s
    q, _, _ = element.equilibrium(case3000)
    r, _, _ = element.evaluate(q, inner_speed_rad_s=w)
    co = eb.coefficients(case3000, [RPM], element=element)
    rotor = er.two_disk_rotor(er.EhlBearingElement(0, co), er.EhlBearingElement(6, co, mounting=-1))
    offset = (q[0], 0.0, 0.0, 0.0, 0.0)
    sites = [er.BearingSite(element, 0, 1, offset), er.BearingSite(element, 6, -1, offset)]
    extra = np.zeros(rotor.ndof)
    for node in (0, 6):
        d = er.node_dofs(rotor, node)
        extra[d[0]] += r[1]  # our y → ROSS x
        extra[d[1]] += r[2]  # our z → ROSS y
    unb = [er.Unbalance(2, unbalance_kg_m)] if unbalance_kg_m else []
    model = er.rotor_model(rotor, sites, unb, extra_force_n=extra)
    return rotor, model, unb, w


def test_static_equilibrium_carries_the_loads(case3000, fitted):
    rotor, model, _, w = setup(case3000, fitted)
    st = model.static_equilibrium(w)
    # The mirrored pair's axial preloads cancel; the radial reactions carry the applied radial
    # loads plus the rotor's weight (ROSS's gravitational_force, along −ROSS y = our −z).
    weight = -rotor.gravitational_force(M=rotor.M0, num_dof=rotor.number_dof)[1::6].sum()
    r = st["reactions"]
    assert r[0, 0] == pytest.approx(r[1, 0], rel=1e-6)
    assert r[:, 1].sum() == pytest.approx(2 * 1000.0, rel=1e-6)
    assert r[:, 2].sum() == pytest.approx(2 * 1000.0 - weight, rel=1e-6)


def test_small_unbalance_agrees_with_ross_linear_time_response(case3000, fitted):
    """Linear limit: 1e-6 kg·m unbalance (0.1 N at 3000 rpm) on disk 1; the nonlinear response
    (implicit, cages fixed: a time-invariant bearing) against ROSS's `integrate_system` with the
    rotor linearized at the static equilibrium (our bearings' K and C). Both are Newmark's
    average-acceleration rule with the same step, so the orbit amplitudes agree to the
    linearization error, O(amplitude²): the issue's 1 % is the bound asserted."""
    rotor, model, unb, w = setup(case3000, fitted, unbalance_kg_m=1e-6)
    h, duration = 2e-5, 0.03
    out = model.simulate(step_s=h, duration_s=duration, speed_rad_s=w, cage_angle_rad=0.0)
    lin = model.linearized(w)
    q0 = lin["static"]["displacement"]
    t = out["time_s"]
    force = er.unbalance_force(rotor, unb, t, w)
    _, y = rotor.integrate_system(
        w, force, t, M=lin["mass"], K=lin["stiffness"], C=lin["damping"], G=lin["gyroscopic"]
    )
    d = er.node_dofs(rotor, 2)
    half = len(t) // 2
    nl = np.hypot(out["displacement"][:, d[0]] - q0[d[0]], out["displacement"][:, d[1]] - q0[d[1]])
    li = np.hypot(y[:, d[0]], y[:, d[1]])
    amp_nl, amp_li = nl[half:].max(), li[half:].max()
    assert amp_li > 1e-9  # a response, not numerical noise
    assert amp_nl == pytest.approx(amp_li, rel=0.01)


def _spectrum(signal, step_s):
    s = signal[len(signal) // 4 :]  # after the start
    s = (s - s.mean()) * np.hanning(len(s))
    return np.fft.rfftfreq(len(s), step_s), np.abs(np.fft.rfft(s))


def test_rolling_cage_shows_the_ball_pass_frequency_and_harmonics(case3000):
    """Radial load, no unbalance, dry Hertz laws (identical balls): as the balls pass the load
    zone the bearing's stiffness varies at Z·f_cage. The bearing node's displacement spectrum
    peaks there (within the resolution 1/T) with its second harmonic standing out of the floor;
    with the cage held the response stays at the static equilibrium."""
    dry = eb.LawElement.hertz(case3000)
    rotor, model, _, w = setup(case3000, dry)
    h, duration = 2e-5, 0.15
    out = model.simulate(step_s=h, duration_s=duration, speed_rad_s=w)
    # The operating cage speed the rolling cage turned at (the bearing model's orbital speeds;
    # the free-angle estimate dry.cage_speed(w) is a few tenths of a percent slower).
    w_cage = out["cage_speed_rad_s"][len(out["time_s"]) // 4 :, 0].mean()
    assert w_cage > dry.cage_speed(w)
    f_bp = dry.ball_count * w_cage / (2 * math.pi)  # ≈ 232 Hz at 3000 rpm
    x = out["displacement"][:, er.node_dofs(rotor, 0)[0]]
    f, a = _spectrum(x, h)
    df = f[1] - f[0]
    band = f > 50.0
    assert abs(f[band][np.argmax(a[band])] - f_bp) <= df
    floor = np.median(a[(f > 50.0) & (f < 3000.0)])
    for k in (1, 2):
        near = np.abs(f - k * f_bp) <= 1.5 * df
        assert a[near].max() > 100 * floor, k
    held = model.simulate(step_s=h, duration_s=0.02, speed_rad_s=w, cage_angle_rad=0.0)
    xh = held["displacement"][:, er.node_dofs(rotor, 0)[0]]
    assert np.ptp(xh) < 1e-3 * np.ptp(x)  # rounding only


def test_lagged_bearing_forces_diverge_where_implicit_ones_are_stable(case3000, fitted):
    """The lightly damped fitted contacts at h = 2e-5 s (a user's choice: ~12 steps per period of
    the 231 Hz ball pass… and of the rotor's modes up to a few kHz): the implicit step stays at
    the unbalance orbit, the lagged forces (ROSS's add_to_RHS) blow up within milliseconds."""
    _, model, _, w = setup(case3000, fitted, unbalance_kg_m=1e-5)
    h = 2e-5
    ok = model.simulate(step_s=h, duration_s=0.02, speed_rad_s=w, cage_angle_rad=0.0)
    y = ok["bearing_displacement"][:, 0, 1]
    assert np.ptp(y) < 1e-6  # bounded: well below a micrometre
    with pytest.raises(eb.EhlBearingError, match=r"t = "):
        model.simulate(
            step_s=h, duration_s=0.02, speed_rad_s=w, cage_angle_rad=0.0, coupling="lagged"
        )
    # Before it fails, the lagged response grows: the first millisecond against the next.
    early = model.simulate(
        step_s=h, duration_s=0.0015, speed_rad_s=w, cage_angle_rad=0.0, coupling="lagged"
    )
    yl = early["bearing_displacement"][:, 0, 1] - y[0]
    n = len(yl) // 3
    assert np.abs(yl[2 * n :]).max() > 10 * np.abs(yl[:n]).max()


def test_run_up_follows_the_ramp(case3000):
    dry = eb.LawElement.hertz(case3000)
    _, model, _, w = setup(case3000, dry, unbalance_kg_m=1e-5)
    out = model.simulate(step_s=5e-5, duration_s=0.02, ramp=(0.5 * w, w, 0.02), record_every=4)
    np.testing.assert_allclose(out["speed_rad_s"], 0.5 * w + 0.5 * w * out["time_s"] / 0.02)
    assert out["breakdown"]["total_s"] >= out["breakdown"]["bearing_s"] > 0
    # The dicts of numpy arrays have the keys of the library's records, in their order.
    assert list(out) == eb.result_keys("rotor_run")
    assert list(model.static_equilibrium(w)) == eb.result_keys("rotor_static")
    with pytest.raises(eb.EhlBearingError, match="rotor_run"):
        eb.result_keys("rotor")


def test_rotor_model_errors_name_the_input(case3000):
    dry = eb.LawElement.hertz(case3000)
    n = 12
    m = eb.RotorModel(np.eye(n), np.zeros((n, n)), np.zeros((n, n)), np.eye(n))
    with pytest.raises(eb.EhlBearingError, match="dofs"):
        m.add_bearing(dry, dofs=[0, 1, 2, 3, 99])
    with pytest.raises(eb.EhlBearingError, match="damping: expected shape"):
        eb.RotorModel(np.eye(3), np.zeros((n, n)), np.zeros((n, n)), np.eye(n))
    m.add_bearing(dry, dofs=[0, 1, 2, 3, 4])
    # Neither speed nor ramp: the message says what is missing; both: that one is too many.
    with pytest.raises(eb.EhlBearingError, match=r"no shaft speed given: pass speed_rad_s .* ramp"):
        m.simulate(step_s=1e-5, duration_s=1e-3)
    with pytest.raises(
        eb.EhlBearingError,
        match=r"both speed_rad_s = 1\S* and ramp = \(0\.0, 1\.0, 1\.0\).* one of",
    ):
        m.simulate(step_s=1e-5, duration_s=1e-3, speed_rad_s=1.0, ramp=(0.0, 1.0, 1.0))
