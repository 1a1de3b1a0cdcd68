"""The bindings of the library: cases, equilibrium, EHL, force elements, coefficients, errors."""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
import tomllib

import ehl_bearing as eb


def test_case_from_file_toml_and_dict_agree(case, examples):
    text = (examples / "7006.toml").read_text()
    from_toml = eb.Case.from_toml(text)
    from_dict = eb.Case.from_dict(tomllib.loads(text))
    for c in (from_toml, from_dict):
        assert c.ball_count == case.ball_count == 11
        assert c.pitch_diameter_m == pytest.approx(0.0425, rel=1e-12)
        assert c.inner_speed_rad_s == pytest.approx(5000 * math.pi / 30, rel=1e-12)
    assert case.with_inner_speed_rpm(3000).inner_speed_rad_s == pytest.approx(100 * math.pi)


def test_library_errors_are_python_exceptions_with_the_message(examples):
    assert issubclass(eb.EhlBearingError, ValueError)
    text = (examples / "7006.toml").read_text().replace("ball_count = 11", "ball_count = 2")
    with pytest.raises(eb.EhlBearingError, match="ball_count"):
        eb.Case.from_toml(text, "bad.toml")
    with pytest.raises(eb.EhlBearingError, match=r"nope\.toml"):
        eb.Case.from_file("nope.toml")


def test_equilibrium_balances_the_case_loads(case):
    eq = eb.equilibrium(case)
    assert eq["converged"]
    r = eq["reaction"]
    reaction = [r[k] for k in r] if isinstance(r, dict) else r
    # The case's loads: F_x = F_y = F_z = 1000 N (examples/7006.toml); tolerance of the solver.
    np.testing.assert_allclose(reaction[:3], [1000.0, 1000.0, 1000.0], rtol=1e-6)


def _displacement(eq):
    d = eq["displacement"]
    return np.array(list(d.values()) if isinstance(d, dict) else d, dtype=float)


def test_force_element_arrays_and_jacobian(case):
    el = eb.LawElement.hertz(case)
    q = _displacement(eb.equilibrium(case))
    w = case.inner_speed_rad_s
    r, k, c = el.evaluate(q, inner_speed_rad_s=w)
    assert r.shape == (5,) and k.shape == (5, 5) and c.shape == (5, 5)
    np.testing.assert_allclose(r[:3], [1000.0, 1000.0, 1000.0], rtol=1e-5)
    assert np.all(c == 0.0)  # dry laws carry no damping
    # The stiffness is ∂reaction/∂q: central differences (1 nm, 1 µrad) agree to 1e-3 of the
    # diagonal (the laws are smooth at this load; step error O(h²)).
    for j, h in enumerate([1e-9, 1e-9, 1e-9, 1e-6, 1e-6]):
        dq = np.zeros(5)
        dq[j] = h
        rp = el.evaluate(q + dq, inner_speed_rad_s=w)[0]
        rm = el.evaluate(q - dq, inner_speed_rad_s=w)[0]
        fd = (rp - rm) / (2 * h)
        scale = np.abs(np.diag(k))
        assert np.all(np.abs(fd - k[:, j]) <= 1e-3 * np.maximum(scale, np.abs(k[:, j]))), j
    column = np.stack([q, 2 * q], axis=1)[:, 0]  # a non-contiguous view
    np.testing.assert_allclose(el.evaluate(column, inner_speed_rad_s=w)[0], r, rtol=1e-9)
    full = el.evaluate(q, inner_speed_rad_s=w, full=True)
    assert full["loads"].shape == (11, 2) and full["approaches"].shape == (11, 2)
    with pytest.raises(eb.EhlBearingError, match="displacement"):
        el.evaluate(np.zeros(4))


def test_cage_speed_pure_rolling(case):
    el = eb.LawElement.hertz(case)
    g = case.ball_diameter_m * math.cos(case.contact_angle_rad) / case.pitch_diameter_m
    assert el.cage_speed(100.0) == pytest.approx(0.5 * 100.0 * (1 - g), rel=1e-12)


