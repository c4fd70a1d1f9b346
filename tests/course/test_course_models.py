"""The controller-tuning numbers chapter 12 quotes are what python-control computes on the
heater model, and a ``model`` figure spec without controllers is a course error."""

import pytest

from plclab.course.model import find_chapter
from plclab.course.models import model_figure, step_summary
from plclab.errors import PlcError

HEATER = {"gain": 1.0, "tau": 697.7, "lag": 4.0}


def test_chapter_12_table_matches_python_control():
    p = step_summary(HEATER, {"kp": 20.0})
    pi100 = step_summary(HEATER, {"kp": 20.0, "tn": 100.0})
    pi700 = step_summary(HEATER, {"kp": 20.0, "tn": 700.0})
    assert p["steady_state"] == pytest.approx(20.0 / 21.0, abs=1e-3)   # 4.8 % remains
    assert p["settling"] == pytest.approx(118, abs=2)
    assert pi100["overshoot"] == pytest.approx(15.1, abs=0.2)
    assert pi100["settling"] == pytest.approx(294, abs=3)
    assert pi700["overshoot"] < 0.5 and pi700["steady_state"] == pytest.approx(1.0)
    assert pi700["settling"] == pytest.approx(124, abs=2)
    text = find_chapter(12).text
    for quoted in ("4.8 % of the step", "| 15 % | 294 s |", "| 0 | 0 | 124 s |", "118 s"):
        assert quoted in text


def test_the_figure_spec_of_chapter_12_uses_the_same_model():
    spec = next(s for s in find_chapter(12).figure_specs if s["kind"] == "model")
    assert spec["plant"] == HEATER


def test_model_figure_needs_controllers(tmp_path):
    with pytest.raises(PlcError) as e:
        model_figure({"file": "x.svg", "plant": HEATER, "controllers": []}, tmp_path / "x.svg")
    assert e.value.code == "PLC3020"
    with pytest.raises(PlcError, match="plant needs gain and tau"):
        step_summary({"gain": 1.0}, {"kp": 1.0})
