"""Lab feedback for an SFC program that did not advance: the scenario names the active step,
its outgoing transitions and the values of their conditions at the end (ADR 0023)."""

from __future__ import annotations

from plclab.grade.engine import grade_sources, read_submission
from plclab.grade.feedback import render_feedback
from plclab.grade.lab import load_lab


def test_the_feedback_of_a_stuck_chart_says_why_it_did_not_advance():
    lab = load_lab("washing-machine")
    sources, _ = read_submission(lab.path / "starter.st")
    res = grade_sources(lab, sources, scenarios=["silk"])
    text = render_feedback(res)
    assert "At the end: Washer is in step Start" in text
    assert "to Fill when 'START_PB': FALSE (START_PB = FALSE)" in text


def test_a_passing_scenario_has_no_such_note():
    lab = load_lab("washing-machine")
    sources, _ = read_submission(lab.path / "solution" / "washer.st")
    res = grade_sources(lab, sources, scenarios=["silk"])
    assert res.score == res.max_score
    assert "At the end:" not in render_feedback(res)
