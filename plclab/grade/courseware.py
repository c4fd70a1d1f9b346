"""The courseware a student gets: labs without their private part, examples, notebooks, course.

The repository's ``labs/``, ``examples/``, ``notebooks/`` and ``course/`` are the instructor's
source. A built wheel carries a *student copy* of them in ``plclab/courseware/`` (the build step
:mod:`plclab.grade.courseware_build` calls :func:`copy_courseware`): every lab without ``solution/`` and ``mistakes/``,
and its ``lab.toml`` without the hidden scenarios, the criteria only they use and the
``[[mistake]]`` tables (:func:`student_lab_toml`). See ``docs/adr/0019-installable-labs.md``.

This module imports only the standard library and nothing of plclab, so the build step can load
it by its path in an isolated build environment.
"""

from __future__ import annotations

import json
import math
import shutil
import tomllib
from pathlib import Path
from typing import Any

PRIVATE_DIRS = ("solution", "mistakes", "variants", "private")
"""Sub-folders of a lab that are the instructor's: never shipped, never copied to students."""

INSTRUCTOR_DIRS = ("instructor",)
"""Folders of the course that are the instructor's (``course/instructor``: worked solutions of
the exercises): never shipped, never copied to students."""

STUDENT_FILES = ("README.md", "README.ru.md", "lab.toml", "checks.py", "alarms.toml", "recipes.toml")
"""Files of a lab folder that ship (with ``starter.*`` and ``*_scenario.toml``, a scenario to
run with ``plclab sim --scenario``)."""
COURSEWARE = ("labs", "examples", "notebooks", "course")
"""The folders of the courseware root."""


def courseware_root() -> Path:
    """Where ``labs/``, ``examples/`` and ``notebooks/`` are: the installed student copy
    (``plclab/courseware``) or, in a source checkout, the repository itself."""
    package = Path(__file__).resolve().parents[1]
    installed = package / "courseware"
    return installed if (installed / "labs").is_dir() else package.parent


# ---------------------------------------------------------------------------- lab.toml


def student_lab_data(data: dict[str, Any]) -> dict[str, Any]:
    """A parsed ``lab.toml`` without its private part: hidden scenarios, the criteria that
    only they use (and ``requires`` naming those), ``[[mistake]]`` tables."""
    out = {k: v for k, v in data.items() if k != "mistake"}
    scen = [s for s in data.get("scenario", []) if s.get("visible", True) is not False]
    # a grader that loads this copy knows how many hidden scenarios are not in it (ADR 0040)
    out["hidden_scenarios_withheld"] = len(data.get("scenario", [])) - len(scen)
    names = {s.get("name") for s in scen}
    out["scenario"] = scen
    crits: list[dict[str, Any]] = []
    for c in data.get("criterion", []):
        c = dict(c)
        if "scenarios" in c:
            c["scenarios"] = [s for s in c["scenarios"] if s in names]
            if not c["scenarios"]:
                continue
        elif "scenario" in c and c["scenario"] not in names:
            continue
        crits.append(c)
    where = {c.get("name"): _scenarios_of(c) for c in crits}
    for c in crits:
        if "requires" in c:  # still a criterion, and still checked in one of c's scenarios
            c["requires"] = [r for r in c["requires"]
                             if r in where and where[r] & _scenarios_of(c)]
    out["criterion"] = crits
    return out


def _scenarios_of(criterion: dict[str, Any]) -> set[str]:
    if "scenarios" in criterion:
        return set(criterion["scenarios"])
    return {criterion["scenario"]} if "scenario" in criterion else set()


def student_lab_toml(text: str) -> str:
    """The student copy of a ``lab.toml`` text (see :func:`student_lab_data`)."""
    data = student_lab_data(tomllib.loads(text))
    head = ("# The student copy of this lab, written when plclab was built: the hidden\n"
            "# scenarios, reference solutions and typical mistakes stay with the instructor\n"
            "# (hidden_scenarios_withheld says how many scenarios are missing).\n")
    return head + dumps_toml(data)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} as TOML")


def _key(k: str) -> str:
    bare = k and all(ch.isalnum() or ch in "-_" for ch in k) and k.isascii()
    return k if bare else json.dumps(k)


def _is_table_array(v: Any) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def dumps_toml(data: dict[str, Any]) -> str:
    """Write a parsed lab file back as TOML: keys first, then ``[[arrays]]`` of tables whose
    values are written inline. Comments are not kept."""
    lines = [f"{_key(k)} = {_value(v)}" for k, v in data.items()
             if not _is_table_array(v) and v != []]
    for k, v in data.items():
        if _is_table_array(v):
            for table in v:
                lines += ["", f"[[{_key(k)}]]"]
                lines += [f"{_key(tk)} = {_value(tv)}" for tk, tv in table.items()]
    return "\n".join(lines) + "\n"


