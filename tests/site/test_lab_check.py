"""'Check against the lab' in the page: the reference solutions pass every visible criterion,
the labs' typical mistakes lose the points the grader takes."""

import tomllib
from pathlib import Path

import pytest

from plclab.grade.courseware import student_lab_data
from plclab.site.lab_check import BROWSER_LABS, check_lab, lab_json_from_dict, seconds
from plclab.site.pages import _lab_wiring

LABS = Path(__file__).resolve().parents[2] / "labs"


def lab(lab_id):
    with open(LABS / lab_id / "lab.toml", "rb") as fh:
        data = student_lab_data(tomllib.load(fh))
    return lab_json_from_dict(lab_id, data, _lab_wiring(LABS / lab_id, data))


@pytest.mark.parametrize("lab_id", BROWSER_LABS)
def test_reference_solutions_score_every_judged_point(lab_id):
    data = lab(lab_id)
    assert data["scenarios"] and all(s.get("visible", True) for s in data["scenarios"])
    for sol in sorted((LABS / lab_id / "solution").glob("*.[sl][td]")):
        res = check_lab(sol.read_text(), sol.suffix[1:], data)
        assert res["diagnostics"] == [], sol
        assert res["of"] > 0 and res["points"] == res["of"], (sol, res["results"])


@pytest.mark.parametrize("lab_id", BROWSER_LABS)
def test_every_typical_mistake_loses_points_on_a_criterion_it_violates(lab_id):
    with open(LABS / lab_id / "lab.toml", "rb") as fh:
        mistakes = tomllib.load(fh)["mistake"]
    data = lab(lab_id)
    for m in mistakes:
        path = LABS / lab_id / "mistakes" / m["file"]
        res = check_lab(path.read_text(), path.suffix[1:], data)
        failed = {r["criterion"] for r in res["results"] if r["passed"] is False}
        named = {v.split(": ", 1)[-1] for v in m["violates"]}
        assert res["points"] < res["of"], m["file"]
        assert failed & named, (m["file"], failed, named)


def test_a_program_that_does_not_compile_returns_its_diagnostics():
    res = check_lab("PROGRAM P\nx := ;\nEND_PROGRAM\n", "st", lab("tank-two-position"))
    assert res["results"] == [] and res["diagnostics"][0]["code"].startswith("PLC0")


def test_durations():
    assert seconds("200ms") == pytest.approx(0.2)
    assert seconds("4min") == 240.0
    assert seconds(3) == 3.0
