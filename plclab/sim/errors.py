"""Error codes of the simulation layer (wiring tables, scenarios, the simulation, traces).

Every problem a user can cause here is a :class:`plclab.errors.PlcError` with one of these codes,
a message that says what to do and, for files, the ``file:line`` of the offending row (TOML
parsers give no positions, so the line is found from the row's text; when that fails the
message still names the row index and the key).

>>> str(sim_error("PLC4002", "no such signal", "w.toml", 3))
'w.toml:3:1: error PLC4002: no such signal'
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

from plclab.errors import Diagnostic, Location, PlcError

CODES: dict[str, tuple[str, str]] = {
    "PLC4001": ("wiring or scenario file cannot be read",
                "The file is missing, is not UTF-8, or is not valid TOML. The message gives the "
                "parser's line and column."),
    "PLC4002": ("unknown plant signal",
                "A wiring row or a scenario names a signal the plant does not have. `plclab "
                "plants` lists every plant's signals."),
    "PLC4003": ("signal wired the wrong way",
                "Sensors and panel inputs go to PLC inputs (modules di, ai or direct to %I or a "
                "variable); actuators and lamps come from PLC outputs (do, ao or direct from %Q "
                "or a variable). A PLC output cannot drive a sensor or a panel input."),
    "PLC4004": ("bad PLC address or variable in a wiring row",
                "The address is not of the form %IX0.0 / %IW64 / %QX0.0 / %QW64, does not fit "
                "the module (bit modules need bits, analog modules words), lies beyond the "
                "process image, or the variable does not exist or has the wrong type."),
    "PLC4005": ("unknown I/O module or unknown key",
                "A wiring row needs plc, signal and module (di, do, ai, ao, direct); every other "
                "key must be a parameter of that module or description."),
    "PLC4006": ("bad value of a wiring parameter",
                "A module parameter has the wrong type or an impossible value (negative time, "
                "unknown signal range, lo == hi...)."),
    "PLC4007": ("wired twice",
                "Two rows write the same PLC input bits, or two rows drive the same plant "
                "actuator. Remove one of them."),
    "PLC4008": ("file made for another plant",
                "The wiring or scenario file says plant = '...' and that is not the plant being "
                "simulated."),
    "PLC4010": ("bad scenario action",
                "An action needs a time (at) and exactly one verb: press, set, ramp, var, force, "
                "unforce, fault, clear, io_fault, io_clear; the message lists the keys the verb "
                "takes."),
    "PLC4011": ("scenario target cannot be written",
                "The scenario may press or set panel inputs (buttons, switches, the environment) "
                "and PLC variables; sensors are computed by the plant and actuators are the "
                "PLC's."),
    "PLC4012": ("bad time or duration",
                "Write durations as 10ms, 1.5s, 90s, 10min, 1h, 2d, 1h30m, T#1m30s or a number of "
                "seconds; times must not be negative."),
    "PLC4013": ("bad condition",
                "Conditions are simple expressions on plant signals, PLC variables and t (the "
                "time in s): LEVEL > 1.9, RUN and SPEED >= 1400, not LS1 or t > 60. Python "
                "callables are accepted from Python."),
    "PLC4014": ("unknown fault",
                "The plant or the I/O module has no fault with that name; the message lists the "
                "valid ones."),
    "PLC4015": ("bad scenario value",
                "The value does not fit the signal (BOOL needs true/false, REAL a number) or the "
                "PLC variable."),
    "PLC4020": ("bad simulation set-up",
                "Unknown plant or plant parameter, a scan time that differs from the PLC's cycle, "
                "a dt that does not divide the scan into whole sub-steps, or a watch list naming "
                "something that cannot be recorded."),
    "PLC4021": ("unknown trace column or bad trace file",
                "The trace has no column of that name (trace.names lists them), or the file is "
                "not a trace saved by plclab."),
}
"""Code -> (title, explanation) for every code this package raises (PLC40xx)."""


def sim_error(code: str, message: str, file: str | None = None, line: int = 0,
              col: int = 1) -> PlcError:
    """A :class:`PlcError` with an optional ``file:line`` location."""
    loc = Location(str(file), line, col if line else 0) if file else None
    return PlcError(code, message, loc)


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """`` Did you mean 'X'?`` (with a leading space) or an empty string."""
    choices = list(choices)
    close = difflib.get_close_matches(str(word), choices, n=2, cutoff=0.6)
    if not close:
        close = [c for c in choices if c.lower() == str(word).lower()]
    if not close:
        return ""
    return " Did you mean " + " or ".join(repr(c) for c in close) + "?"


def raise_all(diags: list[Diagnostic]) -> None:
    """Raise one PlcError carrying every diagnostic (the first one is the headline)."""
    if not diags:
        return
    first = diags[0]
    raise PlcError(first.code, first.message, first.location, diagnostics=list(diags))
