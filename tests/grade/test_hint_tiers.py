"""Hints in tiers (issue 15): `lab check --hint N` shows 0 nothing, 1 the concept (default),
2 also the literal fix; the grader's feedback shows the concept only."""

from __future__ import annotations

import shutil

import pytest

from plclab.cli import main
from plclab.errors import PlcError
from plclab.grade.feedback import render_feedback
from plclab.grade.gradescope import results_json
from plclab.grade.lab import load_lab

MOTOR = load_lab("motor-start-stop")
NO_SEAL_IN = MOTOR.path / "mistakes" / "no_seal_in.ld"
SEAL_IN = next(c for c in MOTOR.criteria if c.name == "keeps running (seal-in)")


def test_the_lab_splits_the_seal_in_hint_into_concept_and_fix():
    assert SEAL_IN.hint and SEAL_IN.hint_fix
    assert "(START OR K1)" in SEAL_IN.hint_fix and "(START OR K1)" not in SEAL_IN.hint


@pytest.mark.parametrize("level", [0, 1, 2])
def test_lab_check_shows_the_tiers_asked_for(level, capsys):
    assert main(["lab", "check", "motor-start-stop", str(NO_SEAL_IN), "--no-media",
                 "--hint", str(level)]) == 0
    out = capsys.readouterr().out
    assert (SEAL_IN.hint in out) == (level >= 1)
    assert (SEAL_IN.hint_fix in out) == (level == 2)


def test_an_unknown_tier_is_refused(capsys):
    assert main(["lab", "check", "motor-start-stop", str(NO_SEAL_IN), "--hint", "3"]) == 1
    assert "PLC5054" in capsys.readouterr().err


def test_the_grader_shows_the_concept_only():
    from plclab.grade.engine import grade_sources, read_submission

    sources, _ = read_submission(str(NO_SEAL_IN))
    res = grade_sources(MOTOR, sources)
    text = render_feedback(res)
    data = str(results_json(res))
    assert SEAL_IN.hint in text and SEAL_IN.hint in data
    assert SEAL_IN.hint_fix not in text and SEAL_IN.hint_fix not in data


def test_a_fix_without_a_concept_is_a_lab_error(tmp_path):
    lab = tmp_path / "lab"
    shutil.copytree(MOTOR.path, lab)
    toml = lab / "lab.toml"
    text = toml.read_text(encoding="utf-8")
    toml.write_text(text.replace(f'hint = "{SEAL_IN.hint}"\n', "", 1), encoding="utf-8")
    with pytest.raises(PlcError) as e:
        load_lab(str(lab))
    assert e.value.code == "PLC5055"


LITERAL = ("IF ", " THEN", ":=", "END_IF")
"""Marks of a literal fix (a statement or an assignment), which belong in ``hint_fix``."""


def _all_labs():
    from plclab.grade.lab import list_labs

    return [load_lab(p) for p in list_labs([])]


@pytest.mark.parametrize("lab", _all_labs(), ids=lambda lab: lab.id)
def test_every_lab_gives_the_concept_first_and_the_literal_fix_only_in_tier_2(lab):
    for c in lab.criteria:
        if c.hint:
            assert not any(m in c.hint for m in LITERAL), (c.name, c.hint)
        if c.hint_fix:
            assert c.hint and c.hint_fix != c.hint


def test_several_labs_have_a_second_tier():
    labs = [lab.id for lab in _all_labs() if any(c.hint_fix for c in lab.criteria)]
    assert len(labs) >= 8, labs
