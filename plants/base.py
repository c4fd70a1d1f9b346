"""Shared machinery for the physics plants.

Every plant is a subclass of :class:`Plant`. The base class owns everything that is the same for
all plants, so that a plant module only describes its physics:

* the signal table (:class:`Signal`), the process image ``_io`` that holds the present value of
  every signal, and the validation of :meth:`Plant.read` and :meth:`Plant.write`;
* fault bookkeeping (:meth:`Plant.inject`, :meth:`Plant.clear`, :attr:`Plant.active_faults`);
* the event list (:class:`Event`, :meth:`Plant.drain_events`);
* the clock (:attr:`Plant.time`) and sub-stepping in :meth:`Plant.step`;
* the seeded random generator (:attr:`Plant.rng`) created in :meth:`Plant.reset`.

A subclass implements four hooks:

``_reset_state()``
    put the physical state back to its initial value (``self.rng`` is already re-seeded);
``_advance(h)``
    integrate the physics over ``h <= max_dt`` seconds (``self.time`` is the start of the step);
``_outputs()``
    copy the physical state into the sensor entries of ``self._io``;
``_faults_changed()``
    optional; cache flags after a fault was injected or cleared.

Signal conventions
------------------
``kind`` says who drives a signal: ``"sensor"`` is computed by the plant, ``"actuator"`` and
``"lamp"`` are written by the PLC, ``"panel"`` is written by the scenario (operator buttons,
selector switches and other things the environment does, such as a hand in a light curtain).
Boolean signals carry the *electrical* state of the contact: a normally closed push button such
as ``STOP`` reads ``True`` while nobody presses it; the scenario presses it by writing ``False``.
"""

from __future__ import annotations

import abc
import difflib
import math
import random
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

__all__ = [
    "Event",
    "Plant",
    "PlantError",
    "Signal",
    "StepProfile",
    "bool_signal",
    "real_signal",
]

KINDS = ("sensor", "actuator", "panel", "lamp")
TYPES = ("bool", "real")
WRITABLE_KINDS = frozenset({"actuator", "panel", "lamp"})


class PlantError(ValueError):
    """A plant was used the wrong way (unknown signal, fault or plant, bad value).

    It is a :class:`ValueError`, so ``except ValueError`` catches it.
    """


@dataclass(frozen=True, slots=True)
class Signal:
    """One named input or output of a plant.

    Parameters
    ----------
    name : str
        Signal name as it appears in wiring tables, e.g. ``"LS1"``.
    kind : str
        ``"sensor"``, ``"actuator"``, ``"panel"`` or ``"lamp"`` (see the module docstring).
    type : str
        ``"bool"`` or ``"real"``.
    unit : str
        Engineering unit (``""`` for booleans).
    range : tuple of float
        Physical range ``(low, high)``; writes to real signals are clipped to it.
    description : str
        One line for tables and tooltips.
    initial : bool or float or None
        Value after :meth:`Plant.reset` for signals written from outside (``None``: ``False``
        for booleans, the low end of the range for reals).
    """

    name: str
    kind: str
    type: str
    unit: str = ""
    range: tuple[float, float] = (0.0, 1.0)
    description: str = ""
    initial: bool | float | None = None

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise PlantError(
                f"signal {self.name!r}: kind must be one of {KINDS}, not {self.kind!r}"
            )
        if self.type not in TYPES:
            raise PlantError(
                f"signal {self.name!r}: type must be one of {TYPES}, not {self.type!r}"
            )

    @property
    def writable(self) -> bool:
        """True for actuators, lamps and panel inputs."""
        return self.kind in WRITABLE_KINDS

    @property
    def default(self) -> bool | float:
        """The value a written signal has after reset."""
        if self.type == "bool":
            return bool(self.initial) if self.initial is not None else False
        return float(self.initial) if self.initial is not None else float(self.range[0])


def bool_signal(name: str, kind: str, description: str, initial: bool = False) -> Signal:
    """Shorthand for a boolean :class:`Signal`."""
    return Signal(name, kind, "bool", "", (0.0, 1.0), description, initial)


