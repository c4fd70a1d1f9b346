"""Analog input and output channels.

An :class:`AnalogInput` is the chain a measured value travels to reach the PLC's input
word::

    plant value (eng units) -> + noise -> transmitter (mA / V) -> input filter (tau)
        -> sample & hold (sample_period) -> ADC (quantise, clip, special codes) -> counts

An :class:`AnalogOutput` is the way back: counts -> DAC -> signal -> actuator (eng units).

Time is virtual: every call passes ``t`` in seconds, monotonic, and the result depends on
the times only, never on the wall clock.

>>> ai = AnalogInput(lo=0.0, hi=160.0, signal="4-20mA", convention="s7")
>>> ai.sample(0.0, 80.0)
13824
>>> ai.inject("wire_break"); ai.sample(0.01, 80.0), ai.status.wire_break
(32767, True)
"""

from __future__ import annotations

import math
import random
from typing import Protocol, runtime_checkable

from plclab.errors import PlcError
from plclab.io._checks import TIME_EPS, check_nonneg, check_range, check_time
from plclab.io.scaling import (
    CountFormat,
    SignalRange,
    Status,
    count_format,
    counts_to_eng,
    counts_to_signal,
    eng_resolution,
    eng_to_counts,
    quantise_counts,
    signal_code,
    signal_range,
    signal_status,
)

__all__ = ["AnalogInput", "AnalogOutput", "LinearTransmitter", "Transmitter"]

AI_FAULTS: dict[str, str] = {
    "wire_break": "the loop opens: 0 mA / 0 V, the range minimum on 0-based ranges, a wire "
                  "break (S7: 32767, NE43: below 3.6 mA) on live-zero ranges",
    "short": "the signal goes to 125 % of the range's top: overflow",
    "stuck": "the input word freezes (at the present value or at value); the diagnostics see "
             "nothing wrong",
}
"""The faults of an analog input (:meth:`AnalogInput.inject`): name -> what happens."""
AO_FAULTS: dict[str, str] = {
    "open": "the wire is open: 0 mA / 0 V reach the actuator",
    "stuck": "the output freezes (at the present value or at value)",
}
"""The faults of an analog output (:meth:`AnalogOutput.inject`): name -> what happens."""


@runtime_checkable
class Transmitter(Protocol):
    """Anything that turns a plant value into a signal: ``output(value) -> mA or V``.

    ``signal`` names the output range (e.g. ``"4-20mA"``).
    """

    signal: str

    def output(self, value: float) -> float:  # pragma: no cover - protocol
        """Signal (mA or V) for the plant value ``value``."""


class LinearTransmitter:
    """An ideal linear transmitter: ``lo .. hi`` engineering units -> the signal range.

    With ``saturate`` (default) the output stays within the range's saturation limits
    (NE43 for 4-20 mA: 3.8 .. 20.5 mA), as real transmitters do.

    Examples
    --------
    >>> tx = LinearTransmitter(0.0, 160.0, "4-20mA")
    >>> tx.output(80.0), tx.output(-10.0), tx.output(500.0)
    (12.0, 3.8, 20.5)
    """

    def __init__(
        self, lo: float, hi: float, signal: str | SignalRange = "4-20mA", saturate: bool = True
    ) -> None:
        check_range(lo, hi)
        self.lo = lo
        self.hi = hi
        self.range = signal_range(signal)
        self.signal = self.range.name
        self.saturate = saturate

    def output(self, value: float) -> float:
        """Signal for the engineering value ``value``."""
        rng = self.range  # rng.from_fraction and min/max, unrolled (issue 19)
        x = rng.lo + (value - self.lo) / (self.hi - self.lo) * (rng.hi - rng.lo)
        if self.saturate:
            lo = rng.sat_lo
            x = x if x > lo else lo
            hi = rng.sat_hi
            x = x if x < hi else hi
        return x

    def __repr__(self) -> str:
        return f"LinearTransmitter({self.lo!r}, {self.hi!r}, {self.signal!r})"


