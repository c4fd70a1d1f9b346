"""Digital input and output channels: contact bounce, input filter, relay delays.

A :class:`DigitalInput` turns a plant's contact (or a voltage, with a threshold) into the
PLC's input bit::

    physical contact -> bounce (raw signal toggles for up to bounce_ms)
        -> input filter (the bit follows the raw signal once it is stable for filter_ms)
        -> PLC bit

Everything is computed from a schedule of event times, so the result is exact and the
same however often :meth:`DigitalInput.sample` is called.

>>> di = DigitalInput(filter_ms=3.0)
>>> di.sample(0.0, False), di.sample(0.010, True), di.sample(0.012, True), di.sample(0.014, True)
(False, False, False, True)
>>> [(round(t, 6), v) for t, v in di.filtered_transitions]   # 10 ms + 3 ms filter
[(0.013, True)]

A :class:`DigitalOutput` is the way back, with the switching delays and wear of a relay:

>>> do = DigitalOutput("relay", close_ms=10.0, open_ms=5.0)
>>> do.apply(0.0, True), do.apply(0.009, True), do.apply(0.010, True), do.operations
(False, False, True, 1)
"""

from __future__ import annotations

import bisect
import math
import random
from dataclasses import dataclass

from plclab.errors import PlcError
from plclab.io._checks import TIME_EPS, check_nonneg, check_time

__all__ = ["IEC_TYPE1_24V", "ChatterStats", "DigitalInput", "DigitalOutput"]

IEC_TYPE1_24V: tuple[float, float] = (5.0, 15.0)
"""IEC 61131-2 type 1 24 V DC input: OFF at or below 5 V, ON at or above 15 V; in
between the bit keeps its state (a hysteresis)."""

DI_FAULTS: dict[str, str] = {
    "open": "the wire is open: the input reads FALSE",
    "stuck_1": "the input reads TRUE whatever the contact does",
}
"""The faults of a digital input (:meth:`DigitalInput.inject`): name -> what happens."""
DO_FAULTS: dict[str, str] = {
    "welded": "the contacts are welded: the actuator stays on",
    "open_coil": "the relay coil is open: the contacts never close",
}
"""The faults of a digital output (:meth:`DigitalOutput.inject`): name -> what happens."""
DO_KINDS = {"transistor": (0.0, 0.0), "relay": (10.0, 5.0)}
"""Digital output kinds: name -> default (close_ms, open_ms)."""


