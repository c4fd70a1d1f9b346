"""The runnable examples in the core's docstrings stay true."""

import doctest
import importlib

import pytest

MODULES = ["plclab", "plclab.errors", "plclab.project", "plclab.lang.lexer",
           "plclab.lang.st_parser", "plclab.lang.types", "plclab.runtime.plc",
           "plclab.runtime.literals"]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    mod = importlib.import_module(name)
    result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
    assert result.attempted > 0, f"{name} has no examples"