class AnalogInput:
    """One analog input channel with its transmitter.

    Parameters
    ----------
    lo, hi : float
        Engineering values at 0 % and 100 % of the signal (transmitter range).
    signal : str
        The module's measuring range: ``"4-20mA"``, ``"0-20mA"``, ``"0-10V"``,
        ``"+-10V"``, ``"1-5V"``...
    convention : {"s7", "book", "full", "logo"}
        Count convention, see :func:`plclab.io.scaling.count_format`.
    bits : int, optional
        ADC resolution (convention default if omitted).
    noise : float
        Standard deviation of Gaussian noise added to the plant value, in engineering
        units. One draw per conversion, so the noise is white at the sampling rate.
    tau : float
        Time constant of the module's first-order input filter, s (0 = none). The filter
        works on the signal, noise included; it starts settled at the first value.
    sample_period : float
        Time between conversions, s (0 = convert at every :meth:`sample`). Conversions
        happen at ``t0 + k * sample_period`` from the first call; between them the
        input word holds the last conversion.
    seed : int
        Seed of the noise generator.
    transmitter : str or Transmitter, optional
        The field device. ``None``: a :class:`LinearTransmitter` on ``signal``. A range
        name: a linear transmitter with that output (e.g. a ``"4-20mA"`` transmitter on a
        ``"0-20mA"`` input, the textbook's "20 % offset"). An object with ``output(value)``
        such as :class:`plclab.io.pt100.RtdTransmitter`.
    wire_break_diagnostic : bool
        S7 live-zero ranges: report a wire break as 32767 (default) or as -32768.

    Notes
    -----
    The plant value passed at time ``t`` is taken to hold since the previous call, so a
    step given at the first call after ``t = 0`` gives the filter response
    ``1 - exp(-t / tau)`` exactly, however often :meth:`sample` is called. With noise,
    every conversion between two calls is computed (one random draw each), so the noise
    sequence depends on the conversions only, not on the calls; without noise the channel
    jumps straight to the last conversion.

    Faults (:meth:`inject`): ``"wire_break"`` (the loop opens: 0 mA / 0 V, which reads the
    range minimum on 0-based ranges and a wire break on live-zero ranges), ``"short"``
    (the signal goes to 125 % of the range's top: overflow), ``"stuck"`` (the input word
    freezes; the diagnostics see nothing wrong). Faults act on the signal before the
    filter, so a filtered input falls towards 0 mA with its time constant.

    Examples
    --------
    >>> ai = AnalogInput(lo=-20.0, hi=220.0, signal="0-20mA", convention="book", bits=12)
    >>> ai.sample(0.0, 10.0)        # the textbook's example, backwards
    512
    >>> ai.eng
    10.0
    >>> a, b = AnalogInput(noise=0.5, seed=1), AnalogInput(noise=0.5, seed=1)
    >>> [a.sample(k * 0.01, 50.0) for k in range(3)] == [b.sample(k * 0.01, 50.0) for k in range(3)]
    True
    """

    def __init__(
        self,
        lo: float = 0.0,
        hi: float = 100.0,
        signal: str = "4-20mA",
        convention: str = "s7",
        bits: int | None = None,
        noise: float = 0.0,
        tau: float = 0.0,
        sample_period: float = 0.0,
        seed: int = 0,
        transmitter: str | Transmitter | None = None,
        wire_break_diagnostic: bool = True,
    ) -> None:
        check_range(lo, hi)
        check_nonneg("noise", noise, "engineering units")
        check_nonneg("tau", tau, "seconds")
        check_nonneg("sample_period", sample_period, "seconds")
        self.lo = lo
        self.hi = hi
        self.range: SignalRange = signal_range(signal)
        self.format: CountFormat = count_format(convention, bits, self.range.bipolar)
        self.noise = noise
        self.tau = tau
        self.sample_period = sample_period
        self.wire_break_diagnostic = wire_break_diagnostic
        if transmitter is None:
            transmitter = LinearTransmitter(lo, hi, self.range)
        elif isinstance(transmitter, (str, SignalRange)):
            transmitter = LinearTransmitter(lo, hi, transmitter)
        elif not callable(getattr(transmitter, "output", None)):
            raise PlcError(
                "PLC9108", "a transmitter must have an output(value) method returning mA or V"
            )
        tx_signal = getattr(transmitter, "signal", None)
        if tx_signal is not None and signal_range(tx_signal).unit != self.range.unit:
            raise PlcError(
                "PLC9108",
                f"the transmitter sends {signal_range(tx_signal).name} but the input measures "
                f"{self.range.name}; a sensor and its input must use the same kind of signal "
                "(current or voltage)",
            )
        self.transmitter: Transmitter = transmitter
        self.seed = seed
        self.reset(seed)

    # ------------------------------------------------------------------ state
    def reset(self, seed: int | None = None) -> None:
        """Start again: forget the time, the filter and any fault.

        ``seed`` replaces the noise seed when given.
        """
        if seed is not None:
            self.seed = seed
        self._rng = random.Random(self.seed)
        self._t: float | None = None  # time of the last call
        self._t0 = 0.0  # time of the first conversion
        self._k = 0  # index of the last conversion
        self._y = 0.0  # filter output (signal)
        self._n = 0.0  # noise for the interval ending at the next conversion
        self._signal = 0.0  # signal held at the last conversion
        self._counts = 0
        self._status = Status()
        self.fault: str | None = None
        self._stuck: tuple[int, Status] | None = None

    # ------------------------------------------------------------------ faults
    def inject(self, fault: str, value: float | None = None) -> None:
        """Inject a fault from the next :meth:`sample` on.

        Parameters
        ----------
        fault : {"wire_break", "short", "stuck"}
        value : float, optional
            ``"stuck"`` only: the engineering value the input is stuck at (default: it
            freezes at its present reading).
        """
        if fault not in AI_FAULTS:
            raise PlcError(
                "PLC9106",
                f"unknown analog input fault {fault!r}; use one of {', '.join(AI_FAULTS)}",
            )
        self.fault = fault
        self._stuck = None
        if fault == "stuck":
            if value is None:
                self._stuck = (self._counts, self.status)
            else:
                x = self.transmitter.output(value)
                self._stuck = (self._code(x), self._diagnose(x))

    def clear(self) -> None:
        """Remove the fault; the channel reads the live signal from the next sample."""
        self.fault = None
        self._stuck = None

    # ------------------------------------------------------------------ reading
    @property
    def counts(self) -> int:
        """The input word: counts of the last conversion (or the stuck value)."""
        return self._stuck[0] if self._stuck is not None else self._counts

    @property
    def signal(self) -> float:
        """The signal (mA or V) held at the last conversion, after the filter."""
        return self._signal

    @property
    def status(self) -> Status:
        """The module's diagnostics for the last conversion (worked out when first asked:
        most conversions are never diagnosed, issue 19)."""
        if self._stuck is not None:
            return self._stuck[1]
        if self._status is None:
            self._status = self._diagnose(self._signal)
        return self._status

    @property
    def eng(self) -> float:
        """The input word scaled back to engineering units (what AI_SCALE computes)."""
        return counts_to_eng(self.counts, self.lo, self.hi, convention=self.format)

    @property
    def resolution(self) -> float:
        """One count step in engineering units (for a linear transmitter on ``signal``).

        >>> round(AnalogInput(0.0, 160.0).resolution, 6)
        0.005787
        """
        tx = self.transmitter
        span = self.hi - self.lo
        if isinstance(tx, LinearTransmitter):
            span *= self.range.span / tx.range.span
        return eng_resolution(0.0, span, convention=self.format)

    def _code(self, x: float) -> int:
        return signal_code(x, self.range, self.format, self.wire_break_diagnostic)[0]

    def _diagnose(self, x: float) -> Status:
        return signal_status(x, self.range, convention=self.format)

    def _input(self, value: float) -> float:
        """Filter input for the current interval: the signal with noise and faults."""
        if self.fault == "wire_break":
            return self.range.open_value
        if self.fault == "short":
            return self.range.short_value
        return self.transmitter.output(value + self._n)

    def _advance(self, x: float, dt: float) -> None:
        if self.tau <= 0.0:
            self._y = x
        elif dt > 0.0:
            self._y = x + (self._y - x) * math.exp(-dt / self.tau)

    def _convert(self) -> None:
        self._signal = self._y
        self._counts = self._code(self._y)
        self._status = None  # diagnosed from self._signal when asked (see status)
        self._n = self._rng.gauss(0.0, self.noise) if self.noise > 0.0 else 0.0

    def sample(self, t: float, value: float) -> int:
        """The input word at time ``t`` for the plant value ``value`` (held since the
        previous call).

        Parameters
        ----------
        t : float
            Virtual time, s; never smaller than at the previous call.
        value : float
            The plant's value in engineering units.

        Returns
        -------
        int
            Counts, as the PLC's input word (``%IW``) reads them.
        """
        last = self._t
        if (last is not None and self.fault is None and self.sample_period <= 0.0
                and self.tau <= 0.0 and self.noise <= 0.0):
            # a noise-free channel without filter converting now: the general path below with
            # the calls of _input, _advance, _convert and _code unrolled (issue 19; the same
            # arithmetic in the same order, tests/io compare it with signal_code)
            if t < last or not math.isfinite(t):
                check_time(t, last, "AnalogInput.sample")
            x = self.transmitter.output(value + self._n)
            self._y = self._signal = x
            rng, fmt = self.range, self.format
            code, flag = quantise_counts(
                fmt.zero + (x - rng.lo) / (rng.hi - rng.lo) * (fmt.full - fmt.zero), fmt)
            if flag < 0:  # under the range: the wire-break code (or not) as _code decides
                code = self._code(x)
            self._counts = code
            self._status = None
            self._n = 0.0
            self._t = t
            return code
        check_time(t, last, "AnalogInput.sample")
        if self._t is None:
            self._t = self._t0 = t
            self._n = self._rng.gauss(0.0, self.noise) if self.noise > 0.0 else 0.0
            self._y = self._input(value)
            self._convert()
            return self.counts
        period = self.sample_period
        t_filter = self._t
        if period <= 0.0:
            self._advance(self._input(value), t - t_filter)
            self._convert()
        else:
            k_last = math.floor((t - self._t0 + TIME_EPS) / period)
            if k_last > self._k and self.noise == 0.0:
                self._k = k_last - 1  # noise-free: jump straight to the last conversion
            while self._k < k_last:
                self._k += 1
                tc = self._t0 + self._k * period
                self._advance(self._input(value), tc - t_filter)
                t_filter = tc
                self._convert()
            self._advance(self._input(value), t - t_filter)
        self._t = t
        return self.counts


