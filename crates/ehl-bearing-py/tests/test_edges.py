"""Hostile Python values at every door: each is an error naming the field and the value, or a
result, never a crash, a hang or an absurd number passed off as an answer."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ehl_bearing as eb

rs = pytest.importorskip("ross")
er = pytest.importorskip("ehl_bearing.ross")

CASE_DICT = {
    "bearing": {
        "ball_count": 11,
        "ball_diameter_mm": 7.0,
        "pitch_diameter_mm": 42.5,
        "inner_conformity": 0.51,
        "outer_conformity": 0.54,
        "contact_angle_deg": 15.0,
    },
    "operating": {"inner_speed_rpm": 5000.0, "force_axial_n": 1000.0},
}


def with_value(table: str, key: str, value):
    d = {k: dict(v) for k, v in CASE_DICT.items()}
    d[table][key] = value
    return d


def test_case_dicts_take_numpy_scalars_and_name_bad_values():
    # numpy scalars are numbers ("int64 is not JSON serializable" before).
    c = eb.Case.from_dict(
        with_value("bearing", "ball_count", np.int64(11))
        | {"operating": {"inner_speed_rpm": np.float32(5000.0), "force_axial_n": 1000.0}}
    )
    assert c.ball_count == 11
    assert math.isclose(c.inner_speed_rad_s, 5000.0 * math.pi / 30.0)
    # NaN, inf and objects name their key ("expected value at line 1 column 28" before).
    for value, words in [
        (float("nan"), ["bearing.ball_diameter_mm = NaN", "finite"]),
        (np.float64("inf"), ["bearing.ball_diameter_mm = inf", "finite"]),
        (object(), ["bearing.ball_diameter_mm", "expected a number"]),
        (None, ["bearing.ball_diameter_mm = None", "leave the key out"]),
    ]:
        with pytest.raises(eb.EhlBearingError) as e:
            eb.Case.from_dict(with_value("bearing", "ball_diameter_mm", value))
        for w in words:
            assert w in str(e.value), str(e.value)
    with pytest.raises(eb.EhlBearingError, match="key 3 is not text"):
        eb.Case.from_dict({"bearing": {3: 1}})


def test_speeds_are_checked_where_they_enter(case):
    with pytest.raises(eb.EhlBearingError, match="inner_speed_rpm = 1e300"):
        case.with_inner_speed_rpm(1e300)
    with pytest.raises(eb.EhlBearingError, match="n·d_m"):
        case.with_inner_speed_rpm(1e6)
    element = eb.LawElement.hertz(case)
    with pytest.raises(eb.EhlBearingError, match="inner_speed_rad_s = NaN"):
        element.cage_speed(float("nan"))
    assert 0.0 < element.cage_speed(100.0) < 100.0


def test_evaluate_takes_any_real_array_like(case):
    element = eb.LawElement.hertz(case)
    q, _, _ = element.equilibrium(case)
    w = case.inner_speed_rad_s
    ref, _, _ = element.evaluate(np.asarray(q, dtype=np.float64), inner_speed_rad_s=w)
    for q_in in [
        list(q),
        tuple(q),
        np.asarray(q, dtype=np.float32),
        np.asarray(q, dtype=">f8"),
        np.asarray(q, dtype=np.float64)[::-1][::-1],
    ]:
        r, _, _ = element.evaluate(q_in, inner_speed_rad_s=w)
        # float32 rounds the displacement to 6e-8 relative; the stiff contacts amplify it.
        rtol = 1e-3 if getattr(q_in, "dtype", None) == np.float32 else 1e-9
        assert np.allclose(r, ref, rtol=rtol, atol=0.0), (q_in, r, ref)
    with pytest.raises(eb.EhlBearingError, match="displacement: expected 5 values, got 3"):
        element.evaluate([0.0, 0.0, 0.0])


def test_an_absurd_displacement_is_flagged_not_passed_off(case):
    element = eb.LawElement.hertz(case)
    q, _, _ = element.equilibrium(case)
    w = case.inner_speed_rad_s
    out = element.evaluate(q, inner_speed_rad_s=w, full=True)
    assert out["overloaded"] == []
    q_tilted = np.array(q)
    q_tilted[3] = 1.0  # 1 rad: a 26 MN contact load came back with nothing flagged
    with pytest.warns(RuntimeWarning, match="no bearing survives"):
        out = element.evaluate(q_tilted, inner_speed_rad_s=w, full=True)
    assert out["overloaded"], out


def test_a_progress_callback_can_stop_a_run_and_time_is_bounded(case):
    element = eb.LawElement.hertz(case)
    rotor = er.two_disk_rotor(
        er.friswell_bearing(0, case, 1000.0), er.friswell_bearing(6, case, 1000.0)
    )
    bare = rs.Rotor(rotor.shaft_elements, rotor.disk_elements)
    # The example rotor's loads: the case's radial reactions at the two bearing nodes.
    w = case.inner_speed_rad_s
    q, _, _ = element.equilibrium(case)
    r, _, _ = element.evaluate(q, inner_speed_rad_s=w)
    extra = np.zeros(bare.ndof)
    for node in (0, 6):
        d = er.node_dofs(bare, node)
        extra[d[0]] += r[1]
        extra[d[1]] += r[2]
    sites = [er.BearingSite(element, 0), er.BearingSite(element, 6, mounting=-1)]
    model = er.rotor_model(bare, sites, [], extra_force_n=extra)

    class Stop(Exception):
        pass

    calls = []

    def progress(step, steps, t):
        calls.append(step)
        if len(calls) == 3:
            raise Stop("user cancel")

    # The callback's exception stops the run and comes out of simulate (it was printed and
    # ignored before).
    with pytest.raises(Stop, match="user cancel"):
        model.simulate(1e-5, 0.05, speed_rad_s=w, progress=progress)
    assert len(calls) == 3
    # A wall-time limit stops a long run with the step reached.
    with pytest.raises(eb.EhlBearingError, match=r"time limit of 0\.2 s reached at step"):
        model.simulate(1e-5, 100.0, speed_rad_s=w, record_every=1000, time_limit_s=0.2)
    with pytest.raises(eb.EhlBearingError, match="time_limit_s = -1"):
        model.simulate(1e-5, 0.01, speed_rad_s=w, time_limit_s=-1.0)
    # A record that cannot fit in memory is refused before any step (1e9 steps were accepted).
    with pytest.raises(eb.EhlBearingError, match="recorded samples"):
        model.simulate(1e-9, 1.0, speed_rad_s=w)


def test_a_characterization_can_be_stopped_from_its_callback(case):
    class Stop(Exception):
        pass

    events = []

    def progress(e):
        events.append(e["event"])
        if e["event"] == "contact_done":
            raise Stop("user cancel")

    # The callback's exception stops the loop (no further contact starts) and is raised (it was
    # printed and ignored before, once per event).
    with pytest.raises(Stop, match="user cancel"):
        eb.characterize(case, method="hertz", progress=progress)
    assert events.count("contact_done") <= 2, events  # at most the contacts in flight
    with pytest.raises(Stop):
        eb.coefficients(case, [3000.0], method="hertz", progress=progress)
    # A progress that is not a function is refused at the door (it failed at every event).
    for call in (
        lambda: eb.characterize(case, method="hertz", progress=3),
        lambda: eb.coefficients(case, [3000.0], method="hertz", progress="x"),
    ):
        with pytest.raises(TypeError, match="progress: expected a function"):
            call()
    with pytest.raises(eb.EhlBearingError, match="time_limit_s = 0"):
        eb.characterize(case, method="hertz", time_limit_s=0.0)
    assert eb.characterize(case, method="hertz", time_limit_s=60.0).converged
