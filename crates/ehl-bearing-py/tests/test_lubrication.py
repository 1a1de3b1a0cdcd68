"""The lubrication report (docs/lubricant.md) in Python: `Characterization.report()` carries it for
a case that describes its oil, and not for the seed given by its constants."""

from __future__ import annotations

import pytest

import ehl_bearing as eb


def test_report_carries_the_lubrication_of_a_described_oil(examples):
    case = eb.Case.from_file(str(examples / "7006_vg46.toml"))
    rep = eb.characterize(case, method="hertz").report()
    lub = rep["lubrication"]
    assert lub["oil"]["iso_vg"] == 46
    assert lub["oil"]["viscosity_pa_s"] == pytest.approx(0.04, rel=2e-2)
    assert len(lub["contacts"]) == 22
    assert lub["kappa"] > 4.0 and lub["min_lambda"] > 3.0
    assert any("inlet shear heating" in w for w in lub["warnings"])


def test_seed_report_has_no_lubrication(case):
    assert "lubrication" not in eb.characterize(case, method="hertz").report()


def test_invalid_description_is_a_python_exception_naming_the_key(examples):
    text = (examples / "7006_vg46.toml").read_text().replace("iso_vg = 46", "iso_vg = 47")
    with pytest.raises(Exception, match=r"lubricant\.iso_vg = 47"):
        eb.Case.from_toml(text, "bad.toml")


def test_oil_supply_gives_the_starvation_of_each_contact(examples):
    """`operating.inlet_meniscus_distance_mm` (docs/lubricant.md §3): each loaded contact's
    report has its starvation figures (Hamrock & Dowson 1977), the same keys as the CLI's JSON."""
    text = (examples / "7006_vg46.toml").read_text()
    text = text.replace(
        "temperature_c = 40.0", "temperature_c = 40.0\ninlet_meniscus_distance_mm = 0.25"
    )
    rep = eb.characterize(eb.Case.from_toml(text, "starved.toml"), method="hertz").report()
    lub = rep["lubrication"]
    assert lub["inlet_meniscus_distance_m"] == pytest.approx(2.5e-4)
    reductions = [c["starvation"]["reduction"] for c in lub["contacts"]]
    assert max(reductions) == pytest.approx(lub["max_starvation_reduction"])
    assert 0.0 < lub["max_starvation_reduction"] < 0.5
    s = lub["contacts"][1]["starvation"]
    assert set(s) == {
        "inlet_distance_ratio",
        "boundary_ratio",
        "reduction",
        "central_reduction",
        "min_film_m",
    }
    with pytest.raises(Exception, match=r"operating\.inlet_meniscus_distance_mm = -1"):
        eb.Case.from_toml(text.replace("= 0.25", "= -1"), "bad.toml")
