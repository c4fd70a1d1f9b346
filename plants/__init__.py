"""Physics plants for the virtual PLC lab.

Each plant speaks engineering units through named signals (see :class:`plants.base.Plant`).
This package never imports ``plclab``; pymunk is imported only when a conveyor is built.

Examples
--------
>>> from plants import get_plant, list_plants
>>> "tank" in list_plants()
True
>>> tank = get_plant("tank", area=2.0)
>>> tank["PUMP"] = True
>>> tank.step(1.0)
>>> tank["FLOW_IN"] > 0
True
"""

from __future__ import annotations

import difflib
import inspect
from typing import Any

from .axes import Axes
from .base import Event, Plant, PlantError, Signal, StepProfile
from .conveyor import Conveyor
from .crossing import Crossing
from .heater import Heater
from .motor import Motor
from .press import Press
from .sump import Sump
from .tank import Tank
from .ventilation import Ventilation
from .washer import Washer

__all__ = [
    "PLANTS",
    "Axes",
    "Conveyor",
    "Crossing",
    "Event",
    "Heater",
    "Motor",
    "Plant",
    "PlantError",
    "Press",
    "Signal",
    "StepProfile",
    "Sump",
    "Tank",
    "Ventilation",
    "Washer",
    "get_plant",
    "list_plants",
    "signal_table",
]

PLANTS: dict[str, type[Plant]] = {
    cls.name: cls for cls in (
        Motor, Tank, Sump, Heater, Conveyor, Ventilation, Press, Washer, Axes, Crossing
    )
}


def list_plants() -> list[str]:
    """Registry keys of all plants, in teaching order."""
    return list(PLANTS)


def get_plant(name: str, **params: Any) -> Plant:
    """Build a plant by registry name.

    Parameters
    ----------
    name : str
        Registry key, e.g. ``"tank"`` (see :func:`list_plants`).
    **params
        Physical parameters of that plant (see its class docstring).

    Raises
    ------
    PlantError
        Unknown plant name or unknown parameter (with a "did you mean" hint).
    """
    cls = PLANTS.get(name)
    if cls is None:
        close = difflib.get_close_matches(str(name), PLANTS, n=3, cutoff=0.5)
        hint = (" Did you mean " + " or ".join(repr(c) for c in close) + "?") if close else ""
        raise PlantError(f"unknown plant {name!r}.{hint} Known plants: {', '.join(PLANTS)}")
    accepted = [
        p.name
        for p in inspect.signature(cls.__init__).parameters.values()
        if p.kind is inspect.Parameter.KEYWORD_ONLY
    ]
    for key in params:
        if key not in accepted:
            close = difflib.get_close_matches(key, accepted, n=3, cutoff=0.5)
            hint = (" Did you mean " + " or ".join(repr(c) for c in close) + "?") if close else ""
            raise PlantError(
                f"plant {name!r} has no parameter {key!r}.{hint} Parameters: {', '.join(accepted)}"
            )
    return cls(**params)


def signal_table(plant: Plant | str) -> str:
    """A Markdown table of a plant's signals (used for ``plants/README.md``)."""
    p = get_plant(plant) if isinstance(plant, str) else plant
    rows = ["| Signal | Kind | Type | Unit | Range | Description |", "|---|---|---|---|---|---|"]
    for s in p.signals.values():
        rng = "" if s.type == "bool" else f"{s.range[0]:g}..{s.range[1]:g}"
        rows.append(f"| `{s.name}` | {s.kind} | {s.type} | {s.unit} | {rng} | {s.description} |")
    return "\n".join(rows)
