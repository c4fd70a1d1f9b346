"""Every lab: reference solutions score 100 %, each typical mistake scores less, at most its
``[[mistake]]`` bound and at most half the points of the tests it violates, and its feedback
says what its header comment expects, the starter compiles and scores low, the README's
I/O table is the one lab.toml generates."""

import re

import pytest

from plclab.grade.engine import grade_sources, read_submission
from plclab.grade.feedback import render_feedback
from plclab.grade.lab import list_labs, load_lab, repo_labs_dir
from plclab.grade.scaffold import readme_table

from .lab_contract import CONVERTED

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
    least = 6 if lab_id in CONVERTED else 3  # issue 31's contract, lab by lab
    assert len(lab.files("mistakes")) >= least, f"at least {least} typical mistakes"
    files = sorted(p.name for p in lab.files("mistakes"))
    assert sorted(m.file for m in lab.mistakes) == files, "one [[mistake]] per mistakes/ file"
    for m in lab.mistakes:
        assert m.violates, f"{m.file}: violates = [the criteria it breaks]"
        violated = lab.violated_tests(m)
        points = sum(c.points for c in lab.criteria for s in c.scenarios
                     if f"{s}: {c.name}" in violated)
        assert m.max_score <= lab.max_score - points / 2, (
            f"{m.file}: max_score {m.max_score:g} leaves it more than half of the "
            f"{points:g} points it violates")
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


@pytest.mark.parametrize("lab_id", sorted(CONVERTED))
def test_lab_has_two_correct_variants(lab_id):
    assert len(load_lab(lab_id).files("variants")) >= 2, (
        f"{lab_id}: at least two correct programs written differently in variants/")


@pytest.mark.parametrize("lab_id,name", _files("variants"))
def test_variant_scores_at_least_95_percent(lab_id, name):
    """A correct program written another way (structure, language, tuning) is not punished."""
    lab, res = _grade(lab_id, lab_path(lab_id) / "variants" / name)
    failed = [f"{t.name}: {t.message}" for t in res.tests if not t.passed]
    assert res.status == "ok", res.status
    assert res.score >= 0.95 * lab.max_score - 1e-9, (
        f"{name}: {res.score:g}/{lab.max_score:g} (< 95 %): {failed}")


@pytest.mark.parametrize("lab_id,name", _files("mistakes"))
def test_mistake_scores_less_with_the_right_message(lab_id, name):
    path = lab_path(lab_id) / "mistakes" / name
    expect = EXPECT.search(path.read_text(encoding="utf-8")).group(1)
    lab, res = _grade(lab_id, path)
    assert res.status == "ok"
    assert res.score < res.max_score
    spec = next(m for m in lab.mistakes if m.file == name)
    assert res.score <= spec.max_score, f"{name} scores {res.score:g}, bound {spec.max_score:g}"
    violated = lab.violated_tests(spec)
    tests = [t for t in res.tests if t.name in violated]
    assert len(tests) == len(violated)
    earned, worth = sum(t.score for t in tests), sum(t.max_score for t in tests)
    assert earned <= worth / 2, (
        f"{name} earns {earned:g} of the {worth:g} points of the criteria it violates")
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


def _solutions_with_tests():
    return [(lab_id, name) for lab_id, name in _files("solution")
            if "END_TEST" in (lab_path(lab_id) / "solution" / name).read_text(encoding="utf-8")]


def test_some_solution_has_st_tests():
    assert ("heater-pid", "heater_pid_inc.st") in _solutions_with_tests()


@pytest.mark.parametrize("lab_id,name", _solutions_with_tests())
def test_solution_st_tests_pass(lab_id, name):
    """The TEST blocks of a reference solution (heater-pid's own incremental PID against
    PID_INC) pass."""
    from plclab.testing import run_test_files

    results = run_test_files([str(lab_path(lab_id) / "solution" / name)])
    assert results and all(r.passed for r in results), [str(r) for r in results]


def test_tank_readme_criteria_table_is_generated():
    """The tank lab's README lists its criteria between markers; every README that has the
    markers must hold exactly the table lab.toml generates."""
    from plclab.grade.scaffold import CRITERIA_END, CRITERIA_START

    lab = load_lab("tank-two-position")
    readme = (lab.path / "README.md").read_text(encoding="utf-8")
    assert readme_table(readme, CRITERIA_START, CRITERIA_END) is not None
    assert "max = 8" in lab.criteria_table_markdown()


@pytest.mark.parametrize("lab_id", LABS)
def test_readme_criteria_table_matches_lab_toml(lab_id):
    from plclab.grade.scaffold import CRITERIA_END, CRITERIA_START

    lab = load_lab(lab_id)
    readme = (lab.path / "README.md").read_text(encoding="utf-8")
    table = readme_table(readme, CRITERIA_START, CRITERIA_END)
    if table is not None:
        assert table == lab.criteria_table_markdown(), (
            f"run: plclab lab show {lab_id} --update-readme")
