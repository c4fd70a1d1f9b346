"""Scaling between engineering units, electrical signals and ADC counts.

Pure functions shared by the I/O modules (:mod:`plclab.io.analog`) and by the
AI_SCALE / AO_SCALE function blocks of the runtime. Three quantities meet here:

* the **engineering value** a plant speaks (bar, degrees Celsius, percent), over a
  measuring range ``lo .. hi``;
* the **electrical signal** on the wire (V or mA), over a standard
  :class:`SignalRange` such as ``"4-20mA"`` whose lower end may be a *live zero*;
* the **counts** the PLC reads from its input word, in one of four
  :class:`CountFormat` conventions:

  ``"book"``  the textbook's rule: ``N / 2**n`` (a 12-bit ADC divides by 4096);
  ``"full"``  ``N / (2**n - 1)``: full scale is the largest code;
  ``"s7"``    Siemens S7: 0..27648 nominal (-27648..27648 bipolar), over-range up to
              32511, under-range down to -4864, 32767 = overflow, -32768 = underflow;
  ``"logo"``  Siemens LOGO!: 0..1000 from a 10-bit ADC.

The textbook's worked example (0-20 mA, -20..+220 degC, 12 bit, N = 512):

>>> counts_to_eng(512, -20.0, 220.0, convention="book", bits=12)
10.0

An S7 4-20 mA pressure transmitter over 0..160 bar:

>>> counts_to_eng(13824, 0.0, 160.0, convention="s7")
80.0
>>> signal_to_counts(12.0, "4-20mA", convention="s7")
13824

Wire break on a live-zero S7 channel reads 32767 (7FFF): the S7-1200 behaviour with the
wire-break diagnostic enabled; without it the channel reads -32768 (8000, underflow):

>>> signal_to_counts(0.0, "4-20mA", convention="s7")
32767
>>> signal_to_counts(0.0, "4-20mA", convention="s7", wire_break_diagnostic=False)
-32768

Quantisation rounds to the nearest code (a mid-tread quantiser); results beyond the
representable codes are clipped (``book``, ``full``, ``logo``) or replaced by the
overflow / underflow code (``s7``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from plclab.errors import PlcError

__all__ = [
    "CONVENTIONS",
    "SIGNAL_RANGES",
    "CountFormat",
    "SignalRange",
    "Status",
    "count_format",
    "counts_status",
    "counts_to_eng",
    "counts_to_signal",
    "eng_resolution",
    "eng_to_counts",
    "eng_to_signal",
    "resolution",
    "signal_range",
    "signal_status",
    "signal_to_counts",
    "signal_to_eng",
]


# --------------------------------------------------------------------------- signal ranges


@dataclass(frozen=True, slots=True)
class SignalRange:
    """A standard electrical signal range.

    Parameters
    ----------
    name : str
        Canonical name, e.g. ``"4-20mA"``.
    lo, hi : float
        Signal at 0 % and at 100 % of the measuring range (``lo`` is the live zero of
        ``4-20mA`` and ``1-5V``).
    unit : str
        ``"V"`` or ``"mA"``.
    sat_lo, sat_hi : float
        Where a transmitter's output saturates when the measured value leaves its range
        (NAMUR NE43 for live-zero current: 3.8 and 20.5 mA).
    wire_break_at : float or None
        Live-zero ranges only: a signal at or below this means a failed transmitter or a
        broken wire (NE43: <= 3.6 mA).
    fault_high_at : float or None
        Live-zero ranges only: a signal at or above this means a failure, typically a short
        circuit in the loop (NE43: >= 21 mA).

    Examples
    --------
    >>> r = signal_range("4-20mA")
    >>> r.span, r.live_zero, r.bipolar
    (16.0, True, False)
    >>> r.to_fraction(12.0)
    0.5
    """

    name: str
    lo: float
    hi: float
    unit: str
    sat_lo: float
    sat_hi: float
    wire_break_at: float | None = None
    fault_high_at: float | None = None

    @property
    def span(self) -> float:
        """Electrical span ``hi - lo``."""
        return self.hi - self.lo

    @property
    def bipolar(self) -> bool:
        """True for ranges symmetric about zero (``+-10V``)."""
        return self.lo < 0.0

    @property
    def live_zero(self) -> bool:
        """True when 0 % is carried by a non-zero signal (4 mA, 1 V)."""
        return self.lo > 0.0

    @property
    def short_value(self) -> float:
        """Signal an input reads when its wire is shorted: 125 % of ``hi``, beyond any
        over-range (25 mA on a current loop, 12.5 V on a 0-10 V input)."""
        return 1.25 * self.hi

    @property
    def open_value(self) -> float:
        """Signal an input reads when its wire is open: 0 mA or 0 V."""
        return 0.0

    def to_fraction(self, value: float) -> float:
        """Signal -> fraction of the nominal range (0.0 at ``lo``, 1.0 at ``hi``)."""
        return (value - self.lo) / self.span

    def from_fraction(self, fraction: float) -> float:
        """Fraction of the nominal range -> signal."""
        return self.lo + fraction * self.span


SIGNAL_RANGES: dict[str, SignalRange] = {
    r.name: r
    for r in (
        SignalRange("0-10V", 0.0, 10.0, "V", 0.0, 10.25),
        SignalRange("0-5V", 0.0, 5.0, "V", 0.0, 5.125),
        SignalRange("1-5V", 1.0, 5.0, "V", 0.95, 5.125, 0.9, 5.25),
        SignalRange("+-10V", -10.0, 10.0, "V", -10.25, 10.25),
        SignalRange("+-5V", -5.0, 5.0, "V", -5.125, 5.125),
        SignalRange("0-20mA", 0.0, 20.0, "mA", 0.0, 20.5),
        SignalRange("4-20mA", 4.0, 20.0, "mA", 3.8, 20.5, 3.6, 21.0),
    )
}
"""The standard ranges by canonical name."""

_RANGE_KEYS = {name.lower(): r for name, r in SIGNAL_RANGES.items()}


def signal_range(signal: str | SignalRange) -> SignalRange:
    """Look up a signal range by name (case, spaces, ``±`` and ``..`` are forgiven).

    Raises
    ------
    PlcError
        PLC9101 for an unknown name.

    Examples
    --------
    >>> signal_range("4..20 mA").name
    '4-20mA'
    >>> signal_range("±10V").lo
    -10.0
    """
    if isinstance(signal, SignalRange):
        return signal
    key = str(signal).strip().lower().replace(" ", "").replace("±", "+-").replace("..", "-")
    if key.startswith("-") and key.count("-") == 2:  # "-10-10v"
        key = "+-" + key.split("-", 2)[2]
    found = _RANGE_KEYS.get(key)
    if found is None:
        raise PlcError(
            "PLC9101",
            f"unknown signal range {signal!r}; use one of {', '.join(SIGNAL_RANGES)}",
        )
    return found


# --------------------------------------------------------------------------- count formats

CONVENTIONS: tuple[str, ...] = ("book", "full", "s7", "logo")
"""The count conventions :func:`count_format` knows."""

_DEFAULT_BITS = {"book": 12, "full": 12, "s7": 15, "logo": 10}

S7_NOMINAL = 27648
S7_OVERRANGE = 32511
S7_UNDERRANGE = -4864
S7_OVERFLOW = 32767
S7_UNDERFLOW = -32768


@dataclass(frozen=True, slots=True)
class CountFormat:
    """How an ADC's codes relate to its signal range.

    ``zero`` counts correspond to the range's lower end, ``full`` counts to its upper
    end, and codes between ``min_code`` and ``max_code`` are what the converter can
    produce. Codes are multiples of ``step`` (S7 modules left-justify their result, so
    a 12-bit channel moves in steps of 8 counts).

    Examples
    --------
    >>> f = count_format("s7")
    >>> f.zero, f.full, f.min_code, f.max_code, f.overflow_code
    (0, 27648, -4864, 32511, 32767)
    >>> count_format("s7", bits=12).step
    8
    >>> count_format("book", bits=12).full
    4096
    """

    convention: str
    bits: int
    bipolar: bool
    zero: int
    full: int
    step: int
    min_code: int
    max_code: int
    underflow_code: int | None = None
    overflow_code: int | None = None
    wire_break_code: int | None = None

    @property
    def nominal_counts(self) -> int:
        """Counts between the range's lower and upper end (the divisor of scaling)."""
        return self.full - self.zero


