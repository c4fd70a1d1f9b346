"""Reading ``lab.toml``: every key checked, every problem a PLC50xx error at ``lab.toml:line:col``.

:class:`LabReader` turns the parsed TOML into a :class:`~plclab.grade.lab_spec.Lab`: the top
level, the plant, the wiring, the I/O table and the scenarios here; the criteria, mistakes,
alarms and recipes in :mod:`.lab_reader_criteria`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from plclab.errors import Location, PlcError
from plclab.lang.addresses import parse_located
from plclab.runtime.plc import MAX_CYCLE_NS, MIN_CYCLE_NS

from .errors import did_you_mean, grade_error
from .lab_reader_criteria import CriteriaSections
from .lab_spec import (
    DIAGRAM_KEYS,
    IO_KEYS,
    LANGUAGES,
    LEVELS,
    SCENARIO_KEYS,
    TOP_KEYS,
    IoRow,
    Lab,
    ScenarioSpec,
)

_SIZE_TYPES = {
    "X": ("BOOL",),
    "B": ("BYTE", "SINT", "USINT", "CHAR"),
    "W": ("WORD", "INT", "UINT"),
    "D": ("DWORD", "DINT", "UDINT", "REAL", "TIME"),
    "L": ("LWORD", "LINT", "ULINT", "LREAL", "LTIME"),
}
_ID = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")


class TomlLocator:
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


class LabReader(CriteriaSections):
    """Turns the parsed TOML into a :class:`Lab`, checking every key."""

    def __init__(self, folder: Path, path: Path, text: str, data: dict[str, Any]) -> None:
        self.folder = folder
        self.path = path
        self.data = data
        self.loc = TomlLocator(text, str(path))

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
                                   "\"wiring.toml\", or inline rows", key="wiring")
                wiring = load_wiring(p)
                src = str(p)
            elif isinstance(w, list):
                wiring = Wiring.from_rows(w, plant, source=str(self.path))
                src = "inline"
            else:
                raise self.err("PLC5004", "wiring is a file (wiring = \"wiring.toml\") "
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
            located = parse_located(addr)
            if located is None:
                raise self.err("PLC5004", f"{what} ({name}): address '{addr}' is not a PLC "
                               "address such as %IX0.0, %QX0.1, %IW64, %MW0", "io", i, "address")
            size = located.size
            if size == "X" and located.bit is None:
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
