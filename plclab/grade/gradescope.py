"""Outputs for instructors: Gradescope's ``results.json`` and the class gradebook CSV.

``results.json`` follows the Gradescope autograder specification: top-level ``score``,
``execution_time``, ``output``, ``output_format``, ``visibility``, ``stdout_visibility`` and
``tests``, each test with ``name``, ``number``, ``score``, ``max_score``, ``status``
("passed"/"failed"), ``output``, ``output_format`` and ``visibility`` ("visible", or
"after_published" for the tests of hidden scenarios, whose output is only passed/failed).

Every file is written atomically (a temporary file, then ``os.replace``), so an interrupted
run never leaves half a file behind.
"""

from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .feedback import hidden_output
from .safety import clean_text, csv_cell, md_fence

VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")
STATUSES = ("passed", "failed")
OUTPUT_FORMATS = ("text", "html", "simple_format", "md", "ansi")

SCHEMA: dict[str, Any] = {
    "type": "object",
    "required": ["tests"],
    "properties": {
        "score": {"type": "number"},
        "execution_time": {"type": "number", "minimum": 0},
        "output": {"type": "string"},
        "output_format": {"enum": list(OUTPUT_FORMATS)},
        "visibility": {"enum": list(VISIBILITIES)},
        "stdout_visibility": {"enum": list(VISIBILITIES)},
        "extra_data": {"type": "object"},
        "tests": {
            "type": "array",
            "items": {
                "type": "object",
                "required": ["name", "score", "max_score", "status", "output", "visibility"],
                "properties": {
                    "name": {"type": "string"},
                    "name_format": {"enum": list(OUTPUT_FORMATS)},
                    "number": {"type": "string"},
                    "score": {"type": "number", "minimum": 0},
                    "max_score": {"type": "number", "minimum": 0},
                    "status": {"enum": list(STATUSES)},
                    "output": {"type": "string"},
                    "output_format": {"enum": list(OUTPUT_FORMATS)},
                    "tags": {"type": "array", "items": {"type": "string"}},
                    "visibility": {"enum": list(VISIBILITIES)},
                    "extra_data": {"type": "object"},
                },
                "additionalProperties": False,
            },
        },
        "leaderboard": {"type": "array"},
    },
    "additionalProperties": False,
}
"""A JSON Schema of the results.json shape (usable with the jsonschema package)."""


def results_json(result: Any) -> dict[str, Any]:
    """The Gradescope ``results.json`` of a :class:`~plclab.grade.engine.Result`."""
    tests = []
    for t in result.tests:
        if t.visible:
            out = t.message if t.passed else t.message + (f"\n\nHint: {t.hint}" if t.hint else "")
        else:
            out = hidden_output(t)
        tests.append({
            "name": t.name,
            "number": t.number,
            "score": float(t.score),
            "max_score": float(t.max_score),
            "status": "passed" if t.passed else "failed",
            "output": out,
            "output_format": "md",
            "tags": [t.scenario],
            "visibility": "visible" if t.visible else "after_published",
        })
    head = [f"Score {result.score:g} / {result.max_score:g}"]
    if result.capped:
        names = sorted({t.criterion for t in result.critical_failures})
        head.append(f"Capped at {result.critical_cap:.0%} of the points (the tests add up to "
                    f"{result.points:g}): a critical requirement failed: "
                    + "; ".join(clean_text(n, 200) for n in names))
    if result.status != "ok":
        head.append(f"status: {result.status}")
    if result.message:
        head.append(result.message)
    if result.diagnostics:
        shown = result.diagnostics[:20]
        more = len(result.diagnostics) - len(shown)
        head.append("\n".join(md_fence([clean_text(d, 4000) for d in shown]
                                        + ([f"... and {more} more"] if more else []))))
    for s in result.scenarios:
        if s.visible:
            head += s.notes
    return {
        "score": float(result.score),
        "execution_time": round(float(result.execution_time), 3),
        "output": "\n\n".join(head),
        "output_format": "md",
        "visibility": "visible",
        "stdout_visibility": "hidden",
        "tests": tests,
    }


def validate_results(data: Any) -> list[str]:
    """Problems of a results.json object against :data:`SCHEMA` (empty list: valid).

    Pure Python, so it needs no jsonschema package.
    """
    problems: list[str] = []

    def check(obj: Any, schema: dict[str, Any], where: str) -> None:
        if "enum" in schema:
            if obj not in schema["enum"]:
                problems.append(f"{where}: {obj!r} is not one of {schema['enum']}")
            return
        ty = schema.get("type")
        types = {"object": dict, "array": list, "string": str}
        if ty == "number":
            if isinstance(obj, bool) or not isinstance(obj, int | float):
                problems.append(f"{where}: {obj!r} is not a number")
            elif "minimum" in schema and obj < schema["minimum"]:
                problems.append(f"{where}: {obj!r} is below {schema['minimum']}")
            return
        if ty in types and not isinstance(obj, types[ty]):
            problems.append(f"{where}: {type(obj).__name__} instead of {ty}")
            return
        if ty == "object":
            for k in schema.get("required", []):
                if k not in obj:
                    problems.append(f"{where}: '{k}' is missing")
            props = schema.get("properties", {})
            for k, v in obj.items():
                if k in props:
                    check(v, props[k], f"{where}.{k}")
                elif schema.get("additionalProperties") is False:
                    problems.append(f"{where}: unknown key '{k}'")
        elif ty == "array" and "items" in schema:
            for i, x in enumerate(obj):
                check(x, schema["items"], f"{where}[{i}]")

    check(data, SCHEMA, "results")
    if isinstance(data, dict) and isinstance(data.get("tests"), list) and "score" in data:
        total = sum(t.get("score", 0) for t in data["tests"] if isinstance(t, dict))
        if data["score"] > total + 1e-6:  # lower only when a critical criterion capped it
            problems.append(f"results.score {data['score']} is more than the sum of the "
                            f"tests {total}")
    return problems


# ---------------------------------------------------------------------------- files


def write_atomic(path: str | os.PathLike, text: str) -> None:
    """Write text (UTF-8, newlines as given) to ``path`` atomically (:func:`write_bytes_atomic`)."""
    write_bytes_atomic(path, text.encode("utf-8"))


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write bytes to ``path`` through a temporary file and ``os.replace``."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    tmp = p.with_name(f".{p.name}.{os.getpid()}.tmp")
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, p)


def write_json(path: str | os.PathLike, data: Any) -> None:
    write_atomic(path, json.dumps(data, indent=2, ensure_ascii=False) + "\n")


def gradebook_csv(results: Iterable[Any], test_names: list[str]) -> str:
    """The class gradebook: student, score, max, status, then one column per test.

    Text cells never start a spreadsheet formula (:func:`~plclab.grade.safety.csv_cell`)."""
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["student", "score", "max", "status"] + [csv_cell(n) for n in test_names])
    for r in sorted(results, key=lambda r: r.student):
        by_name = {t.name: t.score for t in r.tests}
        w.writerow([csv_cell(clean_text(r.student)), f"{r.score:g}", f"{r.max_score:g}",
                    csv_cell(r.status)]
                   + [f"{by_name[n]:g}" if n in by_name else "" for n in test_names])
    return buf.getvalue()