def count_format(
    convention: str | CountFormat = "book", bits: int | None = None, bipolar: bool = False
) -> CountFormat:
    """Build the :class:`CountFormat` of a convention.

    Parameters
    ----------
    convention : {"book", "full", "s7", "logo"} or CountFormat
        ``book`` and ``full`` are unsigned (a bipolar range maps -10 V to 0 counts, as
        the textbook's formula does); ``s7`` is signed; ``logo`` is always 0..1000.
    bits : int, optional
        ADC resolution. ``book``/``full``: 1..24, default 12. ``s7``: value bits without
        the sign, 8..15, default 15 (steps of one count). ``logo``: informative, default 10.
    bipolar : bool
        Whether the signal range is symmetric about zero (matters for ``s7`` only).

    Raises
    ------
    PlcError
        PLC9102 for an unknown convention, PLC9103 for bits out of range.

    Examples
    --------
    >>> count_format("full", bits=10).full
    1023
    >>> count_format("s7", bipolar=True).zero
    -27648
    """
    if isinstance(convention, CountFormat):
        return convention
    name = str(convention).strip().lower()
    if name not in CONVENTIONS:
        raise PlcError(
            "PLC9102",
            f"unknown count convention {convention!r}; use one of {', '.join(CONVENTIONS)}",
        )
    n = _DEFAULT_BITS[name] if bits is None else bits
    if isinstance(n, bool) or not isinstance(n, int):
        raise PlcError("PLC9103", f"ADC bits must be a whole number, not {bits!r}")
    if name in ("book", "full"):
        if not 1 <= n <= 24:
            raise PlcError("PLC9103", f"ADC bits must be 1..24 for '{name}', not {n}")
        top = 2**n
        return CountFormat(name, n, bipolar, 0, top if name == "book" else top - 1, 1, 0, top - 1)
    if name == "s7":
        if not 8 <= n <= 15:
            raise PlcError(
                "PLC9103",
                f"S7 resolution must be 8..15 value bits (sign not counted), not {n}",
            )
        step = 2 ** (15 - n)
        if bipolar:
            lo_code, zero = -32512, -S7_NOMINAL
        else:
            lo_code, zero = S7_UNDERRANGE, 0
        return CountFormat(
            "s7", n, bipolar, zero, S7_NOMINAL, step, lo_code, S7_OVERRANGE,
            S7_UNDERFLOW, S7_OVERFLOW, S7_OVERFLOW,
        )  # fmt: skip
    if not 1 <= n <= 24:
        raise PlcError("PLC9103", f"ADC bits must be 1..24, not {n}")
    return CountFormat("logo", n, bipolar, 0, 1000, 1, 0, 1000)


