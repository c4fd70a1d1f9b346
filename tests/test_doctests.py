"""The runnable examples in the docstrings stay true (one runner for every package)."""

import doctest
import importlib

import pytest

MODULES = [
    # the core
    "plclab", "plclab.errors", "plclab.project", "plclab.lang.lexer", "plclab.lang.frontends.st",
    "plclab.lang.types", "plclab.runtime.plc", "plclab.runtime.literals", "plclab.durations",
    "plclab.suggest", "plclab.problems", "plclab.lang.unparse", "plclab.lang.dump",
    # IL, LD and PLCopen front ends, ladder drawing
    "plclab.lang.frontends.registry", "plclab.lang.frontends.il", "plclab.lang.frontends.ld",
    "plclab.lang.frontends.plcopen",
    "plclab.viz.ladder_svg",
    # I/O modules
    "plclab.io", "plclab.io.scaling", "plclab.io.pt100", "plclab.io.analog",
    "plclab.io.digital",
    # plants
    "plants", "plants.base", "plants.tank", "plants.heater",
    # simulation and trace
    "plclab.sim", "plclab.sim.durations", "plclab.sim.errors", "plclab.sim.wiring",
    "plclab.sim.wirings", "plclab.sim.runner", "plclab.sim.simulation", "plclab.trace.events",
    "plclab.trace.expr", "plclab.trace.trace",
    # visualisation
    "plclab.viz.series", "plclab.viz.chatter", "plclab.viz.figures",
]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name: str) -> None:
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
    assert result.attempted > 0, f"{name} has no examples"
