"""pump-station (issue 31): the correct variants score at least 95 %, and a program whose
priming pump is not gated by the low level (the gap the issue found) is caught and capped."""

from pathlib import Path

import pytest

from plclab.grade.engine import grade_sources, read_submission
from plclab.grade.lab import load_lab

LAB = "pump-station"


def lab_path(lab_id):
    return load_lab(lab_id).path


VARIANTS = sorted(p.name for p in (lab_path(LAB) / "variants").glob("*.st"))


def _grade(path: Path):
    lab = load_lab(LAB)
    sources, _ = read_submission(path)
    return lab, grade_sources(lab, sources)


def test_there_are_two_variants():
    assert len(VARIANTS) >= 2


@pytest.mark.parametrize("name", VARIANTS)
def test_variant_scores_at_least_95_percent(name):
    lab, res = _grade(lab_path(LAB) / "variants" / name)
    assert res.status == "ok"
    failed = [f"{t.name}: {t.message}" for t in res.tests if not t.passed]
    assert res.score >= 0.95 * res.max_score, failed


def test_ungated_priming_is_capped(tmp_path):
    src = (lab_path(LAB) / "solution" / "pump_station.st").read_text(encoding="utf-8")
    wrong = src.replace("IF NY THEN\n    ZAL := NOT DAWL;", "ZAL := NOT DAWL;\nIF NY THEN", 1)
    wrong = wrong.replace("ELSE\n    ZAL := FALSE;\n", "ELSE\n", 1)
    assert wrong.count("ZAL :=") == 1
    f = tmp_path / "p.st"
    f.write_text(wrong, encoding="utf-8")
    lab, res = _grade(f)
    assert res.status == "ok"
    assert res.score <= 0.5 * res.max_score
    assert any(not t.passed and "no priming below the low level" in t.name for t in res.tests)
