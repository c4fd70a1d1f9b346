"""Reading the criteria, mistakes, alarms and recipes of ``lab.toml`` (part of :class:`~plclab.grade.lab_reader.LabReader`).

:class:`CriteriaSections` holds the methods; the reader's helpers (``err``, ``string``,
``unknown``, ``seconds``) and its ``folder`` and ``path`` come from :class:`LabReader`.
"""

from __future__ import annotations

import hashlib
import importlib.util
import re
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

from .criteria import CHECKS, condition, condition_names
from .errors import did_you_mean
from .lab_spec import CRITERION_KEYS, MISTAKE_KEYS, CriterionSpec, MistakeSpec, ScenarioSpec


class CriteriaSections:
    """The sections of ``lab.toml`` about judging a run: criteria, mistakes, alarms, recipes."""

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
