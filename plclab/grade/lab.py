"""Labs: ``labs/<id>/lab.toml`` read, checked strictly, and found by id.

A lab folder holds ``lab.toml`` (the spec: plant, wiring, I/O table, scenarios, criteria),
``README.md`` (the task as a student reads it), ``starter.<ext>``, ``solution/`` and
``mistakes/``. See ``docs/labs.md`` for every key.

Every problem of a lab file is a :class:`~plclab.errors.PlcError` with a code PLC5001..PLC5011,
a message that names the key and says what to write, and the ``lab.toml:line:col`` where the key
is.

For example::

    lab = load_lab("tank-two-position")
    lab.title, [s.name for s in lab.scenarios]
"""

from __future__ import annotations

import hashlib
import importlib.util
import math
import os
import re
import tomllib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import Location, PlcError
from plclab.runtime.plc import MAX_CYCLE_NS, MIN_CYCLE_NS

from .criteria import CHECKS, Verdict, condition, condition_names, run_check, signals_of
from .errors import did_you_mean, grade_error

LANGUAGES = {"st": (".st",), "il": (".il",), "ld": (".ld",), "xml": (".xml",)}
"""Language keys of ``languages`` and their file extensions."""
SOURCE_EXTS = {ext: lang for lang, exts in LANGUAGES.items() for ext in exts}

TOP_KEYS = ("id", "title", "summary", "goals", "plant", "plant_params", "scan", "languages",
            "dialect",
            "time_limit", "memory_limit", "wiring", "io", "watch", "diagram", "scenario",
            "criterion", "mistake", "level", "chapters", "alarms", "recipes", "critical_cap",
            "hidden_scenarios_withheld", "performance_spec")
LEVELS = {1: "beginner", 2: "intermediate", 3: "advanced"}
"""``level`` of a lab (``plclab lab list`` orders by it; the course's path through the labs)."""
SCENARIO_KEYS = ("name", "description", "duration", "seed", "visible", "plant_params",
                 "action", "actions", "until", "watch", "recipe", "task_intervals")
CRITERION_KEYS = ("name", "scenario", "scenarios", "check", "python", "params", "points",
                  "message", "hint", "hint_fix", "signals", "window", "description", "requires",
                  "critical", "requirements")
MISTAKE_KEYS = ("file", "max_score", "violates", "description")
IO_KEYS = ("name", "address", "type", "unit", "description")
DIAGRAM_KEYS = ("signals", "window")

_SIZE_TYPES = {
    "X": ("BOOL",),
    "B": ("BYTE", "SINT", "USINT", "CHAR"),
    "W": ("WORD", "INT", "UINT"),
    "D": ("DWORD", "DINT", "UDINT", "REAL", "TIME"),
    "L": ("LWORD", "LINT", "ULINT", "LREAL", "LTIME"),
}
_ADDR = re.compile(r"^%([IQM])([XBWDL]?)(\d+)(?:\.(\d+))?$", re.IGNORECASE)
_ID = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")


def repo_labs_dir() -> Path:
    """The labs that come with plclab: the installed student copy (``plclab/courseware/labs``)
    or, in a source checkout, the repository's ``labs/`` folder."""
    from .courseware import courseware_root

    return courseware_root() / "labs"


# ---------------------------------------------------------------------------- locations


class _Locator:
    """``file:line:col`` of keys in a TOML text (best effort, for messages)."""

    def __init__(self, text: str, filename: str) -> None:
        self.lines = text.splitlines()
        self.file = filename
        self.headers: dict[str, list[int]] = {}
        for i, ln in enumerate(self.lines):
            m = re.match(r"\s*\[\[\s*([A-Za-z_.]+)\s*\]\]", ln)
            if m:
                self.headers.setdefault(m.group(1), []).append(i)

    def _block(self, section: str | None, index: int | None) -> tuple[int, int]:
        if section is None:
            starts = [i for i, ln in enumerate(self.lines) if re.match(r"\s*\[", ln)]
            return 0, starts[0] if starts else len(self.lines)
        hs = self.headers.get(section, [])
        if index is None or index >= len(hs):
            return -1, -1
        start = hs[index]
        end = len(self.lines)
        for j in range(start + 1, len(self.lines)):
            if re.match(r"\s*\[", self.lines[j]) and not self.lines[j].strip().startswith(
                    f"[[{section}."):
                end = j
                break
        return start, end

    def where(self, section: str | None = None, index: int | None = None,
              key: str | None = None) -> Location:
        a, b = self._block(section, index)
        if a < 0:
            if section is not None and key is None:
                return Location(self.file)
            a, b = 0, len(self.lines)
        if key is not None:
            pat = re.compile(rf"^\s*\"?{re.escape(key)}\"?\s*=")
            for j in range(a, b):
                m = pat.match(self.lines[j])
                if m:
                    col = len(self.lines[j]) - len(self.lines[j].lstrip()) + 1
                    return Location(self.file, j + 1, col)
            # a key of an inline table: diagram = { window = "20s" }
            inline = re.compile(rf"[{{,]\s*(\"?{re.escape(key)}\"?)\s*=")
            for j in range(a, b):
                m = inline.search(self.lines[j])
                if m:
                    return Location(self.file, j + 1, m.start(1) + 1)
        if section is not None:
            return Location(self.file, a + 1, 1)
        return Location(self.file)


# ---------------------------------------------------------------------------- the model


@dataclass
class IoRow:
    """One row of the I/O table: what a student wires to."""

    name: str
    address: str
    type: str
    unit: str = ""
    description: str = ""


@dataclass
class ScenarioSpec:
    """A scenario of the lab: initial state, actions, duration, seed, visibility."""

    name: str
    duration: float
    description: str = ""
    seed: int = 0
    visible: bool = True
    plant_params: dict[str, Any] = field(default_factory=dict)
    actions: list[dict[str, Any]] = field(default_factory=list)
    until: str | None = None
    watch: list[str] = field(default_factory=list)
    recipe: list[tuple[float, str]] = field(default_factory=list)  # (s, record): plclab.scada
    # the tasks configured at one interval run at another ({"10ms": "20ms"}): plclab.runtime.Plc
    task_intervals: dict[str, str] = field(default_factory=dict)

    def scenario(self, duration: float | None = None) -> Any:
        """The :class:`plclab.sim.Scenario` of this spec."""
        from plclab.sim import Scenario

        return Scenario(self.actions, duration=duration or self.duration, until=self.until,
                        description=self.description)


@dataclass
class CriterionSpec:
    """A criterion: a check (or a Python function) on the trace of some scenarios."""

    name: str
    check: str
    params: dict[str, Any]
    points: float = 1.0
    scenarios: list[str] = field(default_factory=list)
    message: str = ""
    hint: str = ""
    signals: list[str] = field(default_factory=list)
    window: float | None = None
    description: str = ""
    function: Callable[..., Any] | None = None
    python: str = ""
    requires: list[str] = field(default_factory=list)
    critical: bool = False  # safety or core function: failing it caps the lab (critical_cap)
    requirements: list[str] = field(default_factory=list)  # README requirement ids, "R1"
    hint_fix: str = ""  # tier 2 of the hint: the literal fix (lab check --hint 2 only)

    def evaluate(self, trace: Any) -> Verdict:
        """Run the check on a trace; a check that cannot run is a failed verdict."""
        try:
            if self.function is not None:
                return _as_verdict(self.function(trace, **self.params), self.python)
            return run_check(self.check, trace, self.params)
        except PlcError as e:
            return Verdict(False, f"this criterion could not be evaluated: {e.message}")
        except Exception as e:  # noqa: BLE001 - a lab's own check must not stop grading
            return Verdict(False, f"this criterion could not be evaluated ({type(e).__name__}: "
                           f"{e}); tell your instructor (PLC5010)")

    def summary(self) -> str:
        """The check and its parameters in one line: ``max_switchings: signal = PUMP, max = 8``."""
        name = self.python if self.function is not None else self.check
        ps = ", ".join(f"{k} = {_fmt_param(v)}" for k, v in self.params.items() if v is not None)
        return f"{name}: {ps}" if ps else name

    def relevant_signals(self) -> list[str]:
        """Signals for the timing diagram of a failure."""
        out = list(self.signals)
        for s in signals_of(self.check, self.params):
            if s not in out:
                out.append(s)
        return out


