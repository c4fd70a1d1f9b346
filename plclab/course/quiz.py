"""Quizzes: the items of a chapter's ``quiz.toml``, grading an answer, and checking the keys.

Four kinds of item (the keys of each are in ``course/README.md``):

* ``choice``  - multiple choice; ``answer`` is the 1-based number of the right choice.
* ``numeric`` - a number within ``tolerance``; ``compute`` is an ST expression (or ``program``
  plus ``show``) that plclab evaluates, so the key is recomputed, never trusted.
* ``output``  - "what does this program output": ``program`` is run (``set`` inputs, ``scans``
  scans or ``run`` virtual time) and the value of ``show`` is the answer.
  ``filename`` (``quiz.st`` by default; ``answer.st`` for ``write``) chooses the language of
  ``program``, ``solution`` and the student's answer: ``quiz.ld``, ``quiz.il``, ``answer.ld``.
* ``write``   - "write a program": the answer is a program, graded by a mini-scenario of
  ``step`` tables (``set``, ``scans`` or ``run``, ``expect``); the key is a ``solution`` that
  must pass it and ``wrong`` programs that must fail it.

``check_quiz`` validates every key; ``ask`` runs a quiz in the terminal, ``quiz_cell`` in a
notebook cell (answers given as a dict, so the notebook also runs headless).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import PlcError
from .model import Chapter, course_error, find_chapter

KINDS = ("choice", "numeric", "output", "write")
_ITEM_KEYS = {
    "choice": {"choices", "answer"},
    "numeric": {"answer"},
    "output": {"program", "show"},
    "write": {"solution", "step"},
}


@dataclass
class Item:
    """One quiz item, validated for its kind's keys."""

    chapter: str
    number: int
    data: dict[str, Any] = field(repr=False)

    @property
    def kind(self) -> str:
        return self.data["kind"]

    @property
    def id(self) -> str:
        return self.data.get("id", f"{self.chapter}#{self.number}")

    @property
    def question(self) -> str:
        return self.data["question"].strip()

    @property
    def explain(self) -> str:
        return self.data["explain"].strip()


def items(chapter: Chapter) -> list[Item]:
    """The chapter's quiz items; a missing key or an unknown kind is a course error."""
    out = []
    for n, d in enumerate(chapter.quiz_data.get("item", []), 1):
        where = f"course/{chapter.slug}/quiz.toml item {n} ({d.get('id', '?')})"
        kind = d.get("kind")
        if kind not in KINDS:
            raise course_error(f"{where}: kind must be one of {', '.join(KINDS)}, not {kind!r}")
        missing = ({"question", "explain"} | _ITEM_KEYS[kind]) - set(d)
        if kind == "numeric" and not ({"compute", "program"} & set(d)):
            missing.add("compute (or program + show)")
        if missing:
            raise course_error(f"{where}: missing {', '.join(sorted(missing))}")
        out.append(Item(chapter.slug, n, d))
    return out


# ---------------------------------------------------------------------------- running programs

def _plc(program: str, filename: str = "quiz.st", cycle: str = "10ms"):
    from ..project import loads

    return loads(program, filename, cycle_time=cycle)


def _drive(plc: Any, step: dict[str, Any]) -> None:
    for name, value in step.get("set", {}).items():
        plc[name] = value
    if "run" in step:
        plc.run(seconds=step["run"])
    else:
        plc.scan(int(step.get("scans", 1)))


def _ran(data: dict[str, Any]) -> Any:
    plc = _plc(data["program"], data.get("filename", "quiz.st"), cycle=data.get("cycle", "10ms"))
    _drive(plc, data)
    return plc


def evaluate_output(data: dict[str, Any]) -> str:
    """Run an ``output`` item's program; the value of ``show`` as an IEC literal."""
    return _ran(data).format(data["show"])


def evaluate_compute(expr: str) -> float:
    """An ST expression evaluated by a real PLC as LREAL."""
    plc = _plc(f"PROGRAM Quiz\nVAR r : LREAL; END_VAR\nr := {expr};\nEND_PROGRAM\n")
    plc.scan()
    return float(plc["Quiz.r"])


def numeric_key(data: dict[str, Any]) -> float:
    """The recomputed answer of a ``numeric`` item."""
    if "compute" in data:
        return evaluate_compute(data["compute"])
    value = _ran(data)[data["show"]]  # TIME is a whole number of ms
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise course_error(f"numeric item: {data['show']} is {value!r}, not a number")
    return float(value)


