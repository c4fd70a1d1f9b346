"""Model answers (course/instructor/answers.toml): every exercise of the course has a worked
solution file or an answer, and every fact an answer states is checked here by plclab itself
(an ST expression, a compile error, the heater model, a plant or lab run, a watch table, the
recipe), with the number in the prose tied to the number checked (``shows``). The checker is
tested on wrong answers it must reject."""

import copy
import re
import tomllib
from pathlib import Path

import pytest

from plclab.course.model import chapters, find_chapter
from plclab.errors import PlcError

ROOT = Path(__file__).resolve().parents[2]
INSTRUCTOR = ROOT / "course" / "instructor"
ANSWERS = tomllib.loads((INSTRUCTOR / "answers.toml").read_text(encoding="utf-8"))["answer"]


def _exercises() -> dict[str, str]:
    """'chapter.n' -> the exercise's text, for every exercise except the quiz line."""
    out = {}
    for c in chapters():
        part = c.text.split("## Exercises", 1)[1].split("\n## ", 1)[0]
        for m in re.finditer(r"^(\d+)\. (.*(?:\n   .*)*)", part, re.M):
            if not re.fullmatch(r"`plclab quiz \d+`.*", m.group(2).strip(), re.S):
                out[f"{c.number}.{m.group(1)}"] = m.group(2)
    return out


def _solution_rows() -> set[str]:
    readme = (INSTRUCTOR / "README.md").read_text(encoding="utf-8")
    out = set()
    for ch, nums in re.findall(r"^\| (\d+) \| ([\d, ]+) \| \[", readme, re.M):
        out |= {f"{ch}.{n.strip()}" for n in nums.split(",")}
    return out


def test_every_exercise_has_a_solution_or_an_answer():
    exercises = _exercises()
    assert len(exercises) >= 66
    covered = _solution_rows() | {a["exercise"] for a in ANSWERS}
    assert sorted(set(exercises) - covered, key=lambda e: tuple(map(int, e.split(".")))) == []
    assert covered <= set(exercises), covered - set(exercises)  # no answer to a lost exercise


def test_each_exercise_is_answered_once_in_answers_toml():
    names = [a["exercise"] for a in ANSWERS]
    assert len(names) == len(set(names))


# ----------------------------------------------------------------------------- the checker

def _heater_model():
    return {"gain": 1.0, "tau": 697.7, "lag": 4.0}


def _close(got: float, want: float, tol: float | None) -> bool:
    return abs(got - want) <= (tol if tol is not None else 1e-6 * max(1.0, abs(want)))


def check(answer: dict, chk: dict) -> None:
    """Raise AssertionError when the check does not hold or the text does not show it."""
    tol = chk.get("tolerance")
    if "shows" in chk:
        assert chk["shows"] in answer["text"], f"{answer['exercise']}: {chk['shows']!r} not in text"
    if "compute" in chk:
        from plclab.course.quiz import evaluate_compute

        got = evaluate_compute(chk["compute"])
        assert _close(got, chk["value"], tol), f"{chk['compute']} = {got}, not {chk['value']}"
    elif "error" in chk:
        from plclab.course.blocks import _produced_codes

        codes, summary = _produced_codes(chk["program"], "answer.st", 1)
        assert codes[:1] == (chk["error"],), f"expected {chk['error']}, got {summary!r}"
    elif "model" in chk:
        from plclab.course.models import step_summary

        got = step_summary(_heater_model(), dict(chk["model"]))
        for key in ("overshoot", "settling"):
            if key in chk:
                assert _close(got[key], chk[key], tol), f"{key}: model {got[key]}, not {chk[key]}"
    elif "plant" in chk:
        from plclab.sim import run

        ch = find_chapter(12)
        spec = next(s for s in ch.figure_specs if s["file"] == chk["plant"])
        src = (ch.folder / "examples" / spec["program"]).read_text(encoding="utf-8")
        old, new = chk["replace"]
        assert old in src
        path = _tmp() / spec["program"]
        path.write_text(src.replace(old, new), encoding="utf-8")
        tr = run([str(path)], plant=spec["plant"], duration=spec["duration"],
                 scenario=spec.get("scenario", {}), seed=int(spec.get("seed", 1)),
                 plant_params=spec.get("plant_params"))
        got = tr.switchings("HEATER")
        assert got == chk["switchings"], f"{got} switchings, not {chk['switchings']}"
    elif "watch" in chk:
        assert _watch_column(chk["watch"], chk["column"]) == chk["values"]
    elif "recipe" in chk:
        from plclab.process import Recipe

        with pytest.raises(PlcError) as e:
            Recipe.juice("Mix").validate(dict(chk["recipe"]), "lemonade")
        assert e.value.code == chk["code"]
    elif "export" in chk:
        xml = _exported(find_chapter(7).folder / chk["export"])
        for text in chk.get("contains", []):
            assert text in xml, f"{text} not in the export of {chk['export']}"
        for text in chk.get("absent", []):
            assert text not in xml, f"{text} in the export of {chk['export']}"
    elif "lab" in chk:
        assert _close(_lab_last_on(chk), chk["last_on"], tol), chk
    else:
        raise AssertionError(f"{answer['exercise']}: a check of an unknown kind: {sorted(chk)}")


