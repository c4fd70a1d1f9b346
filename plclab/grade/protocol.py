"""What a grading child may tell the grader, and how the grader checks it.

The child sends JSON (never pickle: unpickling what a child sent would let a compromised
child run code in the grader) as length-prefixed messages on its pipe:

* ``["compiled", [diagnostic, ...]]``
* ``["media", file name, base64 bytes]`` -- a PNG diagram or an ``.rrd`` recording it drew in
  its own temporary folder; the grader checks name, kind, size and total, and writes it;
* ``["scenario", run, [test, ...]]`` -- one scenario's outcome, as soon as it is known;
* ``["log", text]``, ``["done", result]``, ``["memory"]``, ``["error", text]``.

:class:`Inbox` (in the grader) accepts a message only when it has the expected shape and
types, every score is within 0..points of its criterion, names are the lab's, strings and lists
are within :data:`LIMITS` and pictures are what they claim to be. It builds the
:class:`~plclab.grade.engine.Result` from the lab's own structure, taking from the child only
what the child measures (pass/fail, score, messages, times); anything else raises
:class:`Rejected` and nothing that child sent counts.
"""

from __future__ import annotations

import base64
import binascii
import json
import math
import re
from pathlib import Path
from typing import Any

from .engine import STATUSES, Result, ScenarioRun, TestResult
from .lab import Lab

LIMITS = {
    "message": 24 * 2**20,   # bytes of one message on the pipe
    "text": 4000,            # characters of one string
    "notes": 20,             # notes of one scenario
    "diagnostics": 300,      # compiler messages of one submission (after the per-file cap)
    "png": 2 * 2**20,        # bytes of one diagram
    "rrd": 16 * 2**20,       # bytes of one recording
    "media_total": 48 * 2**20,
    "media_files": 200,
    "log": 16 * 2**10,       # characters of the child's log kept
}
"""Caps on what one child may send; beyond them the child's results are rejected."""

MAGIC = {".png": (b"\x89PNG\r\n\x1a\n",), ".rrd": (b"RRF",)}
INFRA_RETRIES = 2
"""Times a submission is graded again when its process was killed from outside (ADR 0040)."""

MEDIA_NAME = re.compile(r"^[a-z0-9][a-z0-9-]{0,120}\.(png|rrd)$")
_CODE = re.compile(r"^(PLC\d{4})?$")


class Rejected(ValueError):
    """A message of a child that the grader does not accept."""


# ---------------------------------------------------------------------------- the child side


def clip(obj: Any, limit: int = LIMITS["text"]) -> Any:
    """``obj`` with every string cut to ``limit`` characters and non-finite floats as None
    (the child applies it, so an honest child never sends what the grader rejects)."""
    if isinstance(obj, str):
        return obj if len(obj) <= limit else obj[:limit - 1] + "…"
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: clip(v, limit) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [clip(v, limit) for v in obj]
    return obj


def encode(kind: str, *payload: Any) -> bytes:
    """One message as bytes (strings clipped)."""
    return json.dumps([kind, *clip(list(payload))], allow_nan=False).encode("utf-8")


def encode_media(path: Path) -> bytes | None:
    """A ``media`` message for a file the child drew, or None when it is over the caps."""
    kind = path.suffix.lower()
    try:
        size = path.stat().st_size
    except OSError:
        return None
    if kind not in MAGIC or size > LIMITS[kind[1:]]:
        return None
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return json.dumps(["media", path.name, data]).encode("utf-8")


# ---------------------------------------------------------------------------- the grader side


def _text(v: Any, what: str, limit: int = LIMITS["text"]) -> str:
    if not isinstance(v, str):
        raise Rejected(f"{what}: a string expected, got {type(v).__name__}")
    if len(v) > limit:
        raise Rejected(f"{what}: {len(v)} characters (at most {limit})")
    return v


def _texts(v: Any, what: str, most: int) -> list[str]:
    if not isinstance(v, list):
        raise Rejected(f"{what}: a list expected, got {type(v).__name__}")
    if len(v) > most:
        raise Rejected(f"{what}: {len(v)} items (at most {most})")
    return [_text(x, f"{what}[{i}]") for i, x in enumerate(v)]


def _number(v: Any, what: str, lo: float = 0.0, hi: float = math.inf,
            optional: bool = False) -> float | None:
    if v is None and optional:
        return None
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise Rejected(f"{what}: a number expected, got {type(v).__name__}")
    x = float(v)
    if not math.isfinite(x) or not lo <= x <= hi:
        raise Rejected(f"{what}: {x!r} is outside {lo:g}..{hi:g}")
    return x


