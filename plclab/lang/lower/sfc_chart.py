"""The SFC chart model: steps, their action associations, transitions, actions, the chart.

The front ends build it (:mod:`plclab.lang.frontends.sfc_text`, ``plcopen_sfc``); lowering checks
it (:mod:`.sfc_checks`) and turns it into core statements (:mod:`.sfc`); the outline and the
PLCopen export read it. It depends on nothing of the lowering but the IL instruction type.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ...errors import Location
from .. import ast as A
from .il import Instr

__all__ = ["Action", "Assoc", "Chart", "Step", "Transition"]


@dataclass(eq=False)
class Assoc:
    """``A1(L, T#2s)`` inside a step: action, qualifier (upper-case, as written) and time."""

    loc: Location
    action: str
    text: str
    qualifier: str = "N"
    time: A.Expr | None = None


@dataclass(eq=False)
class Step:
    loc: Location
    name: str
    text: str
    initial: bool = False
    assocs: list[Assoc] = field(default_factory=list)


@dataclass(eq=False)
class Transition:
    """``TRANSITION [name] [(PRIORITY := n)] FROM s TO s`` with its condition: an expression
    (``:= cond;``), IL lines (``: LD x ...``) or ST statements assigning the transition name."""

    loc: Location
    name: str | None
    sources: list[tuple[str, Location]]
    targets: list[tuple[str, Location]]
    priority: int | None = None
    spelling: dict[str, str] = field(default_factory=dict)  # step name -> as written
    text: str = ""  # the name as written
    cond: A.Expr | None = None
    body: list[A.Stmt] | None = None
    il: list[Instr] | None = None
    pending: list[A.PendingBody] = field(default_factory=list)  # LD/FBD (PLCopen XML)


@dataclass(eq=False)
class Action:
    """``ACTION name: ... END_ACTION`` with an ST body or IL lines."""

    loc: Location
    name: str
    text: str
    body: list[A.Stmt] = field(default_factory=list)
    il: list[Instr] | None = None
    pending: list[A.PendingBody] = field(default_factory=list)  # LD/FBD/IL (PLCopen XML)


@dataclass(eq=False)
class Chart:
    loc: Location
    steps: list[Step] = field(default_factory=list)
    transitions: list[Transition] = field(default_factory=list)
    actions: list[Action] = field(default_factory=list)
