"""Platinum resistance thermometers (Pt100, PtX) and a 4-20 mA RTD transmitter.

The resistance follows the Callendar-Van Dusen equation of IEC 60751:

    R(T) = R0 (1 + A T + B T^2)                    for 0 <= T <= 850 degC
    R(T) = R0 (1 + A T + B T^2 + C (T - 100) T^3)  for -200 <= T < 0 degC

with A = 3.9083e-3 /degC, B = -5.775e-7 /degC^2 (the textbook's coefficients) and
C = -4.183e-12 /degC^4. R0 is 100 ohm for a Pt100, 1000 ohm for a Pt1000.

>>> resistance(0.0)
100.0
>>> round(resistance(100.0), 4)
138.5055
>>> round(temperature(138.5055), 6)
100.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from plclab.errors import PlcError
from plclab.io.scaling import SignalRange, signal_range

__all__ = ["A", "B", "C", "T_MAX", "T_MIN", "RtdTransmitter", "resistance", "temperature"]

A = 3.9083e-3
"""First-order coefficient, 1/degC."""
B = -5.775e-7
"""Second-order coefficient, 1/degC^2."""
C = -4.183e-12
"""Fourth-order coefficient below 0 degC, 1/degC^4."""
T_MIN = -200.0
"""Lowest temperature of the IEC 60751 range, degC."""
T_MAX = 850.0
"""Highest temperature of the IEC 60751 range, degC."""


def resistance(t: float, r0: float = 100.0) -> float:
    """Resistance of a platinum RTD at ``t`` degC (Callendar-Van Dusen).

    Parameters
    ----------
    t : float
        Temperature in degC. Values outside -200..850 degC are extrapolated.
    r0 : float
        Resistance at 0 degC: 100 for Pt100, 500 for Pt500, 1000 for Pt1000.

    Examples
    --------
    >>> round(resistance(-100.0), 4)
    60.2558
    >>> round(resistance(100.0, r0=1000.0), 3)
    1385.055
    """
    if t >= 0.0:
        return r0 * (1.0 + A * t + B * t * t)
    return r0 * (1.0 + A * t + B * t * t + C * (t - 100.0) * t**3)


def temperature(r: float, r0: float = 100.0) -> float:
    """Temperature in degC of a platinum RTD with resistance ``r`` (inverse of
    :func:`resistance`).

    At or above ``r0`` the quadratic is solved in closed form,
    ``T = 2 (R/R0 - 1) / (A + sqrt(A^2 + 4 B (R/R0 - 1)))`` (the cancellation-free form of
    ``(-A + sqrt(A^2 - 4 B (1 - R/R0))) / (2 B)``); below ``r0`` the C term is included
    by Newton's method starting from the quadratic's root.

    Raises
    ------
    ValueError
        For a resistance that is not positive or has no real solution (above ~761 R0).

    Examples
    --------
    >>> temperature(100.0)
    0.0
    >>> round(temperature(resistance(-150.0)), 9)
    -150.0
    """
    if not r > 0.0 or not math.isfinite(r):
        raise ValueError(f"RTD resistance must be positive and finite, not {r!r}")
    x = r / r0 - 1.0
    disc = A * A + 4.0 * B * x
    if disc < 0.0:
        raise ValueError(f"no temperature has resistance {r} ohm for R0 = {r0} ohm")
    t = 2.0 * x / (A + math.sqrt(disc))
    if t >= 0.0:
        return t
    for _ in range(50):
        f = resistance(t, r0) - r
        df = r0 * (A + 2.0 * B * t + C * (4.0 * t**3 - 300.0 * t * t))
        step = f / df
        t -= step
        if abs(step) < 1e-12:
            break
    return t


_FAULTS = ("open", "short")


@dataclass
class RtdTransmitter:
    """A head-mounted RTD transmitter: platinum sensor in, linear 4-20 mA (or other
    standard signal) out, with NE43 behaviour.

    The output is linear in temperature over ``t_lo .. t_hi`` and saturates at the
    range's limits (3.8 and 20.5 mA) outside it. A sensor fault (open: R -> infinity, or
    short: R -> 0, detected as a resistance outside the -200..850 degC range) drives the
    output to ``fault_signal`` (downscale burnout, default 3.5 mA: NE43 asks <= 3.6 mA).

    Parameters
    ----------
    t_lo, t_hi : float
        Temperatures at 0 % and 100 % of the output, degC.
    signal : str
        Output range, e.g. ``"4-20mA"``.
    r0 : float
        Sensor resistance at 0 degC (100 for Pt100).
    fault_signal : float, optional
        Output on a sensor fault. Default: 1/32 of the span below a live zero (3.5 mA,
        0.875 V), the range minimum otherwise. Give e.g. 21.5 for upscale burnout.
    wires : {2, 3, 4}
        Sensor connection. A 2-wire connection adds both leads' resistance to the
        sensor's (a hot reading); 3- and 4-wire connections compensate it.
    lead_ohm : float
        Resistance of one lead, ohm.

    Examples
    --------
    >>> tx = RtdTransmitter(-50.0, 150.0)
    >>> [round(tx.output(t), 9) for t in (-50.0, 50.0, 150.0)]
    [4.0, 12.0, 20.0]
    >>> tx.output(400.0)      # out of range: saturates (NE43)
    20.5
    >>> tx.inject("open"); tx.output(50.0)
    3.5
    >>> round(RtdTransmitter(0.0, 100.0, wires=2, lead_ohm=0.5).measured_temperature(0.0), 2)
    2.56
    """

    t_lo: float = -50.0
    t_hi: float = 150.0
    signal: str = "4-20mA"
    r0: float = 100.0
    fault_signal: float | None = None
    wires: int = 3
    lead_ohm: float = 0.0
    fault: str | None = field(default=None)

    def __post_init__(self) -> None:
        self._range: SignalRange = signal_range(self.signal)
        self.signal = self._range.name
        if not self.t_hi > self.t_lo:
            raise PlcError(
                "PLC9104",
                f"RTD transmitter range {self.t_lo}..{self.t_hi} degC is empty; give t_lo < t_hi",
            )
        if not self.r0 > 0.0:
            raise PlcError("PLC9104", f"R0 must be positive (100 for Pt100), not {self.r0}")
        if self.wires not in (2, 3, 4):
            raise PlcError("PLC9104", f"an RTD is connected with 2, 3 or 4 wires, not {self.wires}")
        if self.fault_signal is None:
            rng = self._range
            self.fault_signal = rng.lo - rng.span / 32.0 if rng.live_zero else rng.lo
        if self.fault is not None:
            self.inject(self.fault)

    def inject(self, fault: str) -> None:
        """Break the sensor: ``"open"`` (R infinite) or ``"short"`` (R = 0)."""
        if fault not in _FAULTS:
            raise PlcError(
                "PLC9106", f"unknown RTD fault {fault!r}; use one of {', '.join(_FAULTS)}"
            )
        self.fault = fault

    def clear(self) -> None:
        """Repair the sensor."""
        self.fault = None

    def measured_resistance(self, t: float) -> float:
        """Resistance the transmitter sees at sensor temperature ``t`` (leads included)."""
        if self.fault == "open":
            return math.inf
        leads = 2.0 * self.lead_ohm if self.wires == 2 else 0.0
        if self.fault == "short":
            return leads
        return resistance(t, self.r0) + leads

    def measured_temperature(self, t: float) -> float:
        """Temperature the transmitter computes (``nan`` on a sensor fault)."""
        r = self.measured_resistance(t)
        if not resistance(T_MIN, self.r0) <= r <= resistance(T_MAX, self.r0):
            return math.nan
        return temperature(r, self.r0)

    def output(self, t: float) -> float:
        """Output signal (mA or V) at sensor temperature ``t`` degC."""
        measured = self.measured_temperature(t)
        if math.isnan(measured):
            assert self.fault_signal is not None
            return self.fault_signal
        rng = self._range
        x = rng.from_fraction((measured - self.t_lo) / (self.t_hi - self.t_lo))
        return min(rng.sat_hi, max(rng.sat_lo, x))
