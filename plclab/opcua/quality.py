"""The StatusCode of each tag: Good, or Bad with the reason OPC UA Part 8 gives (ADR 0055).

* the PLC is not in RUN (stopped, or stopped on a fault): every tag ``BadOutOfService``;
* an input module reports a wire break or a short circuit (a 4-20 mA loop below 3.6 mA or
  above 21 mA, NAMUR NE43): the tags located on that input, or the variable wired to it,
  ``BadSensorFailure`` (the value is not a measurement any more).
"""

from __future__ import annotations

from typing import Any

GOOD = "Good"
OUT_OF_SERVICE = "BadOutOfService"
SENSOR_FAILURE = "BadSensorFailure"


def input_channels(sim: Any) -> list[Any]:
    """The simulation's input channels that have an I/O module (none without a plant)."""
    transfer = getattr(sim, "transfer", None)
    if transfer is None:
        return []
    return [c for c in transfer.inputs if c.module is not None]


def channel_keys(ch: Any) -> list[str]:
    """Upper-case addresses/paths a channel's tags are found under."""
    keys = [ch.row.plc.strip().upper()]
    if ch.address:
        keys.append(ch.address.upper())
    return keys


def failed(ch: Any) -> bool:
    """Whether the channel's module reports a failed signal (wire break, short circuit)."""
    st = getattr(ch.module, "status", None)
    if st is None:
        return False
    return bool(getattr(st, "wire_break", False) or getattr(st, "short_circuit", False))


def bad_keys(sim: Any) -> set[str]:
    """Upper-case addresses and paths whose input reports a failure now."""
    out: set[str] = set()
    for ch in input_channels(sim):
        if failed(ch):
            out.update(channel_keys(ch))
    return out


def tag_status(tag: Any, running: bool, bad: set[str]) -> str:
    """The status code name of one tag."""
    if not running:
        return OUT_OF_SERVICE
    if bad and ((tag.address or "").upper() in bad or tag.path.upper() in bad):
        return SENSOR_FAILURE
    return GOOD
