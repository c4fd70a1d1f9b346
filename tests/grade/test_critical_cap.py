"""A failed critical criterion caps the whole result at ``critical_cap`` of the lab's points,
whatever the other criteria earned; the cap survives the JSON round trip and reaches the
Gradescope file, whose validator accepts a capped total but no inflated one."""

import pytest

from plclab.errors import PlcError
from plclab.grade import engine
from plclab.grade.engine import Result
from plclab.grade.gradescope import results_json, validate_results
from plclab.grade.lab import load_lab

from .test_grade_criteria import GOOD, make


def _result(critical_failed: bool, cap: float = 0.5) -> Result:
    tests = [engine.TestResult(f"s: c{i}", "s", f"c{i}", 2.0, 2.0, True, "ok") for i in range(9)]
    tests.append(engine.TestResult("s: safety", "s", "safety", 0.0 if critical_failed else 2.0, 2.0,
                            not critical_failed, "bad", critical=True))
    return Result("lab", "ann", tests=tests, critical_cap=cap)


def test_a_failed_critical_criterion_caps_the_score():
    res = _result(True)
    assert res.points == 18 and res.max_score == 20
    assert res.score == 10 and res.capped
    assert [t.criterion for t in res.critical_failures] == ["safety"]
    assert _result(True, cap=0.25).score == 5


def test_a_passed_critical_criterion_caps_nothing():
    res = _result(False)
    assert res.score == res.points == 20 and not res.capped


def test_the_cap_never_raises_a_low_score():
    res = _result(True)
    for t in res.tests[:8]:
        t.score, t.passed = 0.0, False
    assert res.points == 2 and res.score == 2 and not res.capped


def test_the_cap_survives_json_and_reaches_gradescope():
    res = Result.from_json(_result(True, cap=0.4).to_json())
    assert res.score == 8 and res.critical_cap == 0.4
    data = results_json(res)
    assert data["score"] == 8
    assert "Capped at 40%" in data["output"] and "safety" in data["output"]
    assert validate_results(data) == []
    data["score"] = 30  # more than the tests add up to: never valid
    assert validate_results(data)


def test_critical_cap_is_read_from_lab_toml(tmp_path):
    lab = load_lab(make(tmp_path, 'critical_cap = 0.3\n' + GOOD))
    assert lab.critical_cap == 0.3
    assert load_lab(make(tmp_path, GOOD, name="other")).critical_cap == 0.5


@pytest.mark.parametrize("value", ["0.9", "-0.1", "true", '"half"'])
def test_critical_cap_out_of_range_is_a_lab_error(tmp_path, value):
    with pytest.raises(PlcError) as e:
        load_lab(make(tmp_path, f"critical_cap = {value}\n" + GOOD))
    assert e.value.code == "PLC5004" and "critical_cap" in e.value.message
