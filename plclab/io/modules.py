"""The I/O module kinds: one specification per kind of module a wiring row can name.

A :class:`ModuleKind` says everything the rest of plclab needs to know about a kind of I/O
module, once (as :mod:`plclab.lang.builtins` does for the standard functions and blocks):

* which way it carries a signal (``direction``), which plant signals it takes (``signal``:
  BOOL, REAL, or either) and what the PLC sees (``carries``: a bit, integer counts, or the
  value itself), hence the address sizes a row may use (:attr:`ModuleKind.sizes`: size
  letters of a direct address; their widths in bytes are
  :data:`plclab.lang.addresses.SIZE_BYTES`, a layer above this one);
* its parameters in a wiring row (:class:`Param`: a converter key of
  :data:`plclab.sim.wiring.CONVERTERS`, the help text, the choices and the default), the ranges
  and the scaling among them (signal ranges of :data:`~plclab.io.scaling.SIGNAL_RANGES`, count
  conventions of :data:`~plclab.io.scaling.CONVENTIONS`);
* its faults (``faults``: name -> what happens, the table of the module class that implements
  them, e.g. an analog input's wire break);
* how it is built from a row (``build``), how long it must still be called after its input
  changed (``settle``), whether its output depends on the present input only (``memoryless``),
  and which per-scan code of :data:`plclab.sim.transfers.TRANSFERS` moves it (``transfer``).

The wiring loader (:mod:`plclab.sim.wiring`), the binding and the per-scan transfer
(:mod:`plclab.sim.channels`) and the scenario's I/O faults (:mod:`plclab.sim.sim_actions`) read
:data:`KINDS`; a new kind of module is one entry here (ADR 0068). ``tests/io/test_io_modules.py``
checks that every key names a converter and a transfer that exist;
``tests/sim/test_sim_modules.py`` that an entry alone is enough.

>>> KINDS["ai"].direction, KINDS["ai"].sizes, KINDS["di"].sizes, KINDS["direct"].sizes
('in', ('W', 'D'), ('X',), ())
>>> sorted(KINDS["ai"].faults), KINDS["ai"].params["signal_range"].default
(['short', 'stuck', 'wire_break'], '4-20mA')
>>> alternative(KINDS["ai"], "bool").name, alternative(KINDS["do"], "real").name
('di', 'ao')
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from .analog import AI_FAULTS, AO_FAULTS, AnalogInput, AnalogOutput
from .digital import DI_FAULTS, DO_FAULTS, DO_KINDS, DigitalInput, DigitalOutput
from .scaling import CONVENTIONS, signal_range

__all__ = ["KINDS", "ModuleKind", "Param", "SignalTransmitter", "alternative"]


@dataclass(frozen=True)
class Param:
    """One parameter of a wiring row for a module kind.

    ``convert`` is a key of :data:`plclab.sim.wiring.CONVERTERS` (how the value is checked and
    converted); ``choices`` the words a ``"choice"`` takes; ``default`` the value the builder
    uses when the row leaves it out (None: the module class's own default, given in ``help``).
    """

    convert: str
    help: str
    choices: tuple[str, ...] = ()
    default: Any = None

    @property
    def text(self) -> str:
        """The help with the choices and the default, for messages and listings."""
        extra = []
        if self.choices:
            extra.append("one of " + ", ".join(self.choices))
        if self.default is not None:
            extra.append(f"default {self.default}")
        return self.help + (f" ({'; '.join(extra)})" if extra else "")


_SIZES = {"bit": ("X",), "counts": ("W", "D"), "value": ()}
"""Address sizes by what the PLC sees: a bit, integer counts (16 or 32 bits: a word or a double
word), the value itself (any size; a REAL needs D or L, a BOOL X)."""


def _none(module: Any) -> float:
    return 0.0


def _never(module: Any) -> bool:
    return False


@dataclass(frozen=True)
class ModuleKind:
    """The specification of one kind of I/O module (see the module text).

    Attributes
    ----------
    name : str
        What a wiring row writes as ``module``.
    direction : {"in", "out", None}
        Into the PLC, out of it, or (None) following the address or the signal's kind.
    help : str
        One line for people.
    signal : {"bool", "real", "any"}
        The plant signals it takes. A ``"bool"`` kind with ``real_param`` also takes a REAL
        signal when the row gives that parameter (a digital input's ``threshold``).
    carries : {"bit", "counts", "value"}
        The PLC side: a bit (an ``X`` address or a BOOL variable), integer counts (a word or
        a double word, an integer variable), or the value as it is (any size that fits it).
    params : mapping of str to Param
    faults : mapping of str to str
        Fault name -> what happens (the implementing class's own table).
    transfer : str
        Key of :data:`plclab.sim.transfers.TRANSFERS`: the per-scan code that moves it.
    build : callable or None
        ``build(params, signal)`` -> the module object (``signal`` is the plant's signal, with
        ``unit`` and ``range``); None: no module, the value is copied.
    settle, memoryless : callable
        Of the built module: seconds after a change of its input during which it must still
        be called; whether its output depends on the present input only.
    """

    name: str
    direction: str | None
    help: str
    signal: str
    carries: str
    params: Mapping[str, Param]
    faults: Mapping[str, str] = field(default_factory=dict)
    transfer: str = "copy"
    build: Callable[[dict[str, Any], Any], Any] | None = None
    real_param: str = ""
    settle: Callable[[Any], float] = _none
    memoryless: Callable[[Any], bool] = _never

    @property
    def sizes(self) -> tuple[str, ...]:
        """The address sizes a row of this kind may name (empty: any that fits the signal)."""
        return _SIZES[self.carries]

    def takes(self, is_bool: bool, params: Mapping[str, Any] = {}) -> bool:  # noqa: B006
        """Whether a row with these ``params`` may carry a BOOL (or a REAL) plant signal."""
        if self.signal == "any":
            return True
        if is_bool:
            return self.signal == "bool"
        return self.signal == "real" or bool(self.real_param and self.real_param in params)


class SignalTransmitter:
    """The transmitter of a plant signal that already is mA or V (e.g. the tank's LEVEL_MA):
    the value passes unchanged."""

    def __init__(self, signal: str) -> None:
        self.signal = signal

    def output(self, value: float) -> float:
        return float(value)


# ------------------------------------------------------------------------------- builders
def _build_di(p: dict[str, Any], signal: Any) -> DigitalInput:
    return DigitalInput(**p)


def _build_do(p: dict[str, Any], signal: Any) -> DigitalOutput:
    return DigitalOutput(**p)


def _build_ai(p: dict[str, Any], signal: Any) -> AnalogInput:
    rng = signal_range(p.pop("signal_range", _AI_PARAMS["signal_range"].default))
    tx = None
    lo_d, hi_d = signal.range
    if signal.unit and signal.unit == rng.unit:  # the plant already gives mA or V
        tx = SignalTransmitter(rng.name)
        lo_d, hi_d = rng.lo, rng.hi
    lo = p.pop("lo", lo_d)
    hi = p.pop("hi", hi_d)
    return AnalogInput(lo=lo, hi=hi, signal=rng.name, transmitter=tx, **p)


def _build_ao(p: dict[str, Any], signal: Any) -> AnalogOutput:
    rng_name = p.pop("signal_range", _AO_PARAMS["signal_range"].default)
    lo = p.pop("lo", signal.range[0])
    hi = p.pop("hi", signal.range[1])
    return AnalogOutput(lo=lo, hi=hi, signal=rng_name, **p)


# ------------------------------------------------------------------------------- the kinds
_INVERT = Param("bool", "the PLC bit is the inverse of the contact (default false)")
_CONVENTION = Param("choice", "count convention", CONVENTIONS, "s7")
_AI_PARAMS = {
    "lo": Param("number", "engineering value at 0 % of the signal (default: the plant signal's "
                "range)"),
    "hi": Param("number", "engineering value at 100 % (default: the plant signal's range)"),
    "signal_range": Param("signal_range", "electrical range, e.g. \"4-20mA\", \"0-10V\"",
                          default="4-20mA"),
    "convention": _CONVENTION,
    "bits": Param("int", "ADC resolution in bits (convention default)"),
    "noise": Param("nonneg", "standard deviation of Gaussian noise, engineering units"),
    "tau": Param("seconds", "input filter time constant, s (default 0)"),
    "sample_period": Param("seconds", "time between conversions, s (default 0: every scan)"),
    "seed": Param("int", "seed of the noise (mixed with the simulation seed)"),
    "wire_break_diagnostic": Param("bool", "S7 live-zero wire break reads 32767 (default true)"),
}
_AO_PARAMS = {
    "lo": Param("number", "actuator value at 0 % of the signal (default: the plant signal's "
                "range)"),
    "hi": Param("number", "actuator value at 100 % (default: the plant signal's range)"),
    "signal_range": Param("signal_range", "electrical range, e.g. \"0-10V\", \"4-20mA\"",
                          default="0-10V"),
    "convention": _CONVENTION,
    "bits": Param("int", "DAC resolution in bits (convention default)"),
    "clip": Param("bool", "clip the value to lo..hi (default true)"),
}

KINDS: dict[str, ModuleKind] = {k.name: k for k in (
    ModuleKind(
        "di", "in", "digital input: contact bounce and input filter", "bool", "bit", {
            "filter_ms": Param("ms", "input filter delay, ms (default 3)"),
            "bounce_ms": Param("ms", "contact bounce after each change, ms (default 0)"),
            "bounces": Param("bounces", "extra off/on pairs per bounce: n or [lo, hi] "
                             "(default [1, 4])"),
            "threshold": Param("threshold", "for a REAL signal: ON at/above it, or "
                               "[off_max, on_min]"),
            "seed": Param("int", "seed of the bounce generator (mixed with the simulation seed)"),
            "invert": _INVERT,
        }, DI_FAULTS, "held", _build_di, real_param="threshold",
        settle=lambda m: (m.bounce_ms + m.filter_ms) / 1000.0),
    ModuleKind(
        "ai", "in", "analog input: transmitter, noise, filter, ADC -> counts", "real", "counts",
        _AI_PARAMS, AI_FAULTS, "sampled", _build_ai,
        memoryless=lambda m: m.noise == 0.0 and m.tau == 0.0 and m.sample_period == 0.0),
    ModuleKind(
        "do", "out", "digital output: transistor or relay", "bool", "bit", {
            "kind": Param("choice", "transistor or relay", tuple(DO_KINDS), "transistor"),
            "close_ms": Param("ms", "delay command -> contact closed, ms (relay default 10)"),
            "open_ms": Param("ms", "delay command -> contact open, ms (relay default 5)"),
            "invert": Param("bool", "the actuator gets the inverse of the output bit "
                            "(default false)"),
        }, DO_FAULTS, "held", _build_do,
        settle=lambda m: max(m.close_ms, m.open_ms) / 1000.0),
    ModuleKind(
        "ao", "out", "analog output: counts -> DAC -> actuator value", "real", "counts",
        _AO_PARAMS, AO_FAULTS, "on_change", _build_ao, memoryless=lambda m: True),
    ModuleKind(
        "direct", None, "no model: the value is copied", "any", "value", {
            "invert": Param("bool", "BOOL signals only: copy the inverse (default false)"),
        }),
)}
"""The I/O module kinds a wiring row can name, by name."""


def alternative(kind: ModuleKind, signal: str) -> ModuleKind | None:
    """The first module kind of the same direction that takes ``signal`` ("bool" or "real"):
    what an error message proposes instead of ``kind``."""
    for k in KINDS.values():
        if k is not kind and k.direction == kind.direction and k.signal == signal:
            return k
    return None
