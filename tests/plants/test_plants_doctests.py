"""The examples in the plants' docstrings run."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = ["plants", "plants.base", "plants.tank", "plants.heater"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
