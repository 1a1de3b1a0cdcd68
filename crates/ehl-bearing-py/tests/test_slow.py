"""Slow tests (EHL characterizations, minutes): `pytest -m slow` (see README, Python and ROSS)."""

from __future__ import annotations

import json
import pathlib

import numpy as np
import pytest

import ehl_bearing as eb

pytestmark = pytest.mark.slow


def test_contact_quasi_static_fit(examples):
    fit = eb.contact((examples / "contact_7006_inner.toml").read_text(), method="quasi-static")
    # The fitted law reproduces its samples: R² of the LM fit (docs/fit.md) close to 1.
    assert fit["r_squared"] > 0.999
    assert 1.0 < fit["d"] < 2.0  # between linear and beyond Hertz's 1.5 (docs/contact.md)
    # The Richardson film estimate at w0 (129²/257²): the central film above the 129² one, which
    # the coarse grid leaves 5.6 % low (docs/contact.md, "Default accuracy").
    film = fit["film"]
    assert film["grid_fine"] == 257
    assert film["h_central"] > film["h_central_fine"] > fit["samples"][3]["h_central"]


def test_characterize_quasi_static_element_reproduces_the_equilibrium(case):
    ch = eb.characterize(case, method="quasi-static")
    assert ch.converged
    el = ch.law_element()
    r, k, c = el.evaluate(ch.displacement, inner_speed_rad_s=case.inner_speed_rad_s)
    # The fitted laws' equilibrium carries the case's loads (loop tolerance 1e-3 on the loads).
    np.testing.assert_allclose(r[:3], [1000.0] * 3, rtol=2e-3)
    np.testing.assert_allclose(k, ch.stiffness, rtol=1e-6, atol=1e-6 * np.abs(k).max())
    assert np.all(c == 0)  # the quasi-static method fits no damping


def test_stored_harmonic_fit_is_reproduced(case):
    """The test data (tests/data/fitted_7006_3000rpm_harmonic.json) is what the harmonic method
    gives today: same laws within the loop's tolerance (1e-3 on the loads → ~1e-2 on K·δ^d)."""
    data = pathlib.Path(__file__).parent / "data" / "fitted_7006_3000rpm_harmonic.json"
    stored = json.loads(data.read_text())
    ch = eb.characterize(case.with_inner_speed_rpm(3000), method="harmonic")
    now = ch.report()
    for a, b in zip(now["contacts"], stored["contacts"]):
        assert a["load_n"] == pytest.approx(b["load_n"], rel=1e-2, abs=1e-2)