def _fmt_param(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_fmt_param(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{" + ", ".join(f"{k} = {_fmt_param(x)}" for k, x in v.items()) + "}"
    return str(v)


def _cell(text: str) -> str:
    """Text for one cell of a Markdown table."""
    return " ".join(text.split()).replace("|", "\\|")


def _as_verdict(res: Any, where: str) -> Verdict:
    if isinstance(res, Verdict):
        return res
    if isinstance(res, bool):
        return Verdict(res, "passed" if res else "failed")
    if isinstance(res, tuple) and 1 <= len(res) <= 4 and isinstance(res[0], bool):
        passed = res[0]
        msg = str(res[1]) if len(res) > 1 else ("passed" if passed else "failed")
        t = None if len(res) < 3 or res[2] is None else float(res[2])
        sig = list(res[3]) if len(res) > 3 else []
        return Verdict(passed, msg, t, sig)
    raise grade_error("PLC5010", f"python check {where} returned {res!r}; return a Verdict, a "
                      "bool or (passed, message[, t_fail[, signals]])")


@dataclass
class MistakeSpec:
    """A typical wrong program kept in ``mistakes/`` and the score it may earn at most.

    ``violates`` names the criteria it breaks: a criterion name (every scenario that checks
    it) or one test, ``"scenario: criterion"``. The lab's tests hold it to at most
    ``max_score`` and to at most half the points of the tests it violates.
    """

    file: str
    max_score: float
    violates: list[str] = field(default_factory=list)
    description: str = ""


@dataclass
class Lab:
    """A lab read from ``lab.toml`` (see :func:`load_lab`)."""

    id: str
    path: Path
    title: str
    plant: str
    io: list[IoRow]
    scenarios: list[ScenarioSpec]
    criteria: list[CriterionSpec]
    wiring: Any
    wiring_source: str = ""
    summary: str = ""
    goals: list[str] = field(default_factory=list)
    plant_params: dict[str, Any] = field(default_factory=dict)
    scan: str = "10ms"
    languages: list[str] = field(default_factory=lambda: list(LANGUAGES))
    time_limit: float = 30.0
    memory_limit_mb: int = 1536
    watch: list[str] = field(default_factory=list)
    diagram_signals: list[str] = field(default_factory=list)
    diagram_window: float = 20.0
    hash: str = ""
    mistakes: list[MistakeSpec] = field(default_factory=list)
    dialect: str | None = None  # of submissions without a {dialect} pragma (ADR 0017)
    student_watch: list[str] = field(default_factory=list)  # lab check --watch: also drawn
    level: int = 0  # 1 beginner .. 3 advanced; 0 = not given
    chapters: list[int] = field(default_factory=list)  # course chapters that teach it
    alarms: dict[str, Any] | None = None  # the lab's alarm configuration (plclab.scada)
    recipes: dict[str, Any] | None = None  # the lab's recipe and its records (plclab.scada)
    critical_cap: float = 0.5  # a failed critical criterion caps the score at this share
    performance_spec: bool = False  # criteria state a control performance spec (ADR 0049)
    withheld: int | None = None  # the student copy shipped with plclab: hidden scenarios it
    # lacks (``hidden_scenarios_withheld`` in its lab.toml); None: the instructor's lab

    @property
    def student_copy(self) -> bool:
        """The copy shipped to students (pip install): no hidden scenarios, solutions or
        mistakes in it (ADR 0040)."""
        return self.withheld is not None

    # -- queries
    def scenario(self, name: str) -> ScenarioSpec:
        for s in self.scenarios:
            if s.name == name:
                return s
        raise grade_error("PLC5026", f"lab {self.id} has no scenario '{name}'."
                          f"{did_you_mean(name, [s.name for s in self.scenarios])} Scenarios: "
                          + ", ".join(s.name for s in self.scenarios))

    def criteria_for(self, scenario: str) -> list[CriterionSpec]:
        return [c for c in self.criteria if scenario in c.scenarios]

    @property
    def max_score(self) -> float:
        return float(sum(c.points * len(c.scenarios) for c in self.criteria))

    @property
    def visible_scenarios(self) -> list[ScenarioSpec]:
        return [s for s in self.scenarios if s.visible]

    def all_watch(self, scenario: ScenarioSpec | None = None) -> list[str]:
        """Variables recorded in every run: ``watch`` plus the %M addresses of the I/O table."""
        out = list(self.watch)
        for r in self.io:
            if r.address.upper().startswith("%M") and r.address not in out:
                out.append(r.address)
        if scenario is not None:
            out += [w for w in scenario.watch if w not in out]
        out += [w for w in self.student_watch if w not in out]
        return out

    def io_table_markdown(self) -> str:
        """The I/O table as Markdown (what ``plclab lab show`` prints and README.md holds)."""
        rows = ["| Name | Address | Type | Unit | Description |",
                "|---|---|---|---|---|"]
        for r in self.io:
            rows.append(f"| `{r.name}` | `{r.address}` | {r.type} | {r.unit} | "
                        f"{r.description} |")
        return "\n".join(rows)

    def criteria_table_markdown(self) -> str:
        """The criteria as a Markdown table (scenarios, points, the check with its parameters,
        what it means), for the README: generated from lab.toml so that the two cannot
        disagree."""
        hidden = {s.name for s in self.scenarios if not s.visible}
        rows = ["| Criterion | Scenarios | Points | Check | What it checks |",
                "|---|---|---|---|---|"]
        for c in self.criteria:
            scs = ", ".join(f"`{s}`" + (" (hidden)" if s in hidden else "") for s in c.scenarios)
            what = _cell(c.description or c.message)
            flags = " (critical)" if c.critical else ""
            rows.append(f"| {c.name}{flags} | {scs} | {c.points:g} each | {_cell(c.summary())} "
                        f"| {what} |")
        return "\n".join(rows)

    def violated_tests(self, mistake: MistakeSpec) -> list[str]:
        """The tests (``"scenario: criterion"``) a mistake's ``violates`` names."""
        out: list[str] = []
        for v in mistake.violates:
            tests = ([v] if ": " in v else
                     [f"{s}: {c.name}" for c in self.criteria if c.name == v for s in c.scenarios])
            out += [t for t in tests if t not in out]
        return out

    def files(self, sub: str) -> list[Path]:
        """Source files in a sub-folder (``solution``, ``mistakes``), sorted."""
        d = self.path / sub
        if not d.is_dir():
            return []
        return sorted(p for p in d.iterdir() if p.suffix.lower() in SOURCE_EXTS
                      and not p.name.startswith("."))

    @property
    def starter(self) -> list[Path]:
        return sorted(p for p in self.path.glob("starter.*") if p.suffix.lower() in SOURCE_EXTS)

    def __repr__(self) -> str:
        return (f"<Lab {self.id}: {len(self.scenarios)} scenarios, {len(self.criteria)} "
                f"criteria, {self.max_score:g} points>")


# ---------------------------------------------------------------------------- finding labs


def lab_dirs(extra: Iterable[str | os.PathLike] = ()) -> list[Path]:
    """Where labs are looked up: ``extra`` (``--labs``), ``PLCLAB_LABS``, plclab's own labs."""
    out = [Path(p) for p in extra if p]
    env = os.environ.get("PLCLAB_LABS", "")
    out += [Path(p) for p in env.split(os.pathsep) if p]
    out.append(repo_labs_dir())
    return out


def list_labs(extra: Iterable[str | os.PathLike] = ()) -> list[Path]:
    """Every lab folder (one holding a lab.toml) in the lookup path; first one of an id wins."""
    seen: dict[str, Path] = {}
    for d in lab_dirs(extra):
        if not d.is_dir():
            continue
        for sub in sorted(d.iterdir()):
            if (sub / "lab.toml").is_file() and sub.name not in seen:
                seen[sub.name] = sub
    return list(seen.values())


def find_lab(lab: str | os.PathLike, extra: Iterable[str | os.PathLike] = ()) -> Path:
    """The folder of a lab given by id or path (PLC5020 when there is none)."""
    p = Path(lab)
    if p.is_file() and p.name == "lab.toml":
        return p.parent
    if p.is_dir() and (p / "lab.toml").is_file():
        return p
    for d in lab_dirs(extra):  # an id first: `plclab lab get` made a folder of that name
        cand = d / str(lab)
        if p.name == str(lab) and (cand / "lab.toml").is_file():
            return cand
    if p.is_dir():
        raise grade_error("PLC5001", f"{p} has no lab.toml; a lab folder holds lab.toml, "
                          "README.md, a starter, solution/ and mistakes/")
    known = [x.name for x in list_labs(extra)]
    raise grade_error("PLC5020", f"no lab '{lab}'.{did_you_mean(str(lab), known)} Labs: "
                      f"{', '.join(known) or '(none)'}; give a lab id, a lab folder, or "
                      "--labs DIR")


def get_lab_files(lab: str | os.PathLike, dest: Path, extra: Iterable[str | os.PathLike] = (),
                  force: bool = False) -> list[Path]:
    """Copy a lab's student files (``README.md``, ``starter.*``, its notebook) into *dest*;
    never a solution, a mistake or a hidden scenario. PLC5050 when a file is there already
    (unless *force*)."""
    import shutil

    from .courseware import courseware_root

    folder = find_lab(lab, extra)
    files = [folder / "README.md"] if (folder / "README.md").is_file() else []
    files += sorted(p for p in folder.glob("starter.*") if p.suffix.lower() in SOURCE_EXTS)
    for nb in (folder.parent.parent / "notebooks", courseware_root() / "notebooks"):
        if (nb / f"{folder.name}.ipynb").is_file():
            files.append(nb / f"{folder.name}.ipynb")
            break
    there = [dest / f.name for f in files if (dest / f.name).exists()]
    if there and not force:
        raise grade_error("PLC5050", f"{there[0]} exists already: give another folder "
                          "(plclab lab get LAB DIR) or --force to overwrite it")
    try:
        dest.mkdir(parents=True, exist_ok=True)
        return [Path(shutil.copyfile(f, dest / f.name)) for f in files]
    except OSError as e:
        raise grade_error("PLC5050", f"cannot write into {dest}: {e.strerror or e}") from None


def require_hidden(lab: Lab, visible_only: bool = False, use: str = "grade") -> None:
    """PLC5072 when ``lab`` is the student copy shipped with plclab (no hidden scenarios) and
    ``use`` needs them: ``grade`` and the worker (unless ``visible_only``), ``grade-bundle``
    and ``lab audit`` (always). The one place this check and its message live (ADR 0040)."""
    if not lab.student_copy or visible_only:
        return
    how = {"grade": f"plclab grade path/to/labs/{lab.id} SUBMISSIONS (or --labs DIR), or pass "
                    "--visible-only to grade on the visible scenarios alone",
           "grade-bundle": f"plclab grade-bundle path/to/labs/{lab.id}",
           "lab audit": f"plclab lab audit path/to/labs/{lab.id}"}[use]
    raise grade_error("PLC5072", f"{lab.path} is the student copy of {lab.id} that ships with "
                      f"plclab: {lacks(lab)}. Use the instructor's lab folder (labs/{lab.id} of "
                      f"the plclab repository, or your own): {how}")


def lacks(lab: Lab) -> str:
    """What the student copy of a lab lacks, counted: "its 2 hidden scenarios, solutions and
    mistakes are not in it" ("" for an instructor's lab)."""
    if lab.withheld is None:
        return ""
    n = lab.withheld
    what = (f"its {n} hidden scenario{'s' if n != 1 else ''}, solutions and mistakes are"
            if n else "it has no hidden scenario, but its solutions and mistakes are")
    return f"{what} not in it"


def hidden_note(lab: Lab) -> str | None:
    """``lab check --hidden`` with the student copy of a lab: the line saying that it runs
    without the hidden scenarios this copy lacks (None when nothing is missing)."""
    if not lab.withheld:
        return None
    n = lab.withheld
    return (f"note: {lab.path} is the student copy of {lab.id} that ships with plclab: its "
            f"{n} hidden scenario{'s are' if n != 1 else ' is'} not in it, so --hidden runs "
            "the visible ones only. For every scenario use the instructor's lab folder "
            f"(labs/{lab.id} of the plclab repository, or your own; --labs DIR)")


# ---------------------------------------------------------------------------- loading


def load_lab(lab: str | os.PathLike, extra: Iterable[str | os.PathLike] = (),
             deep: bool = False) -> Lab:
    """Read and check a lab (by id or path). ``deep=True`` also binds every scenario to a
    simulation (wiring against the plant, actions and faults), which costs a compile."""
    folder = find_lab(lab, extra)
    path = folder / "lab.toml"
    try:
        raw = path.read_bytes()
        text = raw.decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as e:
        raise grade_error("PLC5001", f"{path}: cannot be read ({e}); save it as UTF-8") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        m = re.search(r"line (\d+), column (\d+)", str(e))
        loc = Location(str(path), int(m.group(1)), int(m.group(2))) if m else Location(str(path))
        raise grade_error("PLC5001", f"not valid TOML: {e}", loc) from None
    lab_obj = _Builder(folder, path, text, data).build()
    h = hashlib.sha256(raw)
    for extra_file in sorted(folder.glob("*.py")):
        h.update(extra_file.read_bytes())
    if lab_obj.wiring_source and Path(lab_obj.wiring_source).is_file():
        h.update(Path(lab_obj.wiring_source).read_bytes())
    lab_obj.hash = h.hexdigest()[:16]
    if deep:
        validate_deep(lab_obj)
    return lab_obj


class _Builder:
    """Turns the parsed TOML into a :class:`Lab`, checking every key."""

    def __init__(self, folder: Path, path: Path, text: str, data: dict[str, Any]) -> None:
        self.folder = folder
        self.path = path
        self.data = data
        self.loc = _Locator(text, str(path))

    # -- error helpers
    def err(self, code: str, msg: str, section: str | None = None, index: int | None = None,
            key: str | None = None) -> PlcError:
        return grade_error(code, msg, self.loc.where(section, index, key))

    def unknown(self, table: Mapping[str, Any], allowed: Iterable[str], what: str,
                section: str | None = None, index: int | None = None,
                extra: Iterable[str] = ()) -> None:
        allowed = list(allowed) + list(extra)
        for k in table:
            if k not in allowed:
                raise self.err("PLC5002", f"unknown key '{k}' in {what}.{did_you_mean(k, allowed)}"
                               f" Keys: {', '.join(allowed)}", section, index, k)

    def string(self, table: Mapping[str, Any], key: str, what: str, section: str | None = None,
               index: int | None = None, required: bool = False, default: str = "") -> str:
        if key not in table:
            if required:
                raise self.err("PLC5003", f"{what} needs '{key}' (a string), e.g. {key} = "
                               f"\"...\"", section, index)
            return default
        v = table[key]
        if not isinstance(v, str):
            raise self.err("PLC5004", f"'{key}' in {what} must be a string in quotes, not "
                           f"{v!r}", section, index, key)
        return v

    def strings(self, table: Mapping[str, Any], key: str, what: str, section: str | None = None,
                index: int | None = None) -> list[str]:
        v = table.get(key, [])
        if isinstance(v, str):
            v = [v]
        if not isinstance(v, list) or not all(isinstance(x, str) for x in v):
            raise self.err("PLC5004", f"'{key}' in {what} must be a list of strings, e.g. "
                           f"{key} = [\"a\", \"b\"]", section, index, key)
        return list(v)

    def seconds(self, v: Any, key: str, what: str, section: str | None = None,
                index: int | None = None, allow_zero: bool = True) -> float:
        from plclab.sim import parse_seconds

        if isinstance(v, bool) or not isinstance(v, int | float | str):
            raise self.err("PLC5004", f"'{key}' in {what} must be a time: seconds (30) or a "
                           f"duration string (\"30s\", \"5min\", \"T#2s\"), not {v!r}",
                           section, index, key)
        try:
            return parse_seconds(v, key, allow_zero=allow_zero)
        except PlcError as e:
            raise self.err("PLC5004", f"'{key}' in {what}: {e.message}", section, index,
                           key) from None

    # -- the whole file
    def build(self) -> Lab:
        d = self.data
        self.unknown(d, TOP_KEYS, "lab.toml (top level)")
        folder_id = self.folder.name
        lab_id = self.string(d, "id", "lab.toml", default=folder_id)
        if lab_id != folder_id:
            raise self.err("PLC5004", f"id = \"{lab_id}\" but the folder is '{folder_id}'; "
                           "they must agree (or leave id out)", key="id")
        title = self.string(d, "title", "lab.toml", required=True)
        summary = self.string(d, "summary", "lab.toml")
        goals = self.strings(d, "goals", "lab.toml")
        plant, params, plant_obj = self.plant(d)
        scan = d.get("scan", "10ms")
        scan_s = self.seconds(scan, "scan", "lab.toml", allow_zero=False)
        if not MIN_CYCLE_NS <= round(scan_s * 1e9) <= MAX_CYCLE_NS:
            raise self.err("PLC5004", f"scan = {scan!r}: a PLC cycle lies between 0.1 ms and "
                           "1 day (e.g. \"10ms\")", key="scan")
        langs = self.strings(d, "languages", "lab.toml") or list(LANGUAGES)
        for lg in langs:
            if lg not in LANGUAGES:
                raise self.err("PLC5004", f"languages: unknown language '{lg}'."
                               f"{did_you_mean(lg, LANGUAGES)} Use st, il, ld, xml",
                               key="languages")
        tl = self.seconds(d.get("time_limit", 30), "time_limit", "lab.toml", allow_zero=False)
        mem = self.memory(d.get("memory_limit", 1536))
        wiring, wsrc = self.wiring(d, plant, plant_obj)
        io = self.io(d, wiring)
        watch = self.strings(d, "watch", "lab.toml")
        diagram = d.get("diagram", {})
        if not isinstance(diagram, Mapping):
            raise self.err("PLC5004", "diagram must be a table: diagram = { signals = [...], "
                           "window = \"20s\" }", key="diagram")
        self.unknown(diagram, DIAGRAM_KEYS, "diagram")
        dsig = self.strings(diagram, "signals", "diagram")
        dwin = self.seconds(diagram.get("window", 20), "window", "diagram", allow_zero=False)
        scenarios = self.scenarios(d, plant_obj, params)
        names = self.names(plant_obj, wiring, io, watch)
        for s in dsig:
            if s not in names:
                raise self.err("PLC5004", f"diagram signal '{s}' is neither a signal of "
                               f"'{plant}' nor a wired or watched address."
                               f"{did_you_mean(s, names)}", key="diagram")
        criteria = self.criteria(d, scenarios, names)
        lab = Lab(lab_id, self.folder, title, plant, io, scenarios, criteria, wiring, wsrc,
                  summary, goals, params, str(scan) if isinstance(scan, str) else f"{scan_s}s",
                  langs, tl, mem, watch, dsig, dwin)
        lab.mistakes = self.mistakes(d, criteria)
        lab.dialect = self.dialect(d)
        lab.level, lab.chapters = self.course_place(d)
        lab.alarms = self.alarms(d)
        lab.recipes = self.recipes(d, scenarios)
        lab.critical_cap = self.critical_cap(d)
        lab.performance_spec = self.performance_spec(d)
        lab.withheld = self.withheld(d)
        return lab

    def withheld(self, d: Mapping[str, Any]) -> int | None:
        """``hidden_scenarios_withheld = N``: written by the build into the student copy of a
        lab (:func:`plclab.grade.courseware.student_lab_data`), the number of hidden scenarios
        it lacks; absent from an instructor's lab."""
        if "hidden_scenarios_withheld" not in d:
            return None
        n = d["hidden_scenarios_withheld"]
        if isinstance(n, bool) or not isinstance(n, int) or n < 0:
            raise self.err("PLC5004", f"hidden_scenarios_withheld = {n!r}: the number of "
                           "hidden scenarios the student copy of a lab lacks (0 or more), "
                           "written when plclab is built; an instructor's lab leaves it out",
                           key="hidden_scenarios_withheld")
        return n

    def performance_spec(self, d: Mapping[str, Any]) -> bool:
        """``performance_spec = true``: the criteria state the requirement as a control
        engineer's performance specification (settling time, overshoot, steady-state error,
        disturbance recovery), so any tuning inside it is right; ``plclab lab audit`` then
        counts a changed tuning constant that meets every criterion as another valid tuning,
        not as a survivor (ADR 0049)."""
        v = d.get("performance_spec", False)
        if not isinstance(v, bool):
            raise self.err("PLC5004", f"performance_spec = {v!r}: true when the criteria state "
                           "a performance specification that every right tuning meets (settling "
                           "time, overshoot, steady-state error), else leave it out",
                           key="performance_spec")
        return v

    def critical_cap(self, d: Mapping[str, Any]) -> float:
        """``critical_cap = 0.5``: the most a submission earns, as a share of the lab's points,
        when a critical criterion fails (at most half; a lab may set it lower)."""
        cap = d.get("critical_cap", 0.5)
        if isinstance(cap, bool) or not isinstance(cap, int | float) or not 0 <= cap <= 0.5:
            raise self.err("PLC5004", f"critical_cap = {cap!r}: the share of the points a "
                           "submission keeps at most when a critical criterion fails, between 0 "
                           "and 0.5 (e.g. critical_cap = 0.4)", key="critical_cap")
        return float(cap)

    def course_place(self, d: Mapping[str, Any]) -> tuple[int, list[int]]:
        """``level = 1..3`` and ``chapters = [N, ...]``: where the lab sits in the course."""
        level = d.get("level", 0)
        if "level" in d and (isinstance(level, bool) or level not in LEVELS):
            raise self.err("PLC5004", "level must be 1 (beginner), 2 (intermediate) or 3 "
                           f"(advanced), not {level!r}", key="level")
        chapters = d.get("chapters", [])
        if not isinstance(chapters, list) or not all(
                isinstance(c, int) and not isinstance(c, bool) and 1 <= c <= 99
                for c in chapters):
            raise self.err("PLC5004", "chapters must be a list of course chapter numbers, e.g. "
                           "chapters = [1, 6]", key="chapters")
        return int(level), sorted(set(chapters))

    def recipes(self, d: Mapping[str, Any], scenarios: list[ScenarioSpec]
                ) -> dict[str, Any] | None:
        """``recipes = "recipes.toml"``: the recipe the scenarios load (``recipe = "juice"``
        or ``recipe = [{ at = "30s", record = "nectar" }, ...]``), checked and kept as data."""
        name = self.string(d, "recipes", "lab.toml")
        raw = {i: s.get("recipe") for i, s in enumerate(d.get("scenario", []))
               if isinstance(s, Mapping) and s.get("recipe") is not None}
        if not name:
            if raw:
                raise self.err("PLC5004", "a scenario loads a recipe, but the lab names no "
                               "recipes file: recipes = \"recipes.toml\"", key="recipes")
            return None
        path = self.folder / name
        if Path(name).name != name or not path.is_file():
            raise self.err("PLC5001", f"recipes = \"{name}\": no such file in the lab folder",
                           key="recipes")
        from plclab.process.recipes import Recipe

        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
            recipe = Recipe.from_dict(data, name)
        except tomllib.TOMLDecodeError as e:
            raise self.err("PLC5004", f"recipes = \"{name}\": not valid TOML ({e})",
                           key="recipes") from None
        except PlcError as e:
            raise self.err("PLC5004", f"recipes = \"{name}\": {e.message}",
                           key="recipes") from None
        by_name = {s.name: s for s in scenarios}
        for i, r in raw.items():
            what = f"[[scenario]] #{i + 1}"
            items = [{"at": 0, "record": r}] if isinstance(r, str) else r
            if not isinstance(items, list) or not all(isinstance(x, Mapping) for x in items):
                raise self.err("PLC5004", f"{what}: recipe is a record name (\"juice\") or a "
                               "list of { at = \"30s\", record = \"nectar\" }", "scenario", i,
                               "recipe")
            loads = []
            for x in items:
                rec = x.get("record")
                if rec not in recipe.records:
                    raise self.err("PLC5004", f"{what}: recipe record {rec!r} is not in {name} "
                                   f"({', '.join(recipe.records)})", "scenario", i, "recipe")
                loads.append((self.seconds(x.get("at", 0), "at", what, "scenario", i), rec))
            spec = by_name.get(str(d["scenario"][i].get("name")))
            if spec is not None:
                spec.recipe = sorted(loads)
        return data

    def alarms(self, d: Mapping[str, Any]) -> dict[str, Any] | None:
        """``alarms = "alarms.toml"``: the lab's alarm configuration, read and checked here and
        kept as data (the grader's worker may not see the lab folder)."""
        name = self.string(d, "alarms", "lab.toml")
        if not name:
            return None
        path = self.folder / name
        if Path(name).name != name or not path.is_file():
            raise self.err("PLC5001", f"alarms = \"{name}\": no such file in the lab folder",
                           key="alarms")
        from plclab.process.alarms import AlarmServer

        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
            AlarmServer.from_dict(data, name)
        except tomllib.TOMLDecodeError as e:
            raise self.err("PLC5004", f"alarms = \"{name}\": not valid TOML ({e})",
                           key="alarms") from None
        except PlcError as e:
            raise self.err("PLC5004", f"alarms = \"{name}\": {e.message}", key="alarms") from None
        return data

    def mistakes(self, d: Mapping[str, Any], criteria: list[CriterionSpec]
                 ) -> list[MistakeSpec]:
        raw = d.get("mistake", [])
        if not isinstance(raw, list) or not all(isinstance(r, Mapping) for r in raw):
            raise self.err("PLC5004", "mistake must be [[mistake]] tables", key="mistake")
        tests = {f"{s}: {c.name}" for c in criteria for s in c.scenarios}
        crits = [c.name for c in criteria]
        out: list[MistakeSpec] = []
        for i, m in enumerate(raw):
            what = f"[[mistake]] #{i + 1}"
            self.unknown(m, MISTAKE_KEYS, what, "mistake", i)
            file = self.string(m, "file", what, "mistake", i, required=True)
            if Path(file).name != file or not (self.folder / "mistakes" / file).is_file():
                raise self.err("PLC5001", f"{what}: no file mistakes/{file} in the lab folder",
                               "mistake", i, "file")
            top = m.get("max_score")
            if isinstance(top, bool) or not isinstance(top, int | float) or top < 0:
                raise self.err("PLC5004", f"{what}: max_score must be a number >= 0, e.g. "
                               "max_score = 12", "mistake", i, "max_score")
            viol = self.strings(m, "violates", what, "mistake", i)
            for v in viol:
                if v not in tests and v not in crits:
                    raise self.err("PLC5009", f"{what}: violates '{v}', which is neither a "
                                   "criterion nor a test 'scenario: criterion'."
                                   f"{did_you_mean(v, crits)}", "mistake", i, "violates")
            out.append(MistakeSpec(file, float(top), viol,
                                   self.string(m, "description", what, "mistake", i)))
        return out

    def dialect(self, d: Mapping[str, Any]) -> str | None:
        """``dialect = "codesys"`` (iec, codesys, s7, matiec): how submissions are read."""
        from plclab.lang.dialect import PROFILES

        v = d.get("dialect")
        if v is None:
            return None
        if not isinstance(v, str) or v.lower() not in PROFILES:
            raise self.err("PLC5004", f"dialect = {v!r}: choose one of "
                           f"{', '.join(PROFILES)}", key="dialect")
        return v.lower()

    def memory(self, v: Any) -> int:
        if isinstance(v, bool) or not isinstance(v, int | float | str):
            raise self.err("PLC5004", "memory_limit is megabytes (1536) or a string such as "
                           "\"1.5GB\"", key="memory_limit")
        try:
            mb = parse_memory(v)
        except ValueError as e:
            raise self.err("PLC5004", f"memory_limit: {e}", key="memory_limit") from None
        return mb

    def plant(self, d: Mapping[str, Any]) -> tuple[str, dict[str, Any], Any]:
        from plants import PLANTS, PlantError, get_plant

        plant = self.string(d, "plant", "lab.toml", required=True)
        if plant not in PLANTS:
            raise self.err("PLC5005", f"unknown plant '{plant}'.{did_you_mean(plant, PLANTS)} "
                           f"Plants: {', '.join(PLANTS)}", key="plant")
        params = d.get("plant_params", {})
        if not isinstance(params, Mapping):
            raise self.err("PLC5004", "plant_params must be a table, e.g. plant_params = "
                           "{ area = 0.2 }", key="plant_params")
        try:
            obj = get_plant(plant, **params)
        except (PlantError, TypeError, ValueError) as e:
            raise self.err("PLC5005", f"plant_params: {e}", key="plant_params") from None
        bad = _bad_plant_param(plant, params)
        if bad:
            raise self.err("PLC5004", f"plant_params: {bad}", key="plant_params")
        return plant, dict(params), obj

    def wiring(self, d: Mapping[str, Any], plant: str, plant_obj: Any) -> tuple[Any, str]:
        from plclab.sim import Wiring, default_wiring, load_wiring

        w = d.get("wiring")
        src = ""
        try:
            if w is None:
                wiring = default_wiring(plant)
                src = f"default wiring of {plant}"
            elif isinstance(w, str):
                p = (self.folder / w).resolve()
                if not p.is_file():
                    raise self.err("PLC5001", f"wiring = \"{w}\": no such file ({p}); give a "
                                   "path relative to the lab folder, e.g. "
                                   "\"../wiring/tank.toml\", or inline rows", key="wiring")
                wiring = load_wiring(p)
                src = str(p)
            elif isinstance(w, list):
                wiring = Wiring.from_rows(w, plant, source=str(self.path))
                src = "inline"
            else:
                raise self.err("PLC5004", "wiring is a file (wiring = \"../wiring/tank.toml\") "
                               "or a list of rows (wiring = [ { plc = \"%IX0.0\", signal = "
                               "\"LS1\", module = \"di\" }, ... ])", key="wiring")
        except PlcError as e:
            if e.code.startswith("PLC50"):
                raise
            raise self.err("PLC5006", f"wiring: {e}", key="wiring") from None
        if wiring.plant and wiring.plant != plant:
            raise self.err("PLC5006", f"the wiring is for the plant '{wiring.plant}', the lab "
                           f"runs '{plant}'", key="wiring")
        sigs = plant_obj.signals
        for r in wiring:
            if r.signal not in sigs:
                raise self.err("PLC5006", f"wiring row {r.plc}: '{plant}' has no signal "
                               f"'{r.signal}'.{did_you_mean(r.signal, sigs)}", key="wiring")
        return wiring, src

    def io(self, d: Mapping[str, Any], wiring: Any) -> list[IoRow]:
        rows = d.get("io")
        if rows is None:
            raise self.err("PLC5003", "the lab needs an I/O table: [[io]] tables with name, "
                           "address, type, unit, description (one per wiring row)")
        if not isinstance(rows, list) or not all(isinstance(r, Mapping) for r in rows):
            raise self.err("PLC5004", "io must be [[io]] tables", key="io")
        out: list[IoRow] = []
        seen_addr: dict[str, int] = {}
        seen_name: dict[str, int] = {}
        for i, r in enumerate(rows):
            what = f"[[io]] #{i + 1}"
            self.unknown(r, IO_KEYS, what, "io", i)
            name = self.string(r, "name", what, "io", i, required=True)
            addr = self.string(r, "address", what, "io", i, required=True).strip()
            ty = self.string(r, "type", what, "io", i, required=True).strip().upper()
            m = _ADDR.match(addr)
            if not m:
                raise self.err("PLC5004", f"{what} ({name}): address '{addr}' is not a PLC "
                               "address such as %IX0.0, %QX0.1, %IW64, %MW0", "io", i, "address")
            size = (m.group(2) or "X").upper()
            if size == "X" and m.group(4) is None:
                raise self.err("PLC5004", f"{what} ({name}): a bit address needs the bit: "
                               f"{addr}.0", "io", i, "address")
            if ty not in _SIZE_TYPES[size]:
                raise self.err("PLC5004", f"{what} ({name}): type {ty} does not fit {addr}; a "
                               f"{size}-address holds {' / '.join(_SIZE_TYPES[size])}",
                               "io", i, "type")
            key = addr.upper()
            if key in seen_addr:
                raise self.err("PLC5011", f"{what}: address {addr} is already row "
                               f"#{seen_addr[key] + 1}", "io", i, "address")
            if name.upper() in seen_name:
                raise self.err("PLC5011", f"{what}: name {name} is already row "
                               f"#{seen_name[name.upper()] + 1}", "io", i, "name")
            seen_addr[key] = i
            seen_name[name.upper()] = i
            out.append(IoRow(name, addr, ty, self.string(r, "unit", what, "io", i),
                             self.string(r, "description", what, "io", i)))
        wired = {}
        for r in wiring:
            if not r.is_address:
                continue
            wired[r.plc.upper()] = r
            if r.plc.upper() not in seen_addr:
                raise self.err("PLC5007", f"wiring row {r.plc} ({r.signal}) is not in the I/O "
                               f"table; add [[io]] name = \"{r.signal}\", address = \"{r.plc}\", "
                               "type, unit, description", "io", 0)
        for i, r in enumerate(out):
            if r.address.upper()[1] in "IQ" and r.address.upper() not in wired:
                raise self.err("PLC5007", f"[[io]] {r.name} ({r.address}) is not wired; add a "
                               "wiring row for it or remove it from the table", "io", i,
                               "address")
        return out

    def names(self, plant_obj: Any, wiring: Any, io: list[IoRow], watch: list[str]
              ) -> list[str]:
        """Names a criterion may use: plant signals, wired PLC addresses, watched ones."""
        out = list(plant_obj.signals)
        out += [r.plc for r in wiring]
        out += [r.address for r in io if r.address.upper().startswith("%M")]
        out += watch
        return out

    def scenarios(self, d: Mapping[str, Any], plant_obj: Any, params: dict[str, Any]
                  ) -> list[ScenarioSpec]:
        from plants import PlantError, get_plant

        raw = d.get("scenario")
        if raw is None:
            raise self.err("PLC5003", "the lab needs at least one [[scenario]] with name and "
                           "duration")
        if not isinstance(raw, list) or not all(isinstance(r, Mapping) for r in raw):
            raise self.err("PLC5004", "scenario must be [[scenario]] tables", key="scenario")
        out: list[ScenarioSpec] = []
        for i, s in enumerate(raw):
            what = f"[[scenario]] #{i + 1}"
            self.unknown(s, SCENARIO_KEYS, what, "scenario", i)
            name = self.string(s, "name", what, "scenario", i, required=True)
            what = f"scenario '{name}'"
            if any(o.name == name for o in out):
                raise self.err("PLC5011", f"two scenarios are called '{name}'", "scenario", i,
                               "name")
            if "duration" not in s:
                raise self.err("PLC5003", f"{what} needs a duration, e.g. duration = \"5min\"",
                               "scenario", i)
            dur = self.seconds(s["duration"], "duration", what, "scenario", i, allow_zero=False)
            seed = s.get("seed", 0)
            if isinstance(seed, bool) or not isinstance(seed, int):
                raise self.err("PLC5004", f"{what}: seed must be a whole number", "scenario", i,
                               "seed")
            vis = s.get("visible", True)
            if not isinstance(vis, bool):
                raise self.err("PLC5004", f"{what}: visible is true or false", "scenario", i,
                               "visible")
            pp = s.get("plant_params", {})
            if not isinstance(pp, Mapping):
                raise self.err("PLC5004", f"{what}: plant_params must be a table", "scenario", i,
                               "plant_params")
            merged = {**params, **pp}
            try:
                get_plant(plant_obj.name, **merged)
            except (PlantError, TypeError, ValueError) as e:
                raise self.err("PLC5005", f"{what}: plant_params: {e}", "scenario", i,
                               "plant_params") from None
            bad = _bad_plant_param(plant_obj.name, pp)
            if bad:
                raise self.err("PLC5004", f"{what}: plant_params: {bad}", "scenario", i,
                               "plant_params")
            acts = s.get("action", s.get("actions", []))
            if not isinstance(acts, list) or not all(isinstance(a, Mapping) for a in acts):
                raise self.err("PLC5008", f"{what}: actions are [[scenario.action]] tables or "
                               "actions = [ { at = \"1s\", press = \"START\" }, ... ]",
                               "scenario", i, "actions")
            until = s.get("until")
            if until is not None and not isinstance(until, str):
                raise self.err("PLC5004", f"{what}: until is a condition string", "scenario", i,
                               "until")
            spec = ScenarioSpec(name, dur, self.string(s, "description", what, "scenario", i),
                                seed, vis, dict(pp), [dict(a) for a in acts], until,
                                self.strings(s, "watch", what, "scenario", i),
                                task_intervals=self.task_intervals(s, what, i))
            try:
                sc = spec.scenario()
            except PlcError as e:
                raise self.err("PLC5008", f"{what}: {e.message}", "scenario", i) from None
            self.check_actions(sc, plant_obj, what, i)
            out.append(spec)
        return out

    def task_intervals(self, s: Mapping[str, Any], what: str, i: int) -> dict[str, str]:
        """``task_intervals = { "10ms" = "20ms" }``: durations on both sides (PLC5004)."""
        from plclab.runtime.plc import parse_task_intervals

        raw = s.get("task_intervals", {})
        if not isinstance(raw, Mapping) or not all(isinstance(v, str) for v in raw.values()):
            raise self.err("PLC5004", f"{what}: task_intervals is a table from the configured "
                           "interval to the one the scenario runs, e.g. task_intervals = "
                           "{ \"10ms\" = \"20ms\" }", "scenario", i, "task_intervals")
        try:
            parse_task_intervals(raw)
        except PlcError as e:
            raise self.err("PLC5004", f"{what}: task_intervals: {e.message}", "scenario", i,
                           "task_intervals") from None
        return dict(raw)

    def check_actions(self, sc: Any, plant_obj: Any, what: str, i: int) -> None:
        from plclab.sim.simulation import Simulation

        sigs = plant_obj.signals
        for a in sc.actions:
            if a.verb in ("set", "ramp") and a.target in sigs and a.value is not None:
                try:
                    Simulation._plant_value(sigs[a.target], a.value)
                except PlcError as e:
                    raise self.err("PLC5008", f"{what}, action {a.index + 1}: {e.message}",
                                   "scenario", i, "actions") from None
            if a.verb in ("press", "set", "ramp") and a.target not in sigs:
                raise self.err("PLC5008", f"{what}, action {a.index + 1}: '{plant_obj.name}' has "
                               f"no signal '{a.target}'.{did_you_mean(a.target, sigs)}",
                               "scenario", i)
            if a.verb in ("fault", "clear") and a.target not in plant_obj.faults:
                raise self.err("PLC5008", f"{what}, action {a.index + 1}: unknown fault "
                               f"'{a.target}'.{did_you_mean(a.target, plant_obj.faults)} Faults"
                               f" of {plant_obj.name}: {', '.join(plant_obj.faults)}",
                               "scenario", i)

    def criteria(self, d: Mapping[str, Any], scenarios: list[ScenarioSpec], names: list[str]
                 ) -> list[CriterionSpec]:
        raw = d.get("criterion")
        if raw is None:
            raise self.err("PLC5003", "the lab needs at least one [[criterion]] with name, "
                           "check and points")
        if not isinstance(raw, list) or not all(isinstance(r, Mapping) for r in raw):
            raise self.err("PLC5004", "criterion must be [[criterion]] tables", key="criterion")
        sc_names = [s.name for s in scenarios]
        out: list[CriterionSpec] = []
        for i, c in enumerate(raw):
            what = f"[[criterion]] #{i + 1}"
            name = self.string(c, "name", what, "criterion", i, required=True)
            what = f"criterion '{name}'"
            if any(o.name == name for o in out):
                raise self.err("PLC5011", f"two criteria are called '{name}'", "criterion", i,
                               "name")
            py = self.string(c, "python", what, "criterion", i)
            chk = self.string(c, "check", what, "criterion", i, default="python" if py else "")
            if not chk:
                raise self.err("PLC5003", f"{what} needs check = one of "
                               f"{', '.join(CHECKS)} (or python = \"module:function\")",
                               "criterion", i)
            if chk != "python" and chk not in CHECKS:
                raise self.err("PLC5009", f"{what}: unknown check '{chk}'."
                               f"{did_you_mean(chk, CHECKS)} Checks: {', '.join(CHECKS)}",
                               "criterion", i, "check")
            allowed = list(CRITERION_KEYS) + (list(CHECKS[chk].params) if chk in CHECKS else [])
            self.unknown(c, allowed, what, "criterion", i)
            if "scenario" in c and "scenarios" in c:
                raise self.err("PLC5004", f"{what}: give scenario or scenarios, not both",
                               "criterion", i, "scenarios")
            scs = self.strings(c, "scenarios" if "scenarios" in c else "scenario", what,
                               "criterion", i) or list(sc_names)
            for s in scs:
                if s not in sc_names:
                    raise self.err("PLC5009", f"{what}: no scenario '{s}'."
                                   f"{did_you_mean(s, sc_names)} Scenarios: "
                                   f"{', '.join(sc_names)}", "criterion", i, "scenario")
            pts = c.get("points", 1)
            if isinstance(pts, bool) or not isinstance(pts, int | float) or pts <= 0:
                raise self.err("PLC5004", f"{what}: points must be a number > 0, e.g. points = 2",
                               "criterion", i, "points")
            sigs = self.strings(c, "signals", what, "criterion", i)
            win = None
            if "window" in c:
                win = self.seconds(c["window"], "window", what, "criterion", i,
                                   allow_zero=False)
            spec = CriterionSpec(name, chk, {}, float(pts), scs,
                                 self.string(c, "message", what, "criterion", i),
                                 self.string(c, "hint", what, "criterion", i), sigs, win,
                                 self.string(c, "description", what, "criterion", i))
            spec.hint_fix = self.string(c, "hint_fix", what, "criterion", i)
            if spec.hint_fix and not spec.hint:
                raise self.err("PLC5055", f"{what}: hint_fix (the literal fix, tier 2) needs "
                               "hint (the concept, tier 1) too, e.g. hint = \"a start must "
                               "survive its release: keep the motor on with its own output\"",
                               "criterion", i, "hint_fix")
            if chk == "python":
                spec.python = py or ""
                if not py:
                    raise self.err("PLC5003", f"{what}: check = \"python\" needs python = "
                                   "\"module:function\"", "criterion", i)
                spec.function = self.python(py, what, i)
                prm = c.get("params", {})
                if not isinstance(prm, Mapping):
                    raise self.err("PLC5004", f"{what}: params is a table passed to the function",
                                   "criterion", i, "params")
                spec.params = dict(prm)
            else:
                if "params" in c:
                    raise self.err("PLC5002", f"{what}: params is only for python checks; write "
                                   f"the parameters of '{chk}' as keys of the criterion",
                                   "criterion", i, "params")
                spec.params = self.check_params(chk, c, what, i, names)
            spec.requires = self.strings(c, "requires", what, "criterion", i)
            crit = c.get("critical", False)
            if not isinstance(crit, bool):
                raise self.err("PLC5004", f"{what}: critical is true or false", "criterion", i,
                               "critical")
            spec.critical = crit
            spec.requirements = self.strings(c, "requirements", what, "criterion", i)
            for r in spec.requires:
                prev = next((o for o in out if o.name == r), None)
                if prev is None:
                    raise self.err("PLC5009", f"{what}: requires '{r}', which is not a criterion "
                                   "written before this one."
                                   f"{did_you_mean(r, [o.name for o in out])}", "criterion", i,
                                   "requires")
                if not any(s in prev.scenarios for s in scs):
                    raise self.err("PLC5009", f"{what}: requires '{r}', which is not checked in "
                                   "any of its scenarios", "criterion", i, "requires")
            for s in sigs:
                if s not in names:
                    raise self.err("PLC5009", f"{what}: signal '{s}' is neither a signal of the "
                                   f"plant nor a wired or watched address.{did_you_mean(s, names)}",
                                   "criterion", i, "signals")
            out.append(spec)
        return out

    def check_params(self, chk: str, c: Mapping[str, Any], what: str, i: int,
                     names: list[str]) -> dict[str, Any]:
        spec = CHECKS[chk]
        out: dict[str, Any] = {}
        for key, prm in spec.params.items():
            if key not in c:
                if prm.required:
                    raise self.err("PLC5009", f"{what}: check '{chk}' needs '{key}'"
                                   + (f" ({prm.help})" if prm.help else ""), "criterion", i)
                if prm.default is not None:
                    out[key] = prm.default
                continue
            v = c[key]
            if prm.kind == "condition":
                if not isinstance(v, str):
                    raise self.err("PLC5009", f"{what}: '{key}' is a condition string such as "
                                   "\"LEVEL >= 1.95\"", "criterion", i, key)
                try:
                    condition(v)
                except PlcError as e:
                    raise self.err("PLC5009", f"{what}, '{key}': {e.message}", "criterion", i,
                                   key) from None
                for n in condition_names(v):
                    if n not in names and not any(n.upper() == x.upper() for x in names):
                        raise self.err("PLC5009", f"{what}, '{key}': '{n}' is neither a signal "
                                       "of the plant nor a wired or watched address."
                                       f"{did_you_mean(n, names)}", "criterion", i, key)
                out[key] = v
            elif prm.kind == "signal":
                if not isinstance(v, str) or not any(v.upper() == x.upper() for x in names):
                    raise self.err("PLC5009", f"{what}: '{key}' = {v!r} is neither a signal of "
                                   "the plant nor a wired or watched address."
                                   f"{did_you_mean(str(v), names)}", "criterion", i, key)
                out[key] = v
            elif prm.kind == "time":
                out[key] = self.seconds(v, key, what, "criterion", i)
            elif prm.kind in ("number", "int"):
                ok = not isinstance(v, bool) and isinstance(v, int | float)
                if prm.kind == "int":
                    ok = ok and float(v).is_integer()
                if not ok:
                    kind = "a whole number" if prm.kind == "int" else "a number"
                    raise self.err("PLC5009", f"{what}: '{key}' must be {kind}, not {v!r}",
                                   "criterion", i, key)
                out[key] = int(v) if prm.kind == "int" else float(v)
            elif prm.kind == "bool":
                if not isinstance(v, bool):
                    raise self.err("PLC5009", f"{what}: '{key}' is true or false", "criterion",
                                   i, key)
                out[key] = v
            elif prm.kind == "table":
                if not isinstance(v, Mapping):
                    raise self.err("PLC5009", f"{what}: '{key}' is a table, e.g. {key} = "
                                   "{ fallen = false }", "criterion", i, key)
                out[key] = dict(v)
            else:
                if not isinstance(v, str):
                    raise self.err("PLC5009", f"{what}: '{key}' is a string", "criterion", i, key)
                out[key] = v
        if chk == "max_switchings" and ("max" in out) == ("per_hour" in out):
            raise self.err("PLC5009", f"{what}: max_switchings needs max (a count) or per_hour "
                           "(a rate), one of them", "criterion", i)
        if chk == "min_dwell" and "on" not in out and "off" not in out:
            raise self.err("PLC5009", f"{what}: min_dwell needs on and/or off", "criterion", i)
        if chk in ("event_count",) and not any(k in out for k in ("min", "max", "equals")):
            raise self.err("PLC5009", f"{what}: event_count needs min, max or equals",
                           "criterion", i)
        if chk == "value" and not any(k in out for k in ("min", "max", "equals")):
            raise self.err("PLC5009", f"{what}: value needs min, max or equals", "criterion", i)
        return out

    def python(self, spec: str, what: str, i: int) -> Callable[..., Any]:
        mod, _, fn = spec.partition(":")
        if not mod or not fn or not re.match(r"^[A-Za-z_]\w*$", mod):
            raise self.err("PLC5010", f"{what}: python = \"{spec}\": write \"module:function\", "
                           "the module being a .py file in the lab folder", "criterion", i,
                           "python")
        file = self.folder / f"{mod}.py"
        if not file.is_file():
            raise self.err("PLC5010", f"{what}: python = \"{spec}\": no file {file}",
                           "criterion", i, "python")
        return load_check_function(file, fn, lambda m: self.err("PLC5010", f"{what}: {m}",
                                                                "criterion", i, "python"))


_MODULES: dict[str, Any] = {}


def load_check_function(file: Path, fn: str, err: Callable[[str], PlcError]) -> Callable:
    """Import ``fn`` from a lab's check file (cached per file)."""
    key = str(file.resolve())
    mod = _MODULES.get(key)
    if mod is None:
        name = f"plclab_lab_check_{hashlib.sha1(key.encode()).hexdigest()[:10]}"
        spec = importlib.util.spec_from_file_location(name, file)
        if spec is None or spec.loader is None:
            raise err(f"cannot import {file}")
        mod = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(mod)
        except Exception as e:  # noqa: BLE001 - report any error in the lab's file
            raise err(f"{file.name} fails to import: {type(e).__name__}: {e}") from None
        _MODULES[key] = mod
    f = getattr(mod, fn, None)
    if not callable(f):
        raise err(f"{file.name} has no function {fn}()")
    return f


def _bad_plant_param(plant: str, params: Mapping[str, Any]) -> str:
    """Why one of ``params`` does not fit the plant's parameter (by the type of its default:
    a number, a switch or a name), or "" when they all fit."""
    import inspect

    from plants import PLANTS

    sig = inspect.signature(PLANTS[plant].__init__).parameters
    for key, v in params.items():
        if key not in sig:
            continue
        default, note = sig[key].default, str(sig[key].annotation)
        if isinstance(default, bool):
            if not isinstance(v, bool):
                return f"{key} is true or false, not {v!r}"
        elif isinstance(default, str):
            if not isinstance(v, str) or not v:
                return f"{key} is a name in quotes, e.g. {default!r}, not {v!r}"
        elif isinstance(default, int | float) or re.fullmatch(r"(int|float)( \| None)?", note):
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                return f"{key} is a finite number, not {v!r}"
        elif isinstance(v, float) and not math.isfinite(v):
            return f"{key} must be finite, not {v!r}"
    return ""


MAX_MEMORY_MB = 1024 * 1024  # 1 TB


def parse_memory(v: Any) -> int:
    """``1536`` (MB), ``"1.5GB"``, ``"800MB"`` -> megabytes."""
    if isinstance(v, int | float) and not isinstance(v, bool):
        mb = float(v)
    else:
        m = re.match(r"^\s*([\d.]+)\s*(gb|g|mb|m)?\s*$", str(v), re.IGNORECASE)
        if not m:
            raise ValueError(f"'{v}' is not a size; write 1536, \"1.5GB\" or \"800MB\"")
        try:
            mb = float(m.group(1)) * (1024 if (m.group(2) or "mb").lower().startswith("g")
                                      else 1)
        except ValueError:
            raise ValueError(f"'{v}' is not a size; write 1536, \"1.5GB\" or \"800MB\"") \
                from None
    if not math.isfinite(mb) or mb > MAX_MEMORY_MB:
        raise ValueError(f"{v!r} is not a memory size a grader can give; write at most "
                         f"{MAX_MEMORY_MB} (MB) or \"1024GB\"")
    if mb < 64:
        raise ValueError(f"{mb:g} MB is too little to run Python; give at least 64 MB")
    return int(mb)


# ---------------------------------------------------------------------------- deep check


def stub_program(lab: Lab) -> str:
    """An ST program that declares every I/O table address (to bind scenarios without a
    student program)."""
    lines = ["PROGRAM LabIoCheck", "VAR"]
    for i, r in enumerate(lab.io):
        lines.append(f"    io{i} AT {r.address} : {r.type};")
    lines += ["END_VAR", "END_PROGRAM"]
    return "\n".join(lines)


def validate_deep(lab: Lab) -> None:
    """Bind every scenario to a simulation of a stub program: checks the wiring against the
    plant and the program's addresses, the actions' targets and faults (PLC5006/PLC5008)."""
    import plclab
    from plclab.sim import Simulation

    try:
        plc_text = stub_program(lab)
        plclab.loads(plc_text, "labcheck.st", cycle_time=lab.scan)
    except PlcError as e:
        raise grade_error("PLC5007", f"{lab.id}: the I/O table does not make a valid program: "
                          f"{e}", Location(str(lab.path / "lab.toml"))) from None
    for sc in lab.scenarios:
        plc = plclab.loads(plc_text, "labcheck.st", cycle_time=lab.scan,
                           task_intervals=sc.task_intervals)
        acts = [a for a in sc.actions if not any(k in a for k in ("var", "force", "unforce"))]
        spec = ScenarioSpec(sc.name, sc.duration, sc.description, sc.seed, sc.visible,
                            sc.plant_params, acts, sc.until, [])
        watch = [w for w in lab.all_watch(sc) if w.startswith("%")]
        try:
            Simulation(plc, lab.plant, lab.wiring, seed=sc.seed, scenario=spec.scenario(),
                       watch=watch, plant_params={**lab.plant_params, **sc.plant_params})
        except PlcError as e:
            code = "PLC5006" if e.code in ("PLC4002", "PLC4003", "PLC4004", "PLC4005", "PLC4006",
                                           "PLC4007", "PLC4008") else "PLC5008"
            raise grade_error(code, f"scenario '{sc.name}': {e.message} ({e.code})",
                              Location(str(lab.path / "lab.toml"))) from None