_TMP: list[Path] = []


def _tmp() -> Path:
    return _TMP[-1]


@pytest.fixture(autouse=True)
def _tmp_dir(tmp_path):
    _TMP.append(tmp_path)
    yield
    _TMP.pop()


def _exported(path: Path) -> str:
    import subprocess
    import sys

    out = _tmp() / "export.xml"
    subprocess.run([sys.executable, "-m", "plclab", "export", str(path.resolve()), "--to",
                    "plcopen", "--fbd", "-o", str(out)], check=True, capture_output=True)
    return out.read_text(encoding="utf-8")


def _watch_column(edits: list[list[str]], column: str) -> list[str]:
    from plclab.process.watch import WatchTable
    from plclab.project import load

    ex = find_chapter(16).folder / "examples"
    text = (ex / "commissioning.toml").read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    plc = load(str(ex / "tank.st"))
    table = WatchTable.from_dict(tomllib.loads(text), "edited commissioning.toml")
    table.attach(plc)
    plc.scan(3)
    lines = [ln.split() for ln in table.report().splitlines()[1:]]
    k = lines[0].index(column) - 1  # "t (s)" is two words in the header, one in a row
    return [row[k] for row in lines[1:]]


def _lab_last_on(chk: dict) -> float:
    import dataclasses

    import numpy as np

    from plclab.grade.engine import _simulate, compile_submission
    from plclab.grade.lab import load_lab

    lab = load_lab(chk["lab"])
    sc = next(s for s in lab.scenarios if s.name == chk["scenario"])
    src = (INSTRUCTOR / chk["solution"]).read_text(encoding="utf-8")
    compiled, problems, _ = compile_submission(lab, [(src, "answer.st")])
    assert compiled is not None, problems
    tr = _simulate(lab, compiled, dataclasses.replace(sc, duration=40 * 60.0))
    t, v = np.asarray(tr.time), np.asarray(tr[chk["signal"]]).astype(bool)
    assert v.any(), f"{chk['signal']} never on"
    return float(t[v].max())


CHECKS = [(a, c) for a in ANSWERS for c in a.get("check", [])]


@pytest.mark.parametrize("answer,chk", CHECKS,
                         ids=[f"{a['exercise']}-{k}" for k, (a, _) in enumerate(CHECKS)])
def test_an_answers_fact_holds(answer, chk):
    check(answer, chk)


def test_most_answers_with_a_number_are_checked():
    checked = {a["exercise"] for a, _ in CHECKS}
    assert len(checked) >= 20


# ------------------------------------------------------------- wrong answers it must catch

def _first(kind: str) -> tuple[dict, dict]:
    return next((a, copy.deepcopy(c)) for a, c in CHECKS if kind in c)


@pytest.mark.parametrize("kind,change", [
    ("compute", {"value": 1234.5}),
    ("error", {"error": "PLC0100"}),
    ("model", {"overshoot": 40.0}),
    ("watch", {"values": ["TRUE", "TRUE", "TRUE"]}),
    ("recipe", {"recipe": {"orange": 10.0, "water": 90.0, "sugar": 1.0, "flavoring": 0.1}}),
    ("shows", {"shows": "a number the text never says"}),
    ("export", {"export": "../06-ladder/examples/tank.ld"}),
])
def test_the_checker_rejects_a_wrong_answer(kind, change):
    answer, chk = _first(kind)
    chk.update(change)
    with pytest.raises((AssertionError, pytest.fail.Exception)):
        check(answer, chk)


def test_the_checker_rejects_a_text_that_says_another_number():
    answer, chk = _first("compute")
    wrong = dict(answer, text=answer["text"].replace(chk["shows"], "something else"))
    with pytest.raises(AssertionError):
        check(wrong, chk)


def test_the_coverage_test_notices_a_missing_answer(monkeypatch):
    exercises = _exercises()
    covered = _solution_rows() | {a["exercise"] for a in ANSWERS if a["exercise"] != "14.2"}
    assert "14.2" in set(exercises) - covered