def test_coefficients_from_element_and_ross_table(case):
    el = eb.LawElement.hertz(case)
    co = eb.coefficients(case, [3000.0, 5000.0], element=el)
    assert [c["inner_speed_rpm"] for c in co] == [3000.0, 5000.0]
    for c in co:
        k = np.array(c["stiffness"])
        # The dry element's own equilibrium: its stiffness is the dry stiffness (Newton to the
        # case's tolerance; 1e-4 relative).
        np.testing.assert_allclose(k, np.array(c["dry_stiffness"]), rtol=1e-4, atol=1e-4 * k.max())
    table = eb.ross_table_csv(co).splitlines()
    assert table[0].split(",")[:5] == ["frequency", "kxx", "kxy", "kyx", "kyy"]
    row = [float(x) for x in table[2].split(",")]
    k = np.array(co[1]["stiffness"])
    assert row[0] == pytest.approx(co[1]["inner_speed_rad_s"])
    # ROSS x ← our y, ROSS y ← our z, ROSS z ← our x.
    assert row[1] == k[1, 1] and row[2] == k[1, 2] and row[3] == k[2, 1] and row[4] == k[2, 2]
    assert row[9] == k[0, 0]


def test_characterize_hertz_reports_progress_and_gives_an_element(case):
    events = []
    ch = eb.characterize(case, method="hertz", progress=events.append)
    assert ch.converged
    assert any(e["event"] == "iteration_done" for e in events)
    rep = ch.report()
    assert len(rep["contacts"]) == 22
    el = ch.law_element()
    r, _, _ = el.evaluate(ch.displacement, inner_speed_rad_s=case.inner_speed_rad_s)
    np.testing.assert_allclose(r[:3], [1000.0] * 3, rtol=1e-4)
    # The same laws through the report dict (as cached by the worked example).
    el2 = eb.LawElement.from_report(case, rep)
    np.testing.assert_allclose(
        el2.evaluate(ch.displacement, inner_speed_rad_s=case.inner_speed_rad_s)[0], r, rtol=1e-9
    )


def test_ehl_point_contact(examples):
    text = (examples / "contact_7006_inner.toml").read_text()
    sol = eb.ehl(text, grid=65)
    # Central film of this contact (M ≈ 2.4e3, L ≈ 25): the Hamrock–Dowson/NVM estimates are
    # ~0.2–0.3 µm (examples/contact_7006_inner.toml); the coarse grid is within a factor 1.5.
    assert 0.1e-6 < sol["h_central"] < 0.5e-6
    assert sol["h_min"] < sol["h_central"]
    assert "fields" not in sol
    with pytest.raises(eb.EhlBearingError, match="load_n"):
        eb.ehl(text.replace("load_n = 600.0", "load_n = -1.0"))


def test_contact_takes_the_method_options(examples):
    text = (examples / "contact_7006_inner.toml").read_text()
    fast = {"steps_per_period": 16, "settling_periods": 1}
    out = eb.contact(
        text, method="harmonic", grid=33, method_options={**fast, "step_tol_film": 2e-5}
    )
    e = out["excitation"]
    assert e["step_tol_film"] == 2e-5 and e["steps_per_period"] == 16
    # The mass group that says when to tighten the step tolerance (docs/contact.md).
    assert 0.1 < e["mass_group_psi_h"] < 100.0
    # Out of range, unknown, twice: the key, the value and the range.
    too_loose = r"method_options\.step_tol_film = 0\.5.*\(0, 0\.01\]"
    with pytest.raises(eb.EhlBearingError, match=too_loose):
        eb.contact(text, method="harmonic", grid=33, method_options={**fast, "step_tol_film": 0.5})
    with pytest.raises(eb.EhlBearingError, match="step_tol"):
        eb.contact(text, method="harmonic", grid=33, method_options={"step_tol": 1e-6})
    with pytest.raises(eb.EhlBearingError, match="grid is given twice"):
        eb.contact(text, grid=33, method_options={"grid": 65})
    with pytest.raises(eb.EhlBearingError, match="method_options"):
        eb.contact(text, method_options=[1, 2])