def quantise_counts(counts: float, fmt: CountFormat) -> tuple[int, int]:
    """Real-valued counts -> (code, flag); flag -1 underflow, 0 in range, +1 overflow."""
    if math.isnan(counts):
        raise ValueError("cannot convert NaN to counts")
    if counts > fmt.max_code + fmt.step:
        q = fmt.max_code + 1
    elif counts < fmt.min_code - fmt.step:
        q = fmt.min_code - 1
    else:
        q = fmt.step * math.floor(counts / fmt.step + 0.5)
    if q > fmt.max_code:
        return (fmt.max_code if fmt.overflow_code is None else fmt.overflow_code), 1
    if q < fmt.min_code:
        return (fmt.min_code if fmt.underflow_code is None else fmt.underflow_code), -1
    return q, 0


def _fraction_to_counts(fraction: float, fmt: CountFormat) -> float:
    return fmt.zero + fraction * fmt.nominal_counts


def _counts_to_fraction(counts: float, fmt: CountFormat) -> float:
    return (counts - fmt.zero) / fmt.nominal_counts


# --------------------------------------------------------------------------- conversions


def eng_to_counts(
    value: float,
    lo: float,
    hi: float,
    *,
    convention: str | CountFormat = "book",
    bits: int | None = None,
    bipolar: bool = False,
    limit: bool = False,
) -> int:
    """Engineering value -> counts (the inverse of :func:`counts_to_eng`), quantised.

    Parameters
    ----------
    value : float
        Engineering value.
    lo, hi : float
        Engineering values at the lower and upper end of the signal range.
    convention, bits, bipolar
        See :func:`count_format`.
    limit : bool
        Clamp to the nominal range first (what AO_SCALE / UNSCALE does) instead of
        using the convention's over-range and overflow codes.

    Examples
    --------
    >>> eng_to_counts(80.0, 0.0, 160.0, convention="s7")
    13824
    >>> eng_to_counts(10.0, -20.0, 220.0, convention="book", bits=12)
    512
    >>> eng_to_counts(200.0, 0.0, 160.0, convention="s7"), eng_to_counts(
    ...     200.0, 0.0, 160.0, convention="s7", limit=True)
    (32767, 27648)
    """
    if hi == lo:
        raise PlcError("PLC9104", f"engineering range is empty (lo = hi = {lo}); give lo != hi")
    fmt = count_format(convention, bits, bipolar)
    fraction = (value - lo) / (hi - lo)
    if limit:
        fraction = min(1.0, max(0.0, fraction))
        code = fmt.step * math.floor(_fraction_to_counts(fraction, fmt) / fmt.step + 0.5)
        return max(fmt.min_code, min(fmt.max_code, code))
    return quantise_counts(_fraction_to_counts(fraction, fmt), fmt)[0]


