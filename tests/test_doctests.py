"""The runnable examples in the docstrings stay true: every module of plclab and plants that has
an example (``>>>``) is found and run, so no list is kept by hand."""

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# the optional extras a module may need; a module that needs a missing one is skipped
OPTIONAL = {"rerun", "pymodbus", "pymunk", "control", "filterpy", "matplotlib"}


def modules_with_examples() -> list[str]:
    out = []
    for pkg in ("plclab", "plants"):
        for path in sorted((ROOT / pkg).rglob("*.py")):
            if ">>> " not in path.read_text(encoding="utf-8"):
                continue
            parts = path.relative_to(ROOT).with_suffix("").parts
            out.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return out


MODULES = modules_with_examples()


def test_examples_are_found() -> None:
    assert {"plclab.project", "plclab.lang.frontends.st", "plclab.suggest"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name: str) -> None:
    try:
        module = importlib.import_module(name)
    except ModuleNotFoundError as e:
        if (e.name or "").split(".")[0] in OPTIONAL:
            pytest.skip(f"{name} needs {e.name}")
        raise
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
    assert result.attempted > 0, f"{name} has no examples"