def test_study_runs_and_reports_progress(tmp_path, examples):
    study_file = tmp_path / "s.toml"
    study_file.write_text(
        f'case = "{examples / "7006.toml"}"\nmethod = "hertz"\n'
        "inner_speeds_rpm = [3000.0, 5000.0]\nload_scales = [0.5, 1.0, 1.5]\n"
    )
    events = []
    out = eb.study(str(study_file), str(tmp_path / "out"), progress=events.append)
    assert out["points"] == 6 and out["computed"] == 6 and not out["failed"]
    assert sum(e["event"] == "point_done" for e in events) == 6
    assert (tmp_path / "out" / "results.csv").exists()
    again = eb.study(str(study_file), str(tmp_path / "out"))
    assert again["computed"] == 0 and again["loaded"] == 6


def test_print_progress_names_the_point_of_a_loop_event(capsys):
    """A study's points may run concurrently: loop lines carry their point; every line starts
    with the time elapsed since the run began."""
    eb.print_progress(
        {
            "event": "loop",
            "index": 1,
            "progress": {"event": "iteration_started", "iteration": 3, "contacts": 22},
        }
    )
    eb.print_progress({"event": "iteration_started", "iteration": 1, "contacts": 5})
    err = capsys.readouterr().err.splitlines()
    assert [line.split("] ", 1)[1] for line in err] == [
        "point 2, iteration 3: 22 contacts",
        "iteration 1: 5 contacts",
    ]
    assert all(line.startswith("[") and line.split("] ")[0].endswith(" s") for line in err)


def test_progress_printer_prints_elapsed_and_per_iteration_and_point_times():
    """Elapsed time since the run began (a loop's first iteration, a study's plan), and the
    times the events carry: the iteration's wall time with its contacts, the point's."""
    now = [100.0]
    out = io.StringIO()
    p = eb.ProgressPrinter(file=out, clock=lambda: now[0])
    now[0] = 105.0
    p({"event": "iteration_started", "iteration": 0, "contacts": 22})  # the clock restarts
    now[0] = 107.5
    p({"event": "contact_done", "iteration": 0})  # skipped
    p({"event": "iteration_started", "iteration": 1, "contacts": 12})  # same run
    now[0] = 119.0
    record = {
        "iteration": 1,
        "seconds": 11.46,
        "characterized": 12,
        "reused": 10,
        "max_load_change": 0.0123,
    }
    p({"event": "iteration_done", "record": record})
    now[0] = 200.0
    p({"event": "planned", "points": 3, "to_compute": 2, "redone": 0})  # a study: restarts
    now[0] = 212.25
    p({"event": "point_started", "index": 0, "inner_speed_rpm": 3000.0, "load_scale": 1.0})
    p({"event": "point_done", "index": 0, "converged": True, "error": None, "seconds": 12.04})
    now[0] = 300.0
    p({"event": "iteration_started", "iteration": 1, "contacts": 4})  # a new loop: restarts
    assert out.getvalue().splitlines() == [
        "[   0.0 s] load prediction: 22 contacts",
        "[   2.5 s] iteration 1: 12 contacts",
        "[  14.0 s] iteration 1 done in 11.5 s (12 contacts characterized, 10 reused): "
        "largest relative load change 1.23e-02",
        "[   0.0 s] study: 3 points, 2 to compute",
        "[  12.2 s] point 1: 3000.0 rpm × 1.0",
        "[  12.2 s] point 1: converged in 12.0 s",
        "[   0.0 s] iteration 1: 4 contacts",
    ]