def counts_to_eng(
    counts: float,
    lo: float,
    hi: float,
    *,
    convention: str | CountFormat = "book",
    bits: int | None = None,
    bipolar: bool = False,
) -> float:
    """Counts -> engineering value: ``y = lo + (N - zero) * (hi - lo) / (full - zero)``.

    With ``zero = 0`` this is the textbook's ``y = ymin + N (ymax - ymin) / Nmax``. The
    result is linear also outside the nominal range (S7 over-range reads above ``hi``);
    check :func:`counts_status` for the special codes.

    Examples
    --------
    >>> counts_to_eng(2048, 0.0, 100.0, convention="book", bits=12)
    50.0
    >>> counts_to_eng(1000, 0.0, 50.0, convention="logo")
    50.0
    >>> counts_to_eng(-27648, -1.0, 1.0, convention="s7", bipolar=True)
    -1.0
    """
    fmt = count_format(convention, bits, bipolar)
    return lo + _counts_to_fraction(counts, fmt) * (hi - lo)


def eng_to_signal(value: float, lo: float, hi: float, signal: str | SignalRange) -> float:
    """Engineering value -> electrical signal of an ideal linear transmitter (no limits).

    Examples
    --------
    >>> eng_to_signal(80.0, 0.0, 160.0, "4-20mA")
    12.0
    """
    if hi == lo:
        raise PlcError("PLC9104", f"engineering range is empty (lo = hi = {lo}); give lo != hi")
    return signal_range(signal).from_fraction((value - lo) / (hi - lo))


def signal_to_eng(value: float, lo: float, hi: float, signal: str | SignalRange) -> float:
    """Electrical signal -> engineering value (linear, no limits).

    Examples
    --------
    >>> signal_to_eng(4.0, -50.0, 150.0, "4-20mA")
    -50.0
    """
    return lo + signal_range(signal).to_fraction(value) * (hi - lo)