def student_texts(text: str, criteria: set[str], scenarios: set[str]) -> str:
    """The student copy of a lab's ``lab.<lang>.toml`` (its texts in a language, ADR 0063):
    only the criteria and scenarios its student ``lab.toml`` keeps, so a hidden criterion's
    name and hint stay with the instructor."""
    data = tomllib.loads(text)
    out = ["# the student copy: the texts of the criteria and scenarios shown to students"]
    for key, value in data.items():
        if isinstance(value, str) or (isinstance(value, list)
                                      and all(isinstance(v, str) for v in value)):
            out.append(f"{_key(key)} = {json.dumps(value, ensure_ascii=False)}")
        elif isinstance(value, list) and all(isinstance(v, dict) for v in value):
            out.append(f"{_key(key)} = [")  # the templates of checks.py's messages
            out += ["  { " + ", ".join(f"{_key(k)} = {json.dumps(x, ensure_ascii=False)}"
                                       for k, x in v.items()) + " }," for v in value]
            out.append("]")
    for table, keep in (("criteria", criteria), ("scenarios", scenarios), ("io", None)):
        for name, entry in data.get(table, {}).items():
            if (keep is not None and name not in keep) or not isinstance(entry, dict):
                continue
            out += ["", f"[{table}.{json.dumps(name, ensure_ascii=False)}]"]
            out += [f"{_key(k)} = {json.dumps(v, ensure_ascii=False)}" for k, v in entry.items()
                    if isinstance(v, str)]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------------------- copying


def copy_student_lab(src: Path, dest: Path) -> Path:
    """Copy one lab folder as a student sees it into *dest* (created): task, I/O table,
    starter, visible scenarios; no solutions, mistakes or hidden scenarios."""
    dest.mkdir(parents=True, exist_ok=True)
    for f in sorted(src.iterdir()):
        if f.is_dir() or f.name.startswith("."):
            continue
        if f.name == "lab.toml":
            text = f.read_text(encoding="utf-8-sig")
            (dest / f.name).write_text(student_lab_toml(text), encoding="utf-8")
        elif (f.name in STUDENT_FILES or f.name.startswith("starter.")
              or f.name.endswith("_scenario.toml")):
            shutil.copyfile(f, dest / f.name)
    for f in sorted(src.glob("lab.*.toml")):  # a language's texts: the student part (ADR 0063)
        data = student_lab_data(tomllib.loads((src / "lab.toml").read_text(encoding="utf-8-sig")))
        (dest / f.name).write_text(student_texts(
            f.read_text(encoding="utf-8-sig"), {c.get("name") for c in data["criterion"]},
            {sc.get("name") for sc in data["scenario"]}), encoding="utf-8")
    return dest


def copy_courseware(root: Path, dest: Path) -> list[Path]:
    """Write the student copy of the courseware under *root* to *dest*: ``labs/`` (each lab
    by :func:`copy_student_lab`, another folder of ``labs/`` as it is), ``examples/``, ``course/``
    (as it is: a quiz's keys are its feedback) and the notebooks.
    Returns the files written."""
    if dest.exists():
        shutil.rmtree(dest)
    labs = root / "labs"
    for sub in sorted(labs.iterdir()) if labs.is_dir() else []:
        if (sub / "lab.toml").is_file():
            copy_student_lab(sub, dest / "labs" / sub.name)
        elif sub.is_dir() and sub.name not in PRIVATE_DIRS:  # shared files of a course
            shutil.copytree(sub, dest / "labs" / sub.name,
                            ignore=shutil.ignore_patterns("__pycache__", ".*"))
    for folder in ("examples", "course"):  # the course: chapters, examples, figure specs, quizzes
        if (root / folder).is_dir():  # course/instructor (worked solutions) stays behind
            shutil.copytree(root / folder, dest / folder,
                            ignore=shutil.ignore_patterns("__pycache__", ".*", *INSTRUCTOR_DIRS))
    nb = root / "notebooks"
    for f in sorted(nb.glob("*.ipynb")) if nb.is_dir() else []:
        (dest / "notebooks").mkdir(parents=True, exist_ok=True)
        shutil.copyfile(f, dest / "notebooks" / f.name)
    return sorted(p for p in dest.rglob("*") if p.is_file())
