"""Run the docstring examples of plclab.io."""

import doctest
import importlib

import pytest

MODULES = [
    "plclab.io",
    "plclab.io.scaling",
    "plclab.io.pt100",
    "plclab.io.analog",
    "plclab.io.digital",
]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name: str) -> None:
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
