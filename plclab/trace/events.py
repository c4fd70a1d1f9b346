"""Events of a run: ``(time, kind, source, message)`` plus optional numeric ``data``."""

from __future__ import annotations

from collections import namedtuple
from typing import Any

_EventBase = namedtuple("_EventBase", ["time", "kind", "source", "message"])


class Event(_EventBase):
    """Something that happened at a time: a plant event, a fault, an operator action...

    It is a 4-tuple ``(time, kind, source, message)`` (so ``t, kind, source, msg = ev``
    works) with one more attribute, ``data``: a dict of extra values (bottle ids, volumes,
    fault parameters) that is not part of the tuple.

    Kinds written by the simulation layer (plants add their own, see ``plant.events``):

    ``scenario``       an operator action or PLC write from the scenario (source: signal or variable)
    ``io_fault``       an I/O module fault injected / ``io_clear`` cleared (source: the PLC side)
    ``relay``          a relay output contact closed or opened (source: the PLC address)
    ``bounce``         a digital input contact bounced (source: the PLC address)
    ``plc_fault``      the PLC stopped on a run-time fault (source: ``plc``)
    ``until``          the run's stop condition became true (source: ``scenario``)
    ``sfc_step``       a chart's active steps changed: ``"Fill -> Boiling"`` (source: the
                       program; data ``left``, ``entered``; ADR 0023)

    >>> e = Event(1.5, "overflow", "tank", "the level reached the rim", {"volume": 2.0})
    >>> t, kind, source, message = e
    >>> kind, e.data["volume"]
    ('overflow', 2.0)
    """

    def __new__(cls, time: float, kind: str, source: str, message: str,
                data: dict[str, Any] | None = None) -> Event:
        self = super().__new__(cls, float(time), str(kind), str(source), str(message))
        self.data = dict(data) if data else {}
        return self

    def to_json(self) -> list[Any]:
        """``[time, kind, source, message, data]`` for JSON."""
        data = {k: v for k, v in self.data.items() if isinstance(v, int | float | str | bool)}
        return [self.time, self.kind, self.source, self.message, data]

    @classmethod
    def from_json(cls, item: list[Any]) -> Event:
        data = item[4] if len(item) > 4 else None
        return cls(item[0], item[1], item[2], item[3], data)

    def __str__(self) -> str:
        return f"{self.time:10.3f} s  {self.kind:<16} {self.source:<10} {self.message}"