class DigitalInput:
    """One digital input channel: contact bounce and the input filter.

    Parameters
    ----------
    filter_ms : float
        Input filter delay, ms: the PLC bit takes a new value only after the raw signal
        has kept it for this long (default 3 ms; the textbook gives 2-3 ms as the
        shortest pulse a general-purpose input registers). 0 passes every raw edge.
    bounce_ms : float
        Contact bounce, ms (0 = an ideal contact; mechanical contacts bounce 1-5 ms).
        After each change of the physical contact the raw signal toggles a random, even
        number of extra times, all within ``bounce_ms``, and ends at the new value.
    bounces : int or (int, int)
        How many extra off/on pairs a bounce has: a number, or the inclusive range it is
        drawn from (default 1..4, i.e. 3 to 9 raw edges per physical change).
    threshold : float or (float, float), optional
        For an analog-ish physical input (volts): ON at or above a single threshold, or
        with a pair ``(off_max, on_min)`` OFF at or below ``off_max``, ON at or above
        ``on_min`` and unchanged in between (see :data:`IEC_TYPE1_24V`).
    seed : int
        Seed of the bounce generator.

    Notes
    -----
    A change of the physical input is taken to happen at the ``t`` of the first call that
    reports it. Faults (:meth:`inject`): ``"open"`` (the wire is open, the raw signal is
    FALSE) and ``"stuck_1"`` (the raw signal is TRUE); both take effect at the next call,
    without bounce, and still pass the input filter.

    Examples
    --------
    >>> di = DigitalInput(filter_ms=3.0, bounce_ms=4.0, seed=7)
    >>> di.sample(0.0, False)
    False
    >>> di.sample(0.100, True), di.sample(0.200, True)
    (False, True)
    >>> edges = di.raw_transitions          # the press at 0.1 s bounces within 4 ms
    >>> len(edges) >= 3, edges[-1][0] - edges[0][0] <= 0.004
    (True, True)
    >>> len(di.filtered_transitions)        # but the PLC sees one edge
    1
    """

    def __init__(
        self,
        filter_ms: float = 3.0,
        bounce_ms: float = 0.0,
        bounces: int | tuple[int, int] = (1, 4),
        threshold: float | tuple[float, float] | None = None,
        seed: int = 0,
    ) -> None:
        check_nonneg("filter_ms", filter_ms, "milliseconds")
        check_nonneg("bounce_ms", bounce_ms, "milliseconds")
        lo, hi = (bounces, bounces) if isinstance(bounces, int) else tuple(bounces)
        if not (isinstance(lo, int) and isinstance(hi, int) and 0 <= lo <= hi):
            raise PlcError(
                "PLC9105",
                f"bounces must be a whole number >= 0 or a range (lo, hi) with lo <= hi, "
                f"not {bounces!r}",
            )
        if threshold is not None:
            th = (threshold, threshold) if isinstance(threshold, (int, float)) else threshold
            if len(th) != 2 or not th[0] <= th[1]:
                raise PlcError(
                    "PLC9105",
                    f"threshold must be a number or (off_max, on_min) with off_max <= on_min, "
                    f"not {threshold!r}",
                )
            self._th: tuple[float, float] | None = (float(th[0]), float(th[1]))
        else:
            self._th = None
        self.filter_ms = filter_ms
        self.bounce_ms = bounce_ms
        self.bounces = (lo, hi)
        self.threshold = threshold
        self.seed = seed
        self.reset(seed)

    def reset(self, seed: int | None = None) -> None:
        """Start again: forget the time, the histories and any fault."""
        if seed is not None:
            self.seed = seed
        self._rng = random.Random(self.seed)
        self._t: float | None = None
        self._contact = False  # physical contact after the threshold
        self._effective = False  # physical value after faults
        self.initial: bool | None = None
        """Raw (and filtered) value at the first call."""
        self._raw: list[tuple[float, bool]] = []  # schedule, may reach into the future
        self._raw_times: list[float] = []
        self._filtered: list[tuple[float, bool]] = []
        self._next = 0  # first raw transition the filter has not decided on
        self._value = False
        self.fault: str | None = None
        self._fault_changed = False

    # ------------------------------------------------------------------ faults
    def inject(self, fault: str) -> None:
        """Inject ``"open"`` (reads FALSE) or ``"stuck_1"`` (reads TRUE) from the next call."""
        if fault not in DI_FAULTS:
            raise PlcError(
                "PLC9106",
                f"unknown digital input fault {fault!r}; use one of {', '.join(DI_FAULTS)}",
            )
        self.fault = fault
        self._fault_changed = True

    def clear(self) -> None:
        """Remove the fault from the next call on."""
        self.fault = None
        self._fault_changed = True

    # ------------------------------------------------------------------ histories
    @property
    def value(self) -> bool:
        """The PLC bit at the time of the last call."""
        return self._value

    @property
    def raw_transitions(self) -> list[tuple[float, bool]]:
        """Edges of the raw (bouncing, unfiltered) signal up to the last call: ``(t, value)``."""
        if self._t is None:
            return []
        end = bisect.bisect_right(self._raw_times, self._t + TIME_EPS)
        return self._raw[:end]

    @property
    def filtered_transitions(self) -> list[tuple[float, bool]]:
        """Edges of the PLC bit up to the last call: ``(t, value)``."""
        return list(self._filtered)

    def raw_at(self, t: float) -> bool:
        """The raw signal at time ``t`` (as far as it is known)."""
        i = bisect.bisect_right(self._raw_times, t)
        if i == 0:
            return bool(self.initial)
        return self._raw[i - 1][1]

    def raw_series(self, t0: float, t1: float, dt: float = 0.001) -> list[tuple[float, bool]]:
        """The raw signal sampled every ``dt`` s from ``t0`` to ``t1`` (for plots, e.g. at
        the 1 ms resolution of a bounce analysis)."""
        n = int(math.floor((t1 - t0) / dt + 1e-9))
        return [(t0 + k * dt, self.raw_at(t0 + k * dt)) for k in range(n + 1)]

    # ------------------------------------------------------------------ evaluation
    def _to_contact(self, physical: bool | float) -> bool:
        if self._th is None or isinstance(physical, bool):
            return bool(physical)
        off_max, on_min = self._th
        x = float(physical)
        if x >= on_min:
            return True
        if x <= off_max:
            return False
        return self._contact

    def _raw_value_at_end(self) -> bool:
        return self._raw[-1][1] if self._raw else bool(self.initial)

    def _schedule(self, tp: float, value: bool, bounce: bool) -> None:
        """Physical change to ``value`` at ``tp``: cancel the rest of any running bounce
        and schedule the raw edges of this one."""
        cut = max(bisect.bisect_right(self._raw_times, tp), self._next)
        del self._raw[cut:]
        del self._raw_times[cut:]
        times = [tp]
        if bounce and self.bounce_ms > 0.0:
            pairs = self._rng.randint(*self.bounces)
            span = self.bounce_ms / 1000.0
            offsets = sorted(span * (1.0 - self._rng.random()) for _ in range(2 * pairs))
            times += [tp + o for o in offsets]
        for i, ti in enumerate(times):
            v = value if i % 2 == 0 else not value
            if v != self._raw_value_at_end() and (not self._raw or ti > self._raw[-1][0]):
                self._raw.append((ti, v))
                self._raw_times.append(ti)

    def _resolve(self, t: float) -> None:
        """Decide every filter event that happens at or before ``t``."""
        delay = self.filter_ms / 1000.0
        raw = self._raw
        while self._next < len(raw):
            ti, vi = raw[self._next]
            fire = ti + delay
            if fire > t + TIME_EPS:
                break
            if self._next + 1 < len(raw) and raw[self._next + 1][0] < fire:
                self._next += 1  # the raw signal changed again before it was stable
                continue
            if vi != self._value:
                self._value = vi
                self._filtered.append((fire, vi))
            self._next += 1

    def sample(self, t: float, physical: bool | float) -> bool:
        """The PLC's input bit at time ``t`` for the physical contact ``physical``.

        Parameters
        ----------
        t : float
            Virtual time, s; never smaller than at the previous call.
        physical : bool or float
            Contact state, or a voltage when the input has a ``threshold``.
        """
        check_time(t, self._t, "DigitalInput.sample")
        self._contact = self._to_contact(physical)
        effective = {"open": False, "stuck_1": True}.get(self.fault or "", self._contact)
        if self._t is None:
            self.initial = self._value = self._effective = effective
        elif effective != self._effective:
            self._schedule(t, effective, bounce=not self._fault_changed)
            self._effective = effective
        self._fault_changed = False
        self._t = t
        self._resolve(t)
        return self._value


