"""Run the docstring examples of plclab.sim and plclab.trace."""

import doctest
import importlib

import pytest

MODULES = [
    "plclab.sim",
    "plclab.sim.durations",
    "plclab.sim.errors",
    "plclab.sim.wiring",
    "plclab.sim.wirings",
    "plclab.sim.runner",
    "plclab.sim.simulation",
    "plclab.trace.events",
    "plclab.trace.expr",
    "plclab.trace.trace",
]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name: str) -> None:
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
