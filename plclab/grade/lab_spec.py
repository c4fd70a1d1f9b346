"""The model of a lab as read from ``lab.toml``: the lab, its I/O rows, scenarios, criteria and
mistakes, and the keys each table of the file may hold.

:func:`plclab.grade.lab.load_lab` builds it (:mod:`.lab_reader` checks every key); the grader,
the scaffold and the course read it.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

from .criteria import Verdict, run_check, signals_of
from .errors import did_you_mean, grade_error

LANGUAGES = {"st": (".st",), "il": (".il",), "ld": (".ld",), "xml": (".xml",)}
"""Language keys of ``languages`` and their file extensions."""
SOURCE_EXTS = {ext: lang for lang, exts in LANGUAGES.items() for ext in exts}
LEVELS = {1: "beginner", 2: "intermediate", 3: "advanced"}
"""``level`` of a lab (``plclab lab list`` orders by it; the course's path through the labs)."""
TOP_KEYS = ("id", "title", "summary", "goals", "plant", "plant_params", "scan", "languages",
            "dialect",
            "time_limit", "memory_limit", "wiring", "io", "watch", "diagram", "scenario",
            "criterion", "mistake", "level", "chapters", "alarms", "recipes", "critical_cap",
            "hidden_scenarios_withheld", "performance_spec")
SCENARIO_KEYS = ("name", "description", "duration", "seed", "visible", "plant_params",
                 "action", "actions", "until", "watch", "recipe", "task_intervals")
CRITERION_KEYS = ("name", "scenario", "scenarios", "check", "python", "params", "points",
                  "message", "hint", "hint_fix", "signals", "window", "description", "requires",
                  "critical", "requirements")
MISTAKE_KEYS = ("file", "max_score", "violates", "description")
IO_KEYS = ("name", "address", "type", "unit", "description")
DIAGRAM_KEYS = ("signals", "window")

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