def test_study_of_a_described_oil_carries_the_lubrication(tmp_path, examples):
    """A study of the seed with its oil described and roughness: the tables gain the lubrication
    columns and the summary the extremes over the points (docs/lubricant.md §2.5)."""
    study_file = tmp_path / "s.toml"
    study_file.write_text(
        f'case = "{examples / "7006_vg46.toml"}"\nmethod = "hertz"\n'
        "inner_speeds_rpm = [3000.0, 5000.0]\nload_scales = [1.0]\n"
    )
    out = eb.study(str(study_file), str(tmp_path / "out"))
    lub = out["lubrication"]
    assert lub["points"] == 2
    assert lub["min_lambda"]["value"] > 1.0 and lub["min_lambda"]["race"] in ("inner", "outer")
    assert 0.0 < lub["max_thermal_reduction"]["value"] < 1.0
    header = (tmp_path / "out" / "points.csv").read_text().splitlines()[0].split(",")
    assert header[-3:] == ["min_lambda_race", "max_thermal_reduction", "lubrication_warnings"]
    results = (tmp_path / "out" / "results.csv").read_text().splitlines()[0]
    assert results.endswith("lambda,thermal_reduction,min_film_thermal_m")


def test_map_method_characterizes_the_218_example(examples):
    """The law map (method "map") from Python: the 218 example lies inside the second embedded
    map, so every contact's law comes from the map (milliseconds) and the fitted-law element
    carries the case's axial load at the equilibrium (loop tolerance 1e-3 on the loads)."""
    case = eb.Case.from_file(str(examples / "218_high_speed.toml"))
    ch = eb.characterize(case, method="map")
    assert ch.converged
    report = ch.report()
    assert report["method"]["name"] == "map"
    r, k, _ = ch.law_element().evaluate(ch.displacement, inner_speed_rad_s=case.inner_speed_rad_s)
    assert r[0] == pytest.approx(22250.0, rel=2e-3)
    np.testing.assert_allclose(k, ch.stiffness, rtol=1e-6, atol=1e-6 * np.abs(k).max())
    # The ROSS table by the map method: its stiffness is the map characterization's (the
    # coefficients at the case's own speed run the same loop).
    co = eb.coefficients(case, [case.inner_speed_rad_s * 30.0 / np.pi], method="map")
    assert co[0]["converged"] and co[0]["source"] == "characterization (map)"
    row = [float(x) for x in eb.ross_table_csv(co).splitlines()[1].split(",")]
    np.testing.assert_allclose(row[4], ch.stiffness[2][2], rtol=1e-3)


def test_map_method_gives_the_harmonic_law_from_the_case_file(examples):
    """`method = "map"` with `[method_options] law = "harmonic"` in the case file: the seed
    case at 3000 rpm lies inside the embedded harmonic map (seed oil, Ψ_H 0.4–8), so every
    contact's law comes from it with its damping c, and the fitted-law element carries that
    damping (a damping matrix with a positive axial diagonal)."""
    text = (examples / "7006.toml").read_text()
    assert "inner_speed_rpm = 5000.0" in text
    text = text.replace("inner_speed_rpm = 5000.0", "inner_speed_rpm = 3000.0")
    case = eb.Case.from_toml(
        'method = "map"\n' + text + '\n[method_options]\nlaw = "harmonic"\n', "7006 at 3000 rpm"
    )
    ch = eb.characterize(case)
    assert ch.converged
    rep = ch.report()
    assert rep["method"]["name"] == "map"
    assert len(rep["contacts"]) == 22
    for c in rep["contacts"]:
        assert c["method"] == "map (harmonic)", c["method"]
        assert c["damping_n_s_m"] > 0.0
    _, _, damping = ch.law_element().evaluate(
        ch.displacement, inner_speed_rad_s=case.inner_speed_rad_s
    )
    assert damping[0, 0] > 0.0