def _number(text: str) -> float:
    t = text.strip().replace("_", "")
    if "#" in t:
        t = t.split("#", 1)[1]
    return float(t)


def run_scenario(program: str, steps: list[dict[str, Any]], filename: str = "answer.st",
                 cycle: str = "10ms") -> list[str]:
    """Grade a written program: the problems found (empty: it passes)."""
    try:
        plc = _plc(program, filename, cycle)
    except PlcError as e:
        return [f"it does not compile: {e}"]
    for k, step in enumerate(steps, 1):
        try:
            _drive(plc, step)
        except PlcError as e:
            return [f"step {k}: {e}"]
        for name, want in step.get("expect", {}).items():
            try:
                got = plc[name]
            except PlcError as e:
                return [f"step {k}: {e}"]
            if not _same(got, want):
                return [f"step {k} ({_describe(step)}): {name} is {plc.format(name)}, "
                        f"expected {_lit(want)}"]
    return []


def _describe(step: dict[str, Any]) -> str:
    parts = [f"{n} := {_lit(v)}" for n, v in step.get("set", {}).items()]
    parts.append(f"run {step['run']}" if "run" in step else f"{step.get('scans', 1)} scan(s)")
    return ", ".join(parts)


def _lit(v: Any) -> str:
    return ("TRUE" if v else "FALSE") if isinstance(v, bool) else str(v)


def _same(got: Any, want: Any, tol: float = 1e-6) -> bool:
    if isinstance(want, bool) or isinstance(got, bool):
        return bool(got) == bool(want) and isinstance(got, bool) == isinstance(want, bool)
    if isinstance(want, int | float) and isinstance(got, int | float):
        return math.isclose(got, want, rel_tol=tol, abs_tol=tol)
    return str(got) == str(want)


# ------------------------------------------------------------------------------------ grading

@dataclass
class Verdict:
    right: bool
    feedback: str


def grade(item: Item, answer: str) -> Verdict:
    """Grade one answer (a choice number, a number, a value, or program text)."""
    d = item.data
    a = answer.strip()
    if item.kind == "choice":
        right = a == str(d["answer"])
        key = f"{d['answer']}. {d['choices'][d['answer'] - 1]}"
    elif item.kind == "numeric":
        want = numeric_key(d)
        key = f"{want:g}{' ' + d['unit'] if 'unit' in d else ''}"
        try:
            right = abs(float(a.replace(",", ".").split()[0]) - want) <= float(
                d.get("tolerance", 1e-6 * max(1.0, abs(want))))
        except (ValueError, IndexError):
            right = False
    elif item.kind == "output":
        key = evaluate_output(d)
        right = _same_literal(a, key)
    else:
        problems = run_scenario(a, d["step"], d.get("filename", "answer.st"))
        right = not problems
        key = "a program that passes the scenario" + (f"; {problems[0]}" if problems else "")
    head = "right." if right else f"not quite: {key}."
    return Verdict(right, f"{head} {item.explain}")


def _same_literal(answer: str, key: str) -> bool:
    a, k = answer.strip().upper(), key.strip().upper()
    bools = {"1": "TRUE", "0": "FALSE", "TRUE": "TRUE", "FALSE": "FALSE"}
    if k in ("TRUE", "FALSE"):
        return bools.get(a) == k
    try:
        return math.isclose(_number(a), _number(k), rel_tol=1e-6, abs_tol=1e-9)
    except ValueError:
        return a.replace(" ", "") == k.replace(" ", "")


# ------------------------------------------------------------------------------- key checking

