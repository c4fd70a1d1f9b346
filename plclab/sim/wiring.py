"""Wiring tables: which plant signal reaches which PLC address or variable, through which module.

A wiring table is a list of rows. Each row joins one PLC address (``%IX0.0``, ``%IW64``,
``%QX0.0``, ``%QW64``) or PLC variable (``Main.SP``) to one plant signal through an I/O module
of :mod:`plclab.io`. The kinds of module, their parameters and faults are specified once, in
:data:`plclab.io.modules.KINDS` (:data:`MODULES` here; ADR 0068); today they are:

========  =========  ===================================================================
module    direction  what it models
========  =========  ===================================================================
di        in         :class:`~plclab.io.DigitalInput`: contact bounce, input filter
ai        in         :class:`~plclab.io.AnalogInput`: transmitter, noise, filter, ADC counts
do        out        :class:`~plclab.io.DigitalOutput`: transistor or relay (delays, wear)
ao        out        :class:`~plclab.io.AnalogOutput`: DAC counts -> actuator value
direct    either     no model: the value is copied (the direction follows the address or,
                     for a variable, the signal's kind)
========  =========  ===================================================================

In TOML (``plclab/sim/wirings/tank.toml``)::

    plant = "tank"
    description = "two level switches, the pump contactor and a level transmitter"
    wiring = [
      { plc = "%IX0.0", signal = "LS1", module = "di", filter_ms = 3, description = "low level" },
      { plc = "%IW64", signal = "LEVEL", module = "ai", lo = 0, hi = 2, signal_range = "4-20mA",
        convention = "s7", noise = 0.002, seed = 1 },
      { plc = "%QX0.0", signal = "PUMP", module = "do", kind = "relay" },
    ]

``[[wiring]]`` tables work too. In Python the same rows are a list of dicts (or
:class:`WireRow`): ``[{"plc": "%IX0.0", "signal": "LS1", "module": "di"}, ...]``.

Rows are checked twice: the keys and parameter values when the table is read
(:meth:`Wiring.from_rows`, :func:`load_wiring`), the plant signals, directions, addresses and
variables when a :class:`~plclab.sim.Simulation` binds the table to a plant and a PLC. Every
problem found is reported at once (one :class:`~plclab.errors.PlcError` with all diagnostics),
with the file and line of the row when the table came from a file.

>>> w = Wiring.from_rows([{"plc": "%IX0.0", "signal": "LS1", "module": "di", "filter_ms": 3}])
>>> w[0].module, w[0].params
('di', {'filter_ms': 3.0})
>>> print(w.to_toml().splitlines()[0])
wiring = [
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from plclab.errors import Diagnostic, Location
from plclab.io.modules import KINDS, Param
from plclab.lang.addresses import LOCATED_RE

from ._toml import read_toml, row_reporter, row_spans
from .durations import parse_ns
from .errors import did_you_mean, raise_all

ADDRESS_RE = LOCATED_RE  # the one parser of direct addresses (plclab.lang.addresses)
ROW_KEYS = ("plc", "signal", "module", "description")


# --------------------------------------------------------------------------- parameter types
class _Bad(ValueError):
    """A parameter value that does not fit (the message says what is expected)."""


def _number(v: Any) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise _Bad("a number")
    return float(v)


def _duration(unit_ns: float, unit: str):
    """A parameter converter for durations in ``unit``: a number of that unit, or a duration
    string ('3ms', '0.5s')."""

    def conv(v: Any) -> float:
        if isinstance(v, str):
            return parse_ns(v) / unit_ns
        x = _number(v)
        if x < 0:
            raise _Bad(f"zero or a positive number of {unit}")
        return x

    return conv


_ms = _duration(1e6, "milliseconds")
_seconds = _duration(1e9, "seconds")


def _nonneg(v: Any) -> float:
    x = _number(v)
    if x < 0:
        raise _Bad("zero or a positive number")
    return x


def _int(v: Any) -> int:
    if isinstance(v, bool) or not isinstance(v, int):
        raise _Bad("a whole number")
    return v


def _bool(v: Any) -> bool:
    if not isinstance(v, bool):
        raise _Bad("true or false")
    return v


def _signal_range(v: Any) -> str:
    from plclab.errors import PlcError
    from plclab.io import signal_range

    if not isinstance(v, str):
        raise _Bad("a signal range name such as \"4-20mA\" or \"0-10V\"")
    try:
        return signal_range(v).name
    except PlcError as e:
        raise _Bad(e.message) from None


def _choice(v: Any, options: tuple[str, ...]) -> str:
    if not isinstance(v, str) or v.lower() not in options:
        raise _Bad("one of " + ", ".join(repr(o) for o in options))
    return v.lower()


def _bounces(v: Any) -> int | tuple[int, int]:
    if isinstance(v, list | tuple):
        if len(v) != 2 or not all(isinstance(x, int) and not isinstance(x, bool) for x in v) \
                or not 0 <= v[0] <= v[1]:
            raise _Bad("a whole number or [lo, hi] with 0 <= lo <= hi")
        return (v[0], v[1])
    n = _int(v)
    if n < 0:
        raise _Bad("a whole number >= 0")
    return n


def _threshold(v: Any) -> float | tuple[float, float]:
    if isinstance(v, list | tuple):
        if len(v) != 2:
            raise _Bad("a number or [off_max, on_min]")
        a, b = _number(v[0]), _number(v[1])
        if a > b:
            raise _Bad("[off_max, on_min] with off_max <= on_min")
        return (a, b)
    return _number(v)


CONVERTERS: dict[str, Callable[[Any, Param], Any]] = {
    "number": lambda v, p: _number(v),
    "nonneg": lambda v, p: _nonneg(v),
    "int": lambda v, p: _int(v),
    "bool": lambda v, p: _bool(v),
    "ms": lambda v, p: _ms(v),
    "seconds": lambda v, p: _seconds(v),
    "signal_range": lambda v, p: _signal_range(v),
    "choice": lambda v, p: _choice(v, p.choices),
    "bounces": lambda v, p: _bounces(v),
    "threshold": lambda v, p: _threshold(v),
}
"""How a parameter value of a wiring row is checked and converted, by the ``convert`` key of
its :class:`plclab.io.modules.Param`: ``conv(value, param)`` -> the value, or ``_Bad`` saying
what is expected."""

MODULES = KINDS
"""The I/O modules a wiring row can name: the specification :data:`plclab.io.modules.KINDS`
(this name is the same dict, so an entry added there is a module here)."""


# --------------------------------------------------------------------------- rows
@dataclass
class WireRow:
    """One row of a wiring table.

    Parameters
    ----------
    plc : str
        A PLC address (``%IX0.0``, ``%IW64``, ``%QX0.0``, ``%QW64``, ``%ID8``...) or a variable
        path (``SP``, ``Main.SP``).
    signal : str
        The plant signal.
    module : str
        A module kind of :data:`MODULES` (``di``, ``ai``, ``do``, ``ao``, ``direct``...).
    params : dict
        Module parameters (see :data:`MODULES`), already checked and converted.
    description : str
        What the row is, for people (shown by ``plclab sim`` and in the trace).
    location : Location, optional
        ``file:line`` of the row when it came from a file.
    index : int
        Position in the table (0-based).
    """

    plc: str
    signal: str
    module: str = "direct"
    params: dict[str, Any] = field(default_factory=dict)
    description: str = ""
    location: Location | None = None
    index: int = 0
    key_locations: dict[str, Location] = field(default_factory=dict, repr=False)

    @property
    def is_address(self) -> bool:
        """True when ``plc`` is a direct address (starts with ``%``)."""
        return self.plc.startswith("%")

    def where(self, key: str | None = None) -> Location | None:
        """Location of the row, or of one of its keys when known."""
        if key is not None and key in self.key_locations:
            return self.key_locations[key]
        return self.location

    def label(self) -> str:
        """``row 3 (%IX0.0 <- LS1)`` for messages."""
        kind = MODULES.get(self.module)
        out = kind.direction == "out" if kind is not None and kind.direction else \
            self.is_address and self.plc[1:2].upper() == "Q"  # direct: the address says
        arrow = "->" if out else "<-"
        return f"wiring row {self.index} ({self.plc} {arrow} {self.signal})"

    def to_dict(self) -> dict[str, Any]:
        """The row as a plain dict (the Python form of a TOML row)."""
        d: dict[str, Any] = {"plc": self.plc, "signal": self.signal, "module": self.module}
        d.update(self.params)
        if self.description:
            d["description"] = self.description
        return d


def _row_from(obj: Any, index: int, file: str | None, text: str | None,
              span: tuple[int, int] | None, diags: list[Diagnostic]) -> WireRow | None:
    if isinstance(obj, WireRow):
        raw = obj.to_dict()
    elif isinstance(obj, Mapping):
        raw = dict(obj)
    else:
        loc = Location(file, span[0], 1) if (file and span) else None
        diags.append(Diagnostic("PLC4005", f"wiring row {index} must be a table like "
                                "{ plc = \"%IX0.0\", signal = \"LS1\", module = \"di\" }, not "
                                f"{obj!r}", loc))
        return None

    loc, bad = row_reporter('wiring row', index, file, text, span, diags)

    n0 = len(diags)
    for key in ("plc", "signal"):
        v = raw.get(key)
        if v is None:
            bad("PLC4005", None, f"'{key}' is missing; every row needs plc, signal and module, "
                "e.g. { plc = \"%IX0.0\", signal = \"LS1\", module = \"di\" }")
        elif not isinstance(v, str) or not v.strip():
            bad("PLC4005", key, f"'{key}' must be a non-empty string, not {v!r}")
    module = raw.get("module", "direct")
    if not isinstance(module, str) or module.lower() not in MODULES:
        bad("PLC4005", "module", f"unknown module {module!r}.{did_you_mean(str(module), MODULES)}"
            f" Modules: {', '.join(MODULES)}")
        return None
    module = module.lower()
    spec = MODULES[module]
    desc = raw.get("description", "")
    if not isinstance(desc, str):
        bad("PLC4006", "description", "description must be a string")
        desc = str(desc)
    params: dict[str, Any] = {}
    for key, value in raw.items():
        if key in ROW_KEYS:
            continue
        if key not in spec.params:
            others = [m for m, s in MODULES.items() if key in s.params]
            hint = did_you_mean(key, list(spec.params) + list(ROW_KEYS))
            if others and not hint:
                hint = f" ('{key}' belongs to module {' / '.join(others)})"
            valid = ", ".join(spec.params) or "(none)"
            bad("PLC4005", key, f"module '{module}' has no parameter '{key}'.{hint} "
                f"Its parameters: {valid}; every row may have a description")
            continue
        param = spec.params[key]
        try:
            params[key] = CONVERTERS[param.convert](value, param)
        except _Bad as e:
            bad("PLC4006", key, f"{key} must be {e}, not {value!r} ({param.text})")
        except Exception as e:  # noqa: BLE001 - PlcError of a duration string
            bad("PLC4006", key, f"{key}: {getattr(e, 'message', e)} ({param.text})")
    if len(diags) > n0:
        return None
    plc = raw["plc"].strip()
    m = ADDRESS_RE.fullmatch(plc.upper())
    if m:
        plc = "%" + m.group(1).upper() + (m.group(2) or "X").upper() + m.group(3) + \
            ("." + m.group(4) if m.group(4) is not None else "")
    elif plc.startswith("%"):
        bad("PLC4004", "plc", f"{plc!r} is not a PLC address; write e.g. %IX0.0 (input bit), "
            "%IW64 (input word), %QX0.0 (output bit), %QW64 (output word)")
        return None
    keys = {k: loc(k) for k in raw if loc(k) is not None}
    return WireRow(plc, raw["signal"].strip(), module, params, desc, loc(), index,
                   {k: v for k, v in keys.items() if v is not None})


class Wiring:
    """A checked wiring table (the rows plus where they came from).

    Build one with :meth:`from_rows` (Python), :func:`load_wiring` / :meth:`load` (a TOML file)
    or :func:`plclab.sim.default_wiring` (the default of a plant).

    Attributes
    ----------
    rows : list of WireRow
    plant : str or None
        The plant the table is made for (checked against the simulated plant when given).
    description : str
    source : str or None
        The file it was read from.
    """

    def __init__(self, rows: list[WireRow], plant: str | None = None, description: str = "",
                 source: str | None = None) -> None:
        self.rows = rows
        self.plant = plant
        self.description = description
        self.source = source

    # ------------------------------------------------------------------ building
    @classmethod
    def from_rows(cls, rows: Iterable[Any] | Wiring, plant: str | None = None,
                  description: str = "", source: str | None = None,
                  _text: str | None = None, _key: str = "wiring") -> Wiring:
        """Check a list of rows (dicts or :class:`WireRow`) and build the table."""
        if isinstance(rows, Wiring):
            return rows
        if isinstance(rows, Mapping) or isinstance(rows, str | bytes):
            from .errors import sim_error

            raise sim_error("PLC4005", "a wiring table is a list of rows such as "
                            "[{\"plc\": \"%IX0.0\", \"signal\": \"LS1\", \"module\": \"di\"}] "
                            "(or a path to a TOML file)")
        rows = list(rows)
        spans = row_spans(_text, _key) if _text is not None else []
        if len(spans) != len(rows):
            spans = []
        diags: list[Diagnostic] = []
        out = []
        for i, r in enumerate(rows):
            row = _row_from(r, i, source, _text, spans[i] if spans else None, diags)
            if row is not None:
                out.append(row)
        raise_all(diags)
        return cls(out, plant, description, source)

    @classmethod
    def load(cls, path: str | os.PathLike) -> Wiring:
        """Read a TOML wiring file (see the module docstring for the format)."""
        data, text, filename = read_toml(path, "wiring")
        return cls.from_data(data, filename, text)

    @classmethod
    def from_data(cls, data: Mapping[str, Any], filename: str | None = None,
                  text: str | None = None) -> Wiring:
        """Build from parsed TOML (``plant``, ``description``, ``wiring`` array)."""
        from .errors import sim_error

        unknown = [k for k in data if k not in ("plant", "description", "wiring")]
        if unknown:
            raise sim_error("PLC4005", f"unknown top-level key '{unknown[0]}' in the wiring file."
                            f"{did_you_mean(unknown[0], ['plant', 'description', 'wiring'])} A "
                            "wiring file has plant, description and a wiring array of rows",
                            filename)
        rows = data.get("wiring")
        if not isinstance(rows, list):
            raise sim_error("PLC4005", "the wiring file has no 'wiring' array; write "
                            "wiring = [ { plc = \"%IX0.0\", signal = \"LS1\", module = \"di\" }, "
                            "... ] or [[wiring]] tables", filename)
        plant = data.get("plant")
        if plant is not None and not isinstance(plant, str):
            raise sim_error("PLC4005", "plant must be a plant name such as \"tank\"", filename)
        desc = data.get("description", "")
        return cls.from_rows(rows, plant, str(desc), filename, text)

    # ------------------------------------------------------------------ output
    def to_rows(self) -> list[dict[str, Any]]:
        """The Python form: a list of plain dicts."""
        return [r.to_dict() for r in self.rows]

    def to_toml(self) -> str:
        """The table as a TOML file (inline-table rows)."""
        lines = []
        if self.plant:
            lines.append(f"plant = {_toml_value(self.plant)}")
        if self.description:
            lines.insert(0, f"description = {_toml_value(self.description)}")
        lines.append("wiring = [")
        for r in self.rows:
            items = ", ".join(f"{k} = {_toml_value(v)}" for k, v in r.to_dict().items())
            lines.append(f"  {{ {items} }},")
        lines.append("]")
        return "\n".join(lines) + "\n"

    # ------------------------------------------------------------------ container
    def __iter__(self) -> Iterator[WireRow]:
        return iter(self.rows)

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, i: int) -> WireRow:
        return self.rows[i]

    def __repr__(self) -> str:
        src = f" from {self.source}" if self.source else ""
        return f"<Wiring {len(self.rows)} rows{src}>"

    def table(self) -> str:
        """A plain-text table of the rows (for the command line)."""
        out = []
        for r in self.rows:
            params = ", ".join(f"{k}={v}" for k, v in r.params.items())
            d = f"  # {r.description}" if r.description else ""
            out.append(f"{r.plc:<10} {r.signal:<14} {r.module:<7} {params}{d}")
        return "\n".join(out)


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    s = str(v).replace("\\", "\\\\").replace('"', '\\"')
    return f'"{s}"'


def load_wiring(path: str | os.PathLike) -> Wiring:
    """Read a TOML wiring file (PLC4001 when unreadable, PLC400x for bad rows)."""
    return Wiring.load(path)

