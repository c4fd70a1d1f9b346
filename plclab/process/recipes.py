"""Recipes: named data records written into PLC variables together, and read back.

WinCC's recipe (``001_c648febd3bbd6efb.txt``, lines 6452-6500): a **recipe** is a fixed data
structure (the *elements*: orange, water, sugar, flavouring), a **record** holds one set of
values for it (orange drink, orange juice, orange nectar). Records live on the operator panel;
only the active one is in the PLC. Loading a record writes every element into its PLC
variable at once, after checking each value against the element's limits; saving reads the
variables back into a record.

>>> import plclab
>>> plc = plclab.loads('''PROGRAM Mix
... VAR Orange, Water, Sugar, Flavoring : REAL; END_VAR
... END_PROGRAM''')
>>> mix = Recipe.juice("Mix")
>>> mix.load_into(plc, "orange_juice")
>>> plc["Mix.Orange"], plc["Mix.Sugar"]
(95.0, 0.5)
>>> plc["Mix.Water"] = 12.0
>>> mix.save_from(plc, "my_drink")["water"]
12.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError
from plclab.process.files import read_toml


@dataclass(frozen=True)
class Element:
    """A field of a recipe: its name, the PLC variable it goes to, unit and limits."""

    name: str
    variable: str
    unit: str = ""
    min: float = -math.inf
    max: float = math.inf
    comment: str = ""


@dataclass
class Recipe:
    """A recipe: elements and named records of values."""

    name: str
    elements: list[Element]
    records: dict[str, dict[str, float]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        names = [e.name for e in self.elements]
        if len(set(names)) != len(names) or not names:
            raise PlcError("PLC6040", f"recipe {self.name}: give each element a distinct name")
        for rec, values in self.records.items():
            self.validate(values, rec)
        self._sched: list[tuple[float, str]] = []

    @classmethod
    def juice(cls, program: str = "Mix") -> Recipe:
        """The textbook's juice recipe "Mix" (Tables 21-22) for a program ``program`` with
        REAL variables Orange, Water, Sugar, Flavoring. The book types sugar and flavouring
        as Int (kg) but gives 1.5 and 0.2: they are REAL here."""
        els = [Element("orange", f"{program}.Orange", "l", 0, 100, "orange concentrate"),
               Element("water", f"{program}.Water", "l", 0, 100, "water"),
               Element("sugar", f"{program}.Sugar", "kg", 0, 5, "sugar"),
               Element("flavoring", f"{program}.Flavoring", "kg", 0, 1, "flavouring")]
        recs = {"orange_drink": {"orange": 90, "water": 10, "sugar": 1.5, "flavoring": 0.2},
                "orange_juice": {"orange": 95, "water": 5, "sugar": 0.5, "flavoring": 0.1},
                "orange_nectar": {"orange": 70, "water": 30, "sugar": 1.5, "flavoring": 0.4}}
        return cls("Mix", els, {k: {n: float(x) for n, x in v.items()} for k, v in recs.items()})

    # ------------------------------------------------------------------ checking
    def validate(self, values: dict[str, Any], record: str = "record") -> dict[str, float]:
        """The values as floats when every element is given and within its limits; else
        PlcError PLC6040 listing every problem."""
        problems = []
        out: dict[str, float] = {}
        known = {e.name for e in self.elements}
        for k in values:
            if k not in known:
                problems.append(f"{k} is not an element of the recipe ({', '.join(known)})")
        for e in self.elements:
            v = values.get(e.name)
            if v is None:
                problems.append(f"{e.name} is missing")
                continue
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                problems.append(f"{e.name} = {v!r} is not a number")
                continue
            if not e.min <= v <= e.max:
                problems.append(f"{e.name} = {v:g} {e.unit}".rstrip() +
                                f" is outside {e.min:g}..{e.max:g}")
                continue
            out[e.name] = float(v)
        if problems:
            raise PlcError("PLC6040", f"recipe {self.name}, record {record}: "
                           + "; ".join(problems))
        return out

    def record(self, name: str) -> dict[str, float]:
        if name not in self.records:
            raise PlcError("PLC6041", f"recipe {self.name} has no record {name!r}; the records "
                           f"are {', '.join(self.records) or '(none)'}")
        return self.records[name]

    # ------------------------------------------------------------------ PLC transfer
    def load_into(self, plc: Any, record: str | dict[str, Any]) -> None:
        """Write a record (its name or the values) into the PLC: all elements or none."""
        values = self.validate(record, "given") if isinstance(record, dict) else \
            self.validate(self.record(record), record)
        from plclab.lang import types as T

        setters = []
        for e in self.elements:
            try:
                var = plc.var(e.variable)
                v = values[e.name]
                if T.base_of(var.type).kind in ("int", "bits"):
                    if not float(v).is_integer():
                        raise PlcError("PLC6041", f"recipe {self.name}: {e.variable} is "
                                       f"{var.type}: {e.name} = {v:g} must be a whole number")
                    v = int(v)
                setters.append((var.set, v, e))
            except PlcError as err:
                raise PlcError("PLC6041", f"recipe {self.name}: element {e.name} goes to "
                               f"{e.variable}: {err.message}") from None
        for set_, v, e in setters:
            try:
                set_(v)
            except (TypeError, ValueError):
                raise PlcError("PLC6041", f"recipe {self.name}: {e.variable} cannot hold "
                               f"{v:g}; declare it REAL") from None

    def save_from(self, plc: Any, record: str) -> dict[str, float]:
        """Read the elements' variables into the record ``record`` (checked), and return it."""
        values = {}
        for e in self.elements:
            try:
                values[e.name] = plc.var(e.variable).get()
            except PlcError as err:
                raise PlcError("PLC6041", f"recipe {self.name}: element {e.name} comes from "
                               f"{e.variable}: {err.message}") from None
        values = self.validate({k: float(v) for k, v in values.items()}, record)
        self.records[record] = values
        return values

    # ------------------------------------------------------------------ files
    @classmethod
    def load(cls, path: str | Path) -> Recipe:
        """Read a recipe (TOML): ``name``, ``[[element]]`` rows, ``[record.NAME]`` tables."""
        return cls.from_dict(read_toml(path, "PLC6040", "recipe"), str(path))

    @classmethod
    def from_dict(cls, data: dict[str, Any], source: str = "recipe") -> Recipe:
        els = []
        for i, row in enumerate(data.get("element", []), 1):
            if not isinstance(row, dict) or not {"name", "variable"} <= set(row):
                raise PlcError("PLC6040", f"{source}: [[element]] {i} needs name and variable")
            bad = set(row) - {"name", "variable", "unit", "min", "max", "comment"}
            if bad:
                raise PlcError("PLC6040", f"{source}: element {row['name']}: unknown key(s) "
                               f"{', '.join(sorted(bad))}")
            els.append(Element(str(row["name"]), str(row["variable"]), str(row.get("unit", "")),
                               float(row.get("min", -math.inf)), float(row.get("max", math.inf)),
                               str(row.get("comment", ""))))
        recs = data.get("record", {})
        if not isinstance(recs, dict):
            raise PlcError("PLC6040", f"{source}: records are tables [record.NAME]")
        return cls(str(data.get("name", Path(source).stem)), els,
                   {str(k): dict(v) for k, v in recs.items()})

    def to_toml(self) -> str:
        """The recipe as TOML (what :meth:`load` reads)."""
        lines = [f"name = {_q(self.name)}", ""]
        for e in self.elements:
            lines += ["[[element]]", f"name = {_q(e.name)}", f"variable = {_q(e.variable)}"]
            if e.unit:
                lines.append(f"unit = {_q(e.unit)}")
            if math.isfinite(e.min):
                lines.append(f"min = {e.min!r}")
            if math.isfinite(e.max):
                lines.append(f"max = {e.max!r}")
            if e.comment:
                lines.append(f"comment = {_q(e.comment)}")
            lines.append("")
        for name, values in self.records.items():
            lines.append(f"[record.{_q(name)}]")
            lines += [f"{k} = {float(v)!r}" for k, v in values.items()]
            lines.append("")
        return "\n".join(lines)

    def save(self, path: str | Path) -> None:
        Path(path).write_text(self.to_toml(), encoding="utf-8")

    # ------------------------------------------------------------------ simulation hook
    def schedule(self, t: float, record: str) -> Recipe:
        """Load ``record`` into the PLC at virtual time ``t`` (s) of a simulation."""
        self.record(record)
        self._sched.append((float(t), record))
        self._sched.sort()
        return self

    def bind(self, sim: Any) -> None:
        self._plc = sim.plc
        self._log: list[tuple[float, str]] = []

    def after_scan(self, sim: Any, t_ns: int, recorded: bool) -> None:
        t = t_ns / 1e9
        while self._sched and self._sched[0][0] <= t + 1e-12:
            _, rec = self._sched.pop(0)
            self.load_into(self._plc, rec)
            self._log.append((t, rec))

    def finish(self, sim: Any) -> tuple[list[Any], dict[str, Any]]:
        from plclab.trace.events import Event

        evs = [Event(t, "recipe", self.name, f"record {rec} loaded into the PLC",
                     {"record": rec, **self.records[rec]}) for t, rec in self._log]
        return evs, {"recipe": {"name": self.name, "elements": [e.name for e in self.elements],
                                "records": {k: dict(v) for k, v in self.records.items()}}}


def _q(text: str) -> str:
    import json

    return json.dumps(text, ensure_ascii=False)