def _bool(v: Any, what: str) -> bool:
    if not isinstance(v, bool):
        raise Rejected(f"{what}: true or false expected, got {type(v).__name__}")
    return v


def _obj(v: Any, what: str) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise Rejected(f"{what}: an object expected, got {type(v).__name__}")
    return v


class Inbox:
    """The messages of one grading child, checked against the lab (see the module doc).

    ``media_dir`` is where accepted pictures are written (None: pictures are refused)."""

    def __init__(self, lab: Lab, media_dir: Path | None) -> None:
        self.lab = lab
        self.media_dir = media_dir
        self.media: set[str] = set()
        self.media_bytes = 0
        self.diags: list[str] | None = None
        self.scenarios: list[ScenarioRun] = []
        self.tests: list[TestResult] = []
        self.done: Result | None = None
        self.failure: tuple[str, str] | None = None
        self.log = ""
        self.numbers = {s.name: i for i, s in enumerate(lab.scenarios, 1)}

    # -- one message
    def receive(self, raw: bytes) -> None:
        """Check and take one message (raises :class:`Rejected`)."""
        try:
            msg = json.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, ValueError, RecursionError) as e:
            raise Rejected(f"not JSON ({type(e).__name__})") from None
        if not isinstance(msg, list) or not msg or not isinstance(msg[0], str):
            raise Rejected("a message is a list starting with its kind")
        kind, args = msg[0], msg[1:]
        handler = {"compiled": self._compiled, "media": self._media, "scenario": self._scenario,
                   "log": self._log, "done": self._done, "memory": self._memory,
                   "error": self._error}.get(kind)
        if handler is None:
            raise Rejected(f"unknown message kind {kind[:40]!r}")
        if self.done is not None or self.failure is not None:
            raise Rejected(f"'{kind[:40]}' after the final message")
        handler(*self._arity(kind, args))

    @staticmethod
    def _arity(kind: str, args: list[Any]) -> list[Any]:
        want = {"compiled": 1, "media": 2, "scenario": 2, "log": 1, "done": 1, "memory": 0,
                "error": 1}[kind]
        if len(args) != want:
            raise Rejected(f"'{kind}' takes {want} values, got {len(args)}")
        return args

    def _compiled(self, diags: Any) -> None:
        if self.diags is not None:
            raise Rejected("'compiled' sent twice")
        self.diags = _texts(diags, "diagnostics", LIMITS["diagnostics"])

    def _log(self, text: Any) -> None:
        self.log = _text(text, "log", LIMITS["log"])

    def _memory(self) -> None:
        self.failure = ("memory", "")

    def _error(self, text: Any) -> None:
        self.failure = ("error", _text(text, "error"))

    def _media(self, name: Any, data: Any) -> None:
        name = _text(name, "media name", 200)
        if self.media_dir is None:
            raise Rejected("media sent although none were asked for")
        if not MEDIA_NAME.match(name):
            raise Rejected(f"media name {name[:60]!r} is not a diagram or recording name")
        if name in self.media:
            raise Rejected(f"media {name} sent twice")
        kind = name[name.rindex("."):]
        if not isinstance(data, str) or len(data) > LIMITS[kind[1:]] * 4 // 3 + 8:
            raise Rejected(f"media {name}: too large or not text")
        try:
            blob = base64.b64decode(data, validate=True)
        except (binascii.Error, ValueError):
            raise Rejected(f"media {name}: not base64") from None
        if len(blob) > LIMITS[kind[1:]]:
            raise Rejected(f"media {name}: {len(blob)} bytes (at most {LIMITS[kind[1:]]})")
        if not blob.startswith(MAGIC[kind]):
            raise Rejected(f"media {name}: not a {kind[1:].upper()} file")
        if len(self.media) >= LIMITS["media_files"]:
            raise Rejected("too many media files")
        self.media_bytes += len(blob)
        if self.media_bytes > LIMITS["media_total"]:
            raise Rejected("media larger than allowed in all")
        from .gradescope import write_bytes_atomic

        write_bytes_atomic(self.media_dir / name, blob)
        self.media.add(name)

    def _scenario(self, run: Any, tests: Any) -> None:
        run_obj = self._run(run)
        if any(s.name == run_obj.name for s in self.scenarios):
            raise Rejected(f"scenario {run_obj.name} sent twice")
        self.tests += self._tests(run_obj.name, tests)
        self.scenarios.append(run_obj)

    def _done(self, result: Any) -> None:
        d = _obj(result, "result")
        if d.get("lab_id") != self.lab.id:
            raise Rejected("result of another lab")
        status = d.get("status")
        if status not in STATUSES:
            raise Rejected(f"status {str(status)[:40]!r}")
        runs = d.get("scenarios")
        if not isinstance(runs, list) or len(runs) > len(self.lab.scenarios):
            raise Rejected("scenarios: a list of the lab's scenarios expected")
        tests_by: dict[str, list[Any]] = {}
        all_tests = d.get("tests")
        if not isinstance(all_tests, list):
            raise Rejected("tests: a list expected")
        for t in all_tests:
            tests_by.setdefault(str(_obj(t, "test").get("scenario"))[:200], []).append(t)
        res = Result(self.lab.id, status=status, lab_title=self.lab.title,
                     critical_cap=self.lab.critical_cap, message=_text(d.get("message", ""), "message"),
                     diagnostics=_texts(d.get("diagnostics", []), "diagnostics",
                                        LIMITS["diagnostics"]))
        seen: set[str] = set()
        for r in runs:
            run_obj = self._run(r)
            if run_obj.name in seen:
                raise Rejected(f"scenario {run_obj.name} twice in the result")
            seen.add(run_obj.name)
            res.scenarios.append(run_obj)
            res.tests += self._tests(run_obj.name, tests_by.pop(run_obj.name, []))
        if tests_by:
            raise Rejected("tests of scenarios that are not in the result")
        self.done = res

    # -- pieces
    def _run(self, d: Any) -> ScenarioRun:
        d = _obj(d, "scenario")
        name = d.get("name")
        spec = next((s for s in self.lab.scenarios if s.name == name), None)
        if spec is None:
            raise Rejected(f"unknown scenario {str(name)[:60]!r}")
        rrd = d.get("rrd")
        if rrd is not None and (rrd not in self.media or not str(rrd).endswith(".rrd")):
            raise Rejected(f"scenario {spec.name}: recording {str(rrd)[:60]!r} was not sent")
        code = _text(d.get("code", ""), "code", 8)
        if not _CODE.match(code):
            raise Rejected(f"scenario {spec.name}: code {code!r}")
        return ScenarioRun(spec.name, spec.description, spec.visible,
                           _bool(d.get("ran"), "ran"), _text(d.get("error", ""), "error"),
                           _texts(d.get("notes", []), "notes", LIMITS["notes"]),
                           _number(d.get("duration", 0.0), "duration") or 0.0,
                           _number(d.get("wall_s", 0.0), "wall_s") or 0.0, rrd,
                           _text(d.get("rrd_note", ""), "rrd_note"), code)

    def _tests(self, scenario: str, tests: Any) -> list[TestResult]:
        if not isinstance(tests, list):
            raise Rejected("tests: a list expected")
        crits = self.lab.criteria_for(scenario)
        if len(tests) != len(crits):
            raise Rejected(f"scenario {scenario}: {len(tests)} tests for {len(crits)} criteria")
        spec = self.lab.scenario(scenario)
        number = self.numbers[scenario]
        out = []
        for j, (c, t) in enumerate(zip(crits, tests, strict=True), 1):
            t = _obj(t, "test")
            what = f"test '{scenario}: {c.name}'"
            if t.get("scenario") != scenario or t.get("criterion") != c.name:
                raise Rejected(f"{what}: sent for another criterion")
            passed = _bool(t.get("passed"), f"{what}.passed")
            score = _number(t.get("score"), f"{what}.score", 0.0, c.points) or 0.0
            if not passed and score:
                raise Rejected(f"{what}: failed with a score of {score:g}")
            diagram = t.get("diagram")
            if diagram is not None and (diagram not in self.media
                                        or not str(diagram).endswith(".png")):
                raise Rejected(f"{what}: diagram {str(diagram)[:60]!r} was not sent")
            t_fail = t.get("t_fail")
            t_fail = None if t_fail is None else _number(t_fail, f"{what}.t_fail", -math.inf)
            out.append(TestResult(f"{scenario}: {c.name}", scenario, c.name, score, c.points,
                                  passed, _text(t.get("message", ""), f"{what}.message"),
                                  _text(t.get("detail", ""), f"{what}.detail"), t_fail,
                                  spec.visible, c.hint, diagram, f"{number}.{j}",
                                  critical=c.critical))
        return out