class AnalogOutput:
    """One analog output channel (DAC) and the actuator behind it.

    ``counts -> DAC (clip to the convention's codes, quantise to its step) -> signal ->
    engineering value`` of an actuator that is linear over ``lo .. hi``.

    Parameters
    ----------
    lo, hi : float
        Engineering values at 0 % and 100 % of the signal (e.g. 0..100 % valve opening).
    signal : str
        Output range, e.g. ``"0-10V"`` or ``"4-20mA"``.
    convention, bits
        Count convention and DAC resolution, see :func:`plclab.io.scaling.count_format`.
    clip : bool
        Clip the engineering value to ``lo .. hi`` (the actuator's end stops).

    Faults: ``"open"`` (the wire is open: 0 mA / 0 V reach the actuator) and ``"stuck"``
    (the output holds its present value, or ``value`` in engineering units).

    Examples
    --------
    >>> ao = AnalogOutput(lo=0.0, hi=100.0, signal="0-10V", convention="s7")
    >>> ao.apply(0.0, 13824), ao.signal
    (50.0, 5.0)
    >>> ao.apply(0.1, 40000), round(ao.signal, 3)   # clipped at the over-range, 11.759 V
    (100.0, 11.759)
    >>> AnalogOutput(0.0, 10.0, "0-10V", "book", bits=8).apply(0.0, 1)   # one 8-bit step
    0.0390625
    """

    def __init__(
        self,
        lo: float = 0.0,
        hi: float = 100.0,
        signal: str = "0-10V",
        convention: str = "s7",
        bits: int | None = None,
        clip: bool = True,
    ) -> None:
        check_range(lo, hi)
        self.lo = lo
        self.hi = hi
        self.range: SignalRange = signal_range(signal)
        self.format: CountFormat = count_format(convention, bits, self.range.bipolar)
        self.clip = clip
        self.reset()

    def reset(self) -> None:
        """Start again: output at the range's zero counts, no fault, no time."""
        self._t: float | None = None
        self.fault: str | None = None
        self._stuck: float | None = None
        self.counts = self.format.zero
        self._signal = self._dac(self.counts)

    @property
    def resolution(self) -> float:
        """One DAC step in engineering units."""
        return eng_resolution(self.lo, self.hi, convention=self.format)

    @property
    def signal(self) -> float:
        """The signal (mA or V) on the output terminals."""
        if self.fault == "open":
            return self.range.open_value
        return self._signal

    @property
    def value(self) -> float:
        """The engineering value the actuator receives."""
        if self.fault == "stuck" and self._stuck is not None:
            return self._stuck
        return self._to_eng(self.signal)

    def _dac(self, counts: float) -> float:
        fmt = self.format
        code = fmt.step * math.floor(counts / fmt.step + 0.5)
        code = max(fmt.min_code, min(fmt.max_code, code))
        x = counts_to_signal(code, self.range, convention=fmt)
        if not self.range.bipolar:
            x = max(0.0, x)
        return x

    def _to_eng(self, x: float) -> float:
        y = self.lo + self.range.to_fraction(x) * (self.hi - self.lo)
        if self.clip:
            y = min(max(self.lo, self.hi), max(min(self.lo, self.hi), y))
        return y

    def inject(self, fault: str, value: float | None = None) -> None:
        """Inject ``"open"`` or ``"stuck"`` (at ``value`` eng units, or the present value)."""
        if fault not in AO_FAULTS:
            raise PlcError(
                "PLC9106",
                f"unknown analog output fault {fault!r}; use one of {', '.join(AO_FAULTS)}",
            )
        self._stuck = (self.value if value is None else value) if fault == "stuck" else None
        self.fault = fault

    def clear(self) -> None:
        """Remove the fault."""
        self.fault = None
        self._stuck = None

    def apply(self, t: float, counts: int) -> float:
        """Write ``counts`` to the DAC at time ``t``; return the actuator's engineering value.

        Examples
        --------
        >>> AnalogOutput(0.0, 100.0, "4-20mA").apply(0.0, 6912)
        25.0
        """
        check_time(t, self._t, "AnalogOutput.apply")
        self._t = t
        self.counts = int(counts)
        self._signal = self._dac(counts)
        return self.value

    def eng_to_counts(self, value: float) -> int:
        """Counts to write for the engineering value ``value`` (nominal range only).

        >>> AnalogOutput(0.0, 100.0, "0-10V").eng_to_counts(50.0)
        13824
        """
        return eng_to_counts(value, self.lo, self.hi, convention=self.format, limit=True)