def real_signal(
    name: str,
    kind: str,
    unit: str,
    low: float,
    high: float,
    description: str,
    initial: float | None = None,
) -> Signal:
    """Shorthand for a real-valued :class:`Signal`."""
    return Signal(name, kind, "real", unit, (float(low), float(high)), description, initial)


@dataclass(frozen=True, slots=True)
class Event:
    """Something noteworthy that happened in the plant.

    Parameters
    ----------
    time : float
        Plant time in seconds.
    kind : str
        Short machine-readable tag, e.g. ``"overflow"``.
    message : str
        One sentence for a student.
    data : dict
        Extra numbers (volumes, bottle ids, ...).
    """

    time: float
    kind: str
    message: str
    data: dict[str, Any] = field(default_factory=dict)


ProfileSpec = float | int | Sequence[tuple[float, float]] | Callable[[float], float] | None


class StepProfile:
    """A value that changes with time: a constant, a step table or a function.

    Parameters
    ----------
    spec : float, sequence of (time_s, value), callable or None
        ``None`` means zero. A table is a piecewise-constant signal: the value of the last entry
        whose time is ``<= t`` (zero before the first entry). A callable receives the plant time
        in seconds.
    what : str
        Name used in error messages.

    Examples
    --------
    >>> p = StepProfile([(0, 1.0), (10, 2.0)])
    >>> p(5.0), p(10.0), p(99.0)
    (1.0, 2.0, 2.0)
    """

    __slots__ = ("_const", "_fn", "_i", "_times", "_values")

    def __init__(self, spec: ProfileSpec, what: str = "profile") -> None:
        self._fn: Callable[[float], float] | None = None
        self._times: list[float] | None = None
        self._values: list[float] = []
        self._const = 0.0
        self._i = 0
        if spec is None:
            return
        if isinstance(spec, bool) or isinstance(spec, int | float):
            self._const = float(spec)
        elif callable(spec):
            self._fn = spec
        else:
            try:
                pairs = [(float(t), float(v)) for t, v in spec]
            except (TypeError, ValueError) as exc:
                raise PlantError(
                    f"{what} must be a number, a list of (time_s, value) pairs or a function of "
                    f"time; got {spec!r}"
                ) from exc
            if not pairs:
                return
            if any(b[0] < a[0] for a, b in zip(pairs, pairs[1:], strict=False)):
                raise PlantError(f"{what}: the times of the (time_s, value) pairs must increase")
            self._times = [p[0] for p in pairs]
            self._values = [p[1] for p in pairs]

    @property
    def is_zero(self) -> bool:
        """True when the profile is identically zero (lets plants skip work)."""
        return self._fn is None and self._times is None and self._const == 0.0

    def reset(self) -> None:
        """Forget the table position (call from the plant's reset)."""
        self._i = 0

    def __call__(self, t: float) -> float:
        fn = self._fn
        if fn is not None:
            return float(fn(t))
        times = self._times
        if times is None:
            return self._const
        i = self._i
        if t < times[i]:
            if i == 0:
                return 0.0
            i = 0
            if t < times[0]:
                self._i = 0
                return 0.0
        n = len(times)
        while i + 1 < n and times[i + 1] <= t:
            i += 1
        self._i = i
        return self._values[i]


