"""I/O modules: what stands between a plant and the PLC.

Layer ``io`` (``docs/adr/0013-layers-and-lazy-cli.md``): pure Python on the standard library,
below the PLC core, whose analog scaling blocks share :mod:`~plclab.io.scaling`'s math.

A plant speaks engineering units (bar, degC, metres, a contact that is closed or
open); a PLC sees bits and ADC counts in its process image. The modules here turn one
into the other, with the imperfections a real installation has::

    plant ──value──► transmitter ──mA/V──► AnalogInput ──counts──► %IW ─┐
    plant ──contact─► bounce ──raw──► DigitalInput (filter) ──bit──► %I  ├─► PLC program
    plant ◄──value── actuator ◄──mA/V── AnalogOutput ◄──counts── %QW ◄──┤
    plant ◄──contact─ DigitalOutput (relay delay, wear) ◄──bit── %Q ◄───┘

* :mod:`~plclab.io.scaling`: pure functions between engineering units, signals
  (``"4-20mA"``, ``"0-10V"``...) and counts (``"book"``, ``"full"``, ``"s7"``,
  ``"logo"`` conventions), resolution and status bits (NAMUR NE43).
* :mod:`~plclab.io.analog`: :class:`AnalogInput` (noise, filter, sample & hold,
  quantisation, wire break / short / stuck) and :class:`AnalogOutput` (DAC).
* :mod:`~plclab.io.digital`: :class:`DigitalInput` (contact bounce, input filter) and
  :class:`DigitalOutput` (transistor or relay).
* :mod:`~plclab.io.pt100`: platinum RTDs and a 4-20 mA RTD transmitter.
* :mod:`~plclab.io.modules`: the specification of each kind of module a wiring row names
  (:data:`KINDS`: direction, signals, addresses, parameters, faults, builder; ADR 0068).

Every channel runs on virtual time: each call passes ``t`` (seconds, never decreasing)
and results depend only on the times and the seed.

>>> ai = AnalogInput(lo=0.0, hi=160.0, signal="4-20mA", convention="s7")
>>> ai.sample(0.0, 80.0), ai.eng
(13824, 80.0)

Configuration errors are :class:`plclab.errors.PlcError` with codes
PLC9101 unknown signal range, PLC9102 unknown count convention, PLC9103 ADC bits out of
range, PLC9104 empty or bad measuring range, PLC9105 negative time or count parameter,
PLC9106 unknown fault, PLC9107 unknown output kind, PLC9108 transmitter does not match
the input, PLC9109 time not finite or going backwards.
"""

from plclab.io.analog import AnalogInput, AnalogOutput, LinearTransmitter, Transmitter
from plclab.io.digital import IEC_TYPE1_24V, ChatterStats, DigitalInput, DigitalOutput
from plclab.io.modules import KINDS, ModuleKind
from plclab.io.pt100 import RtdTransmitter, resistance, temperature
from plclab.io.scaling import (
    CONVENTIONS,
    SIGNAL_RANGES,
    CountFormat,
    SignalRange,
    Status,
    count_format,
    counts_status,
    counts_to_eng,
    counts_to_signal,
    eng_resolution,
    eng_to_counts,
    eng_to_signal,
    resolution,
    signal_range,
    signal_status,
    signal_to_counts,
    signal_to_eng,
)

__all__ = [
    "CONVENTIONS",
    "IEC_TYPE1_24V",
    "KINDS",
    "SIGNAL_RANGES",
    "AnalogInput",
    "AnalogOutput",
    "ChatterStats",
    "CountFormat",
    "DigitalInput",
    "DigitalOutput",
    "LinearTransmitter",
    "ModuleKind",
    "RtdTransmitter",
    "SignalRange",
    "Status",
    "Transmitter",
    "count_format",
    "counts_status",
    "counts_to_eng",
    "counts_to_signal",
    "eng_resolution",
    "eng_to_counts",
    "eng_to_signal",
    "resolution",
    "resistance",
    "signal_range",
    "signal_status",
    "signal_to_counts",
    "signal_to_eng",
    "temperature",
]