def check_item(item: Item) -> list[str]:
    """Problems with an item's key (empty: the key is valid)."""
    d = item.data
    where = f"course/{item.chapter}/quiz.toml {item.id}"
    try:
        if item.kind == "choice":
            if not (isinstance(d["answer"], int) and 1 <= d["answer"] <= len(d["choices"])):
                return [f"{where}: answer must number one of the {len(d['choices'])} choices"]
            if len(set(d["choices"])) != len(d["choices"]):
                return [f"{where}: two choices are the same"]
        elif item.kind == "numeric":
            got = numeric_key(d)
            tol = float(d.get("tolerance", 1e-6 * max(1.0, abs(got))))
            if abs(got - float(d["answer"])) > tol:
                return [f"{where}: the key says {d['answer']} but plclab computes {got:g}"]
        elif item.kind == "output":
            got = evaluate_output(d)
            if "answer" in d and not _same_literal(str(d["answer"]), got):
                return [f"{where}: the key says {d['answer']} but the program shows {got}"]
        else:
            fn = d.get("filename", "answer.st")
            problems = run_scenario(d["solution"], d["step"], fn)
            if problems:
                return [f"{where}: the solution fails its scenario: {problems[0]}"]
            for k, wrong in enumerate(d.get("wrong", []), 1):
                if not run_scenario(wrong, d["step"], fn):
                    return [f"{where}: wrong program {k} passes the scenario; the scenario "
                            "does not tell them apart"]
    except PlcError as e:
        return [f"{where}: {e}"]
    return []


def check_quiz(chapter: Chapter) -> tuple[int, list[str]]:
    """(number of items, problems) for one chapter's quiz."""
    its = items(chapter)
    problems = [p for it in its for p in check_item(it)]
    return len(its), problems


# -------------------------------------------------------------------------------- the terminal

def _show(n: int, it: Item, print_fn: Callable[[str], None]) -> None:
    print_fn(f"{n}. {it.question}")
    if it.kind == "choice":
        for k, c in enumerate(it.data["choices"], 1):
            print_fn(f"   {k}) {c}")
    elif it.kind == "output":
        print_fn(_indent(it.data["program"]))
    elif it.kind == "write":
        if "starter" in it.data:
            print_fn("   Starter:\n" + _indent(it.data["starter"]))
        print_fn("   Answer with the path of your program file (or the program itself).")


def ask(chapter: Chapter, input_fn: Callable[[str], str] = input,
        print_fn: Callable[[str], None] = print) -> tuple[int, int]:
    """Ask every item of a chapter's quiz; print feedback; return (right, total)."""
    its = items(chapter)
    right = 0
    print_fn(f"Quiz: {chapter.title} ({len(its)} questions; an empty answer skips)\n")
    for n, it in enumerate(its, 1):
        _show(n, it, print_fn)
        try:
            answer = input_fn("   your answer: ")
        except EOFError:
            answer = ""
        if not answer.strip():
            print_fn("   skipped.\n")
            continue
        if it.kind == "write":
            answer = _read_program(answer)
        v = grade(it, answer)
        right += v.right
        print_fn(f"   {v.feedback}\n")
    print_fn(f"score: {right}/{len(its)}")
    return right, len(its)


def quiz_cell(chapter: Chapter | int | str, answers: dict[Any, Any] | None = None,
              course_dir: str | None = None,
              print_fn: Callable[[str], None] = print) -> tuple[int, int]:
    """The quiz of a notebook cell: never reads stdin, so the notebook also runs headless.
    ``answers`` maps a question's number (or its id) to the answer; the questions are printed,
    each answered one with its feedback. Returns (right, total).

    >>> from plclab.course.model import find_chapter
    >>> right, total = quiz_cell(find_chapter(2), {1: "2"}, print_fn=lambda s: None)
    >>> right, total >= 1
    (1, True)
    """
    ch = chapter if isinstance(chapter, Chapter) else find_chapter(chapter, course_dir)
    its = items(ch)
    answers = answers or {}
    right = answered = 0
    print_fn(f"Quiz: chapter {ch.number}, {ch.title} ({len(its)} questions). Put your answers "
             "in `answers` ({1: \"2\", ...}) and run the cell again.\n")
    for n, it in enumerate(its, 1):
        _show(n, it, print_fn)
        a = answers.get(n, answers.get(it.id))
        if a is None or not str(a).strip():
            print_fn("   (not answered yet)\n")
            continue
        text = _read_program(str(a)) if it.kind == "write" else str(a)
        v = grade(it, text)
        right += v.right
        answered += 1
        print_fn(f"   your answer: {str(a).strip()[:60]}\n   {v.feedback}\n")
    # not "score: n/m", which is the lab's score in the same notebook
    print_fn(f"quiz: {right} right of {len(its)} ({answered} answered)")
    return right, len(its)


def _read_program(path: str) -> str:
    from pathlib import Path

    p = Path(path.strip())
    try:
        return p.read_text(encoding="utf-8")
    except OSError:
        return path  # the program itself was typed or pasted


def _indent(text: str) -> str:
    return "\n".join("      " + line for line in text.strip().splitlines())