class Plant(abc.ABC):
    """Base class of all plants (see the module docstring for the subclass hooks).

    Attributes
    ----------
    name : str
        Registry key (class attribute).
    title : str
        Human-readable title (class attribute).
    FAULTS : dict
        Fault name -> description (class attribute).
    EVENTS : dict
        Event kind -> description (class attribute); every plant may also emit
        ``fault_injected`` and ``fault_cleared``.
    max_dt : float
        Largest time step in seconds after which the outputs still mean something; larger
        steps given to :meth:`step` are split into sub-steps of at most ``max_dt``.
    time : float
        Seconds since the last :meth:`reset`.
    rng : random.Random
        The plant's only source of randomness, seeded by :meth:`reset`.
    """

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    FAULTS: ClassVar[dict[str, str]] = {}
    EVENTS: ClassVar[dict[str, str]] = {}
    max_dt: float = 0.01

    def __init__(self, signals: Iterable[Signal]) -> None:
        table: dict[str, Signal] = {}
        for sig in signals:
            if sig.name in table:
                raise PlantError(f"{type(self).__name__}: signal {sig.name!r} defined twice")
            table[sig.name] = sig
        self._signals = table
        self._wspec: dict[str, tuple[bool, float, float]] = {
            s.name: (s.type == "bool", s.range[0], s.range[1]) for s in table.values() if s.writable
        }
        self._io: dict[str, bool | float] = {
            s.name: (False if s.type == "bool" else 0.0) for s in table.values()
        }
        self._faults: dict[str, dict[str, Any]] = {}
        self._events: list[Event] = []
        self.time = 0.0
        self.seed = 0
        self.rng = random.Random(0)
        self.reset(0)

    # ------------------------------------------------------------------ description
    @property
    def signals(self) -> dict[str, Signal]:
        """All signals in table order (a copy; changing it changes nothing)."""
        return dict(self._signals)

    @property
    def faults(self) -> dict[str, str]:
        """Fault name -> one-line description."""
        return dict(self.FAULTS)

    @property
    def events(self) -> dict[str, str]:
        """Event kinds this plant emits -> description (plus the two fault events)."""
        out = dict(self.EVENTS)
        out["fault_injected"] = "a fault was injected (data: fault and its numeric params)"
        out["fault_cleared"] = "a fault was cleared"
        return out

    @property
    def active_faults(self) -> dict[str, dict[str, Any]]:
        """Faults injected and not cleared, with the parameters given to :meth:`inject`."""
        return {k: dict(v) for k, v in self._faults.items()}

    # ------------------------------------------------------------------ life cycle
    def reset(self, seed: int = 0) -> None:
        """Return to the initial state; everything random afterwards depends only on ``seed``.

        Clears faults, events and all written signals (they take their ``initial`` value).
        """
        self.time = 0.0
        self.seed = int(seed)
        self.rng = random.Random(self.seed)
        self._events = []
        self._faults = {}
        io = self._io
        for s in self._signals.values():
            if s.writable:
                io[s.name] = s.default
        self._faults_changed()
        self._reset_state()
        self._outputs()

    def step(self, dt: float) -> None:
        """Advance the physics by ``dt`` seconds (sub-stepped at :attr:`max_dt`)."""
        max_dt = self.max_dt
        if dt <= max_dt:
            if dt > 0.0:
                self._advance(dt)
                self.time += dt
                self._outputs()
            elif dt < 0.0 or dt != dt:
                raise PlantError(f"{self.name}: step(dt) needs dt >= 0 seconds, got {dt!r}")
            return
        if not math.isfinite(dt):
            raise PlantError(f"{self.name}: step(dt) needs a finite dt, got {dt!r}")
        n = math.ceil(dt / max_dt - 1e-9)
        h = dt / n
        t0 = self.time
        for k in range(n):
            self._advance(h)
            self.time = t0 + (k + 1) * h
        self._outputs()

    # ------------------------------------------------------------------ signals
    def read(self, name: str) -> bool | float:
        """Present value of a signal (any kind)."""
        try:
            return self._io[name]
        except KeyError:
            raise self._unknown_signal(name) from None

    def write(self, name: str, value: bool | float) -> None:
        """Set an actuator, lamp or panel input.

        Booleans accept ``bool`` and numbers (non-zero is ``True``); reals accept numbers and are
        clipped to the signal's range. Writing a sensor raises :class:`PlantError`.
        """
        spec = self._wspec.get(name)
        if spec is None:
            raise self._not_writable(name)
        if spec[0]:
            if type(value) is bool:
                self._io[name] = value
            elif isinstance(value, int | float) and value == value:
                self._io[name] = bool(value)
            else:
                raise PlantError(
                    f"{self.name}.{name} is a BOOL signal; write True or False, not {value!r}"
                )
        else:
            if isinstance(value, str) or not isinstance(value, int | float):
                raise PlantError(
                    f"{self.name}.{name} is a REAL signal; write a number, not {value!r}"
                )
            v = float(value)
            if v != v:
                raise PlantError(f"{self.name}.{name}: cannot write NaN")
            lo = spec[1]
            hi = spec[2]
            self._io[name] = lo if v < lo else hi if v > hi else v

    def __getitem__(self, name: str) -> bool | float:
        return self.read(name)

    def __setitem__(self, name: str, value: bool | float) -> None:
        self.write(name, value)

    def values(self) -> dict[str, bool | float]:
        """All signal values at once (a copy)."""
        return dict(self._io)

    # ------------------------------------------------------------------ faults
    def inject(self, fault: str, **params: Any) -> None:
        """Activate a named fault now (see :attr:`faults`); parameters are fault specific."""
        if fault not in self.FAULTS:
            raise self._unknown_fault(fault)
        self._faults[fault] = dict(params)
        self._on_inject(fault, params)
        self._faults_changed()
        data = {k: v for k, v in params.items() if _is_number(v) and k != "fault"}
        self._emit(
            "fault_injected", f"fault {fault!r} injected: {self.FAULTS[fault]}", fault=fault, **data
        )
        self._outputs()

    def clear(self, fault: str) -> None:
        """Remove a fault injected earlier (clearing an inactive fault does nothing)."""
        if fault not in self.FAULTS:
            raise self._unknown_fault(fault)
        if self._faults.pop(fault, None) is None:
            return
        self._on_clear(fault)
        self._faults_changed()
        self._emit("fault_cleared", f"fault {fault!r} cleared", fault=fault)
        self._outputs()

    def fault(self, name: str) -> dict[str, Any] | None:
        """Parameters of an active fault, or ``None`` when it is not active."""
        return self._faults.get(name)

    # ------------------------------------------------------------------ events, records
    def drain_events(self) -> list[Event]:
        """Events since the last call (oldest first); the internal list is emptied."""
        ev = self._events
        self._events = []
        return ev

    def snapshot(self) -> dict[str, float]:
        """Extra numeric state worth recording (flat ``str -> float``)."""
        return {}

    def geometry(self) -> dict[str, Any]:
        """Static shapes for drawing, in metres (``{}`` when the plant has none)."""
        return {}

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r} t={self.time:.3f}s>"

    # ------------------------------------------------------------------ hooks
    @abc.abstractmethod
    def _reset_state(self) -> None:
        """Set the physical state to its initial values (after the seed is set)."""

    @abc.abstractmethod
    def _advance(self, h: float) -> None:
        """Integrate the physics over one sub-step of ``h`` seconds."""

    @abc.abstractmethod
    def _outputs(self) -> None:
        """Compute the sensor signals from the state."""

    def _faults_changed(self) -> None:  # noqa: B027 - optional hook
        """Called after every inject/clear/reset; cache fault flags here."""

    def _on_inject(self, fault: str, params: dict[str, Any]) -> None:  # noqa: B027
        """Called when ``fault`` becomes active (before :meth:`_faults_changed`)."""

    def _on_clear(self, fault: str) -> None:  # noqa: B027 - optional hook
        """Called when ``fault`` is cleared (before :meth:`_faults_changed`)."""

    # ------------------------------------------------------------------ helpers
    def _emit(self, kind: str, message: str, **data: Any) -> None:
        self._events.append(Event(self.time, kind, message, data))

    def _unknown_signal(self, name: str) -> PlantError:
        hint = _did_you_mean(str(name), self._signals)
        return PlantError(
            f"plant {self.name!r} has no signal {name!r}.{hint} Signals: {', '.join(self._signals)}"
        )

    def _not_writable(self, name: str) -> PlantError:
        sig = self._signals.get(name)
        if sig is None:
            return self._unknown_signal(name)
        return PlantError(
            f"{self.name}.{name} is a {sig.kind}: the plant computes it, so it can only be read. "
            f"Writable signals: {', '.join(self._wspec)}"
        )

    def _unknown_fault(self, fault: str) -> PlantError:
        hint = _did_you_mean(str(fault), self.FAULTS)
        valid = ", ".join(self.FAULTS) or "(none)"
        return PlantError(
            f"plant {self.name!r} has no fault {fault!r}.{hint} Valid faults: {valid}"
        )


def _did_you_mean(word: str, choices: Iterable[str]) -> str:
    choices = list(choices)
    close = difflib.get_close_matches(word, choices, n=3, cutoff=0.5)
    if not close:
        upper = [c for c in choices if c.lower() == word.lower()]
        close = upper
    if not close:
        return ""
    return " Did you mean " + " or ".join(repr(c) for c in close) + "?"


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float | bool)