def signal_code(
    value: float, rng: SignalRange, fmt: CountFormat, wire_break_diagnostic: bool
) -> tuple[int, int]:
    code, flag = quantise_counts(_fraction_to_counts(rng.to_fraction(value), fmt), fmt)
    if flag < 0 and rng.live_zero and wire_break_diagnostic and fmt.wire_break_code is not None:
        code = fmt.wire_break_code
    return code, flag


def signal_to_counts(
    value: float,
    signal: str | SignalRange = "4-20mA",
    *,
    convention: str | CountFormat = "s7",
    bits: int | None = None,
    wire_break_diagnostic: bool = True,
) -> int:
    """Electrical signal -> the code the ADC reports (quantised, clipped, special codes).

    Parameters
    ----------
    value : float
        Signal in the range's unit (mA or V).
    signal : str or SignalRange
        The input's measuring range.
    convention, bits
        See :func:`count_format`.
    wire_break_diagnostic : bool
        ``s7`` live-zero ranges: below the under-range (< 1.185 mA) report 32767, as an
        S7-1200 with the wire-break diagnostic does; otherwise report -32768 (underflow).

    Examples
    --------
    >>> signal_to_counts(20.0, "4-20mA", convention="s7")
    27648
    >>> signal_to_counts(22.0, "4-20mA", convention="s7")
    31104
    >>> signal_to_counts(4.0, "0-20mA", convention="s7")  # the book's 20 % offset: 5530
    5530
    >>> signal_to_counts(10.0, "0-10V", convention="book", bits=12)  # clipped to 2**12 - 1
    4095
    >>> signal_to_counts(0.0, "+-10V", convention="book", bits=14)
    8192
    """
    rng = signal_range(signal)
    fmt = count_format(convention, bits, rng.bipolar)
    return signal_code(value, rng, fmt, wire_break_diagnostic)[0]


def counts_to_signal(
    counts: float,
    signal: str | SignalRange = "4-20mA",
    *,
    convention: str | CountFormat = "s7",
    bits: int | None = None,
) -> float:
    """Counts -> electrical signal (linear; the DAC side, or decoding an input word).

    Examples
    --------
    >>> counts_to_signal(13824, "0-10V", convention="s7")
    5.0
    >>> round(counts_to_signal(-4864, "4-20mA", convention="s7"), 3)
    1.185
    """
    rng = signal_range(signal)
    fmt = count_format(convention, bits, rng.bipolar)
    return rng.from_fraction(_counts_to_fraction(counts, fmt))


def resolution(
    signal: str | SignalRange = "0-10V",
    bits: int | None = None,
    convention: str | CountFormat = "book",
) -> float:
    """Smallest signal change one code step represents, in the signal's unit.

    ``book``: span / 2**n, the textbook's definition.

    Examples
    --------
    >>> round(resolution("0-10V", 12) * 1000, 2)   # mV
    2.44
    >>> round(resolution("+-10V", 14) * 1000, 2)   # mV
    1.22
    >>> round(resolution("4-20mA", convention="s7") * 1000, 3)  # uA
    0.579
    """
    rng = signal_range(signal)
    fmt = count_format(convention, bits, rng.bipolar)
    return rng.span * fmt.step / fmt.nominal_counts


def eng_resolution(
    lo: float,
    hi: float,
    *,
    convention: str | CountFormat = "book",
    bits: int | None = None,
    bipolar: bool = False,
) -> float:
    """One code step in engineering units (always positive).

    Examples
    --------
    >>> eng_resolution(-20.0, 220.0, convention="book", bits=12)
    0.05859375
    """
    fmt = count_format(convention, bits, bipolar)
    return abs(hi - lo) * fmt.step / fmt.nominal_counts


# --------------------------------------------------------------------------- status


