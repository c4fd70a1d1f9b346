"""The runnable examples in the docstrings of the IL, LD and PLCopen front ends and the ladder
drawing stay true."""

import doctest
import importlib

import pytest

MODULES = ["plclab.lang.il_parser", "plclab.lang.ld_parser", "plclab.lang.plcopen",
           "plclab.viz.ladder_svg"]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    mod = importlib.import_module(name)
    result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
