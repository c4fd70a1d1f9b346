"""Every lab: reference solutions score 100 %, each typical mistake scores less and its
feedback says what its header comment expects, the starter compiles and scores low, the README's
I/O table is the one lab.toml generates."""

import re

import pytest

from plclab.grade.commands import readme_table
from plclab.grade.engine import grade_sources, read_submission
from plclab.grade.feedback import render_feedback
from plclab.grade.lab import list_labs, load_lab, repo_labs_dir

LABS = [p.name for p in list_labs() if p.parent == repo_labs_dir()]
EXPECT = re.compile(r"\(\*\s*expect:\s*(.+?)\s*\*\)")


def _files(sub):
    out = []
    for lab_id in LABS:
        lab = load_lab(lab_id)
        out += [(lab_id, p.name) for p in lab.files(sub)]
    return out


def _grade(lab_id, path):
    lab = load_lab(lab_id)
    sources, _ = read_submission(path)
    return lab, grade_sources(lab, sources)


def test_the_labs_exist():
    assert {"motor-start-stop", "tank-two-position", "relay-thermostat",
            "bottle-reject"} <= set(LABS)


@pytest.mark.parametrize("lab_id", LABS)
def test_lab_is_valid_and_complete(lab_id):
    lab = load_lab(lab_id, deep=True)  # binds every scenario to the plant and the wiring
    assert lab.files("solution"), "a reference solution"
    assert len(lab.files("mistakes")) >= 2, "at least two typical mistakes"
    assert lab.starter, "a starter file"
    assert any(not s.visible for s in lab.scenarios), "a hidden scenario"
    assert any(s.visible for s in lab.scenarios)
    for m in lab.files("mistakes"):
        assert EXPECT.search(m.read_text(encoding="utf-8")), f"{m.name}: (* expect: ... *)"


@pytest.mark.parametrize("lab_id", LABS)
def test_readme_io_table_matches_lab_toml(lab_id):
    lab = load_lab(lab_id)
    readme = (lab.path / "README.md").read_text(encoding="utf-8")
    assert readme_table(readme) == lab.io_table_markdown(), (
        f"run: plclab lab show {lab_id} --update-readme")


@pytest.mark.parametrize("lab_id,name", _files("solution"))
def test_solution_scores_full_marks(lab_id, name):
    lab, res = _grade(lab_id, lab_path(lab_id) / "solution" / name)
    failed = [f"{t.name}: {t.message}" for t in res.tests if not t.passed]
    assert res.status == "ok" and not failed, failed
    assert res.score == res.max_score == lab.max_score


@pytest.mark.parametrize("lab_id,name", _files("mistakes"))
def test_mistake_scores_less_with_the_right_message(lab_id, name):
    path = lab_path(lab_id) / "mistakes" / name
    expect = EXPECT.search(path.read_text(encoding="utf-8")).group(1)
    _, res = _grade(lab_id, path)
    assert res.status == "ok"
    assert res.score < res.max_score
    text = render_feedback(res, instructor=True)
    assert expect.lower() in text.lower(), f"'{expect}' not in the feedback of {name}"


@pytest.mark.parametrize("lab_id", LABS)
def test_starter_compiles_and_scores_low(lab_id):
    lab = load_lab(lab_id)
    for path in lab.starter:
        sources, _ = read_submission(path)
        res = grade_sources(lab, sources, scenarios=[s.name for s in lab.visible_scenarios])
        assert res.status == "ok", res.diagnostics
        assert not [d for d in res.diagnostics if " error " in f" {d} "]
        assert res.score <= 0.25 * res.max_score


def lab_path(lab_id):
    return load_lab(lab_id).path