@dataclass(frozen=True, slots=True)
class Status:
    """Diagnostic bits of an analog channel.

    Attributes
    ----------
    wire_break : bool
        Live-zero signal at or below the NE43 failure level (<= 3.6 mA, <= 0.9 V): broken
        wire or failed transmitter. Never set on 0-based ranges, where a broken wire just
        reads as the range minimum.
    short_circuit : bool
        Live-zero signal at or above the NE43 high failure level (>= 21 mA, >= 5.25 V).
    underrange, overrange : bool
        Signal below ``lo`` / above ``hi`` of the range (still measured).
    underflow, overflow : bool
        Beyond what the ADC can represent: the code is clipped or a special code.

    Examples
    --------
    >>> Status().ok
    True
    >>> Status(wire_break=True, underrange=True).flags()
    ('wire_break', 'underrange')
    """

    wire_break: bool = False
    short_circuit: bool = False
    underrange: bool = False
    overrange: bool = False
    underflow: bool = False
    overflow: bool = False

    @property
    def ok(self) -> bool:
        """True when no bit is set."""
        return not self.flags()

    def flags(self) -> tuple[str, ...]:
        """Names of the bits that are set."""
        return tuple(name for name in self.__slots__ if getattr(self, name))


def signal_status(
    value: float,
    signal: str | SignalRange = "4-20mA",
    *,
    convention: str | CountFormat | None = None,
    bits: int | None = None,
) -> Status:
    """Diagnose an electrical signal (what a module's diagnostics know).

    ``underflow`` / ``overflow`` are only computed when a ``convention`` is given.

    Examples
    --------
    >>> signal_status(3.0, "4-20mA").flags()
    ('wire_break', 'underrange')
    >>> signal_status(3.7, "4-20mA").flags()
    ('underrange',)
    >>> signal_status(25.0, "4-20mA", convention="s7").flags()
    ('short_circuit', 'overrange', 'overflow')
    >>> signal_status(0.0, "0-10V").ok   # a broken 0-10 V wire reads as the minimum
    True
    """
    rng = signal_range(signal)
    flag = 0
    if convention is not None:
        fmt = count_format(convention, bits, rng.bipolar)
        flag = signal_code(value, rng, fmt, True)[1]
    return Status(
        wire_break=rng.wire_break_at is not None and value <= rng.wire_break_at,
        short_circuit=rng.fault_high_at is not None and value >= rng.fault_high_at,
        underrange=value < rng.lo,
        overrange=value > rng.hi,
        underflow=flag < 0,
        overflow=flag > 0,
    )


def counts_status(
    counts: int,
    *,
    convention: str | CountFormat = "s7",
    bits: int | None = None,
    bipolar: bool = False,
    live_zero: bool = False,
) -> Status:
    """Diagnose a code as the PLC program sees it (counts only, no signal).

    Only conventions with special codes (``s7``) can tell a fault from a reading at the
    end of the range: a clipping ADC reads a broken wire as its minimum code. On an S7
    live-zero channel 32767 means overflow *or* wire break; both bits are set, and the
    module's diagnostics (:attr:`plclab.io.AnalogInput.status`) tell which.

    Examples
    --------
    >>> counts_status(30000).flags()
    ('overrange',)
    >>> counts_status(32767, live_zero=True).flags()
    ('wire_break', 'overflow')
    >>> counts_status(-32768).flags()
    ('underflow',)
    >>> counts_status(0, convention="book").ok
    True
    """
    fmt = count_format(convention, bits, bipolar)
    overflow = fmt.overflow_code is not None and counts == fmt.overflow_code
    underflow = fmt.underflow_code is not None and counts == fmt.underflow_code
    special = overflow or underflow
    return Status(
        wire_break=live_zero and fmt.wire_break_code is not None and counts == fmt.wire_break_code,
        underrange=not special and fmt.min_code <= counts < fmt.zero,
        overrange=not special and fmt.full < counts <= fmt.max_code,
        underflow=underflow,
        overflow=overflow,
    )