@dataclass(frozen=True, slots=True)
class ChatterStats:
    """How hard an output was worked over a run (see :meth:`DigitalOutput.chatter_stats`).

    Attributes
    ----------
    switchings : int
        Contact changes (closing and opening).
    operations : int
        Contact closures caused by the coil (the wear counter).
    duration : float
        Length of the run, s (first to last call).
    per_minute : float
        Switchings per minute over the run.
    min_on, min_off : float or None
        Shortest completed closed / open interval, s (None if there was none).
    """

    switchings: int
    operations: int
    duration: float
    per_minute: float
    min_on: float | None
    min_off: float | None


class DigitalOutput:
    """One digital output: a transistor (instant) or a relay (delays, wear).

    Parameters
    ----------
    kind : {"transistor", "relay"}
    close_ms, open_ms : float, optional
        Switching delays, ms, from the command to the contact closing / opening. Defaults:
        0 / 0 for a transistor, 10 / 5 for a relay.

    Notes
    -----
    A command change at ``t`` moves the contact at ``t + delay``. A command that reverts
    before the contact moved cancels the move, so pulses shorter than the delay never
    reach the load. Faults (:meth:`inject`): ``"welded"`` (the contact is closed from the
    next call on, whatever the command) and ``"open_coil"`` (the coil never pulls in: the
    contact opens with its delay and stays open). Contact changes caused by a fault are
    in :attr:`switch_times` but not in :attr:`operations`.

    Examples
    --------
    >>> do = DigitalOutput("relay")
    >>> [do.apply(t / 1000, c) for t, c in [(0, True), (4, False), (20, False)]]
    [False, False, False]
    >>> do.operations                      # a 4 ms pulse is shorter than the 10 ms delay
    0
    """

    def __init__(
        self, kind: str = "transistor", close_ms: float | None = None, open_ms: float | None = None
    ) -> None:
        if kind not in DO_KINDS:
            raise PlcError(
                "PLC9107",
                f"unknown digital output kind {kind!r}; use one of {', '.join(DO_KINDS)}",
            )
        close_default, open_default = DO_KINDS[kind]
        self.kind = kind
        self.close_ms = close_default if close_ms is None else close_ms
        self.open_ms = open_default if open_ms is None else open_ms
        check_nonneg("close_ms", self.close_ms, "milliseconds")
        check_nonneg("open_ms", self.open_ms, "milliseconds")
        self.reset()

    def reset(self) -> None:
        """Start again: contact open, counters and history cleared, no fault."""
        self._t: float | None = None
        self._t_first: float | None = None
        self._command = False  # effective command the contact is heading for
        self._state = False
        self._pending: tuple[float, bool] | None = None
        self.operations = 0
        """Contact closures caused by the coil (wear)."""
        self.switch_times: list[tuple[float, bool]] = []
        """Every contact change: ``(t, closed)``."""
        self.fault: str | None = None
        self._fault_changed = False

    @property
    def state(self) -> bool:
        """The contact at the time of the last call (True = closed)."""
        return self._state

    def inject(self, fault: str) -> None:
        """Inject ``"welded"`` or ``"open_coil"`` from the next call on."""
        if fault not in DO_FAULTS:
            raise PlcError(
                "PLC9106",
                f"unknown digital output fault {fault!r}; use one of {', '.join(DO_FAULTS)}",
            )
        self.fault = fault
        self._fault_changed = True

    def clear(self) -> None:
        """Remove the fault from the next call on."""
        self.fault = None
        self._fault_changed = True

    def _switch(self, t: float, closed: bool, counted: bool) -> None:
        if closed == self._state:
            return
        self._state = closed
        self.switch_times.append((t, closed))
        if closed and counted:
            self.operations += 1

    def _run_pending(self, t: float) -> None:
        if self._pending is not None and self._pending[0] <= t + TIME_EPS:
            te, closed = self._pending
            self._pending = None
            self._switch(te, closed, counted=True)

    def apply(self, t: float, commanded: bool) -> bool:
        """Command the output at time ``t``; return the contact state at ``t``.

        Parameters
        ----------
        t : float
            Virtual time, s; never smaller than at the previous call.
        commanded : bool
            The PLC's output bit (``%Q``).
        """
        check_time(t, self._t, "DigitalOutput.apply")
        if self._t_first is None:
            self._t_first = t
        self._t = t
        self._run_pending(t)
        if self.fault == "welded":
            self._pending = None
            self._switch(t, True, counted=False)
            self._command = True
            self._fault_changed = False
            return self._state
        command = bool(commanded) and self.fault != "open_coil"
        if command != self._command or self._fault_changed:
            self._command = command
            self._pending = None
            if command != self._state:
                delay = (self.close_ms if command else self.open_ms) / 1000.0
                self._pending = (t + delay, command)
        self._fault_changed = False
        self._run_pending(t)
        return self._state

    def chatter_stats(self) -> ChatterStats:
        """Switching statistics over the run so far.

        Examples
        --------
        >>> do = DigitalOutput()
        >>> for k in range(61):
        ...     _ = do.apply(k * 0.5, k % 4 == 1)      # on for 0.5 s every 2 s
        >>> s = do.chatter_stats()
        >>> s.switchings, s.operations, s.per_minute, s.min_on, s.min_off
        (30, 15, 60.0, 0.5, 1.5)
        """
        duration = 0.0
        if self._t is not None and self._t_first is not None:
            duration = self._t - self._t_first
        n = len(self.switch_times)
        on: list[float] = []
        off: list[float] = []
        for (t0, closed), (t1, _) in zip(self.switch_times, self.switch_times[1:], strict=False):
            (on if closed else off).append(t1 - t0)
        return ChatterStats(
            switchings=n,
            operations=self.operations,
            duration=duration,
            per_minute=n / duration * 60.0 if duration > 0.0 else 0.0,
            min_on=min(on) if on else None,
            min_off=min(off) if off else None,
        )
