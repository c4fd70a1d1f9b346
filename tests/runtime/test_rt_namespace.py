"""The namespace of generated code (plclab.runtime.rt.HELPERS) is joined from the helper modules
of the runtime, one module per concept: each module's private callables, each name once."""

from __future__ import annotations

import types

import pytest

from plclab.runtime import rt
from plclab.runtime.rt_faults import helpers_of


def test_every_helper_module_gives_its_private_callables_and_nothing_else() -> None:
    given = {}
    for module in rt.MODULES:
        mine = helpers_of(vars(module))
        assert mine, f"{module.__name__} gives generated code nothing: why is it in MODULES?"
        for name, obj in mine.items():
            assert rt.HELPERS[name] is obj, f"{module.__name__}.{name}"
        given.update(mine)
    # the rest are the few standard-library objects rt.py adds by name
    assert set(rt.HELPERS) - set(given) == {"_math", "_unpack_from", "_pack_into"}


def test_public_names_and_data_stay_out_of_generated_code() -> None:
    for name in ("Fault", "Budget", "format_value", "fmt_real", "string_literal", "RefAttr",
                 "out_of_bounds", "helpers_of", "_PUN", "_LEADING_NUMBER", "__name__"):
        assert name not in rt.HELPERS, name
    # the helpers the code generator emits most are there, as the same objects as in their module
    assert rt.HELPERS["_idiv"](-7, 2) == -3 and rt.HELPERS["_left"]("abc", 2) == "ab"
    assert rt.HELPERS["_oob"] is rt.rt_faults.out_of_bounds


def test_two_helpers_of_one_name_are_caught_and_one_object_twice_is_not() -> None:
    shared = object.__new__(type("Shared", (), {"__call__": lambda self: 0}))
    a = types.ModuleType("plclab.runtime.rt_a")
    b = types.ModuleType("plclab.runtime.rt_b")
    a._x, b._x = (lambda: 1), (lambda: 2)
    a._same = b._same = shared
    a.public, a._data, a.__dunder__ = (lambda: 3), {"k": 1}, (lambda: 4)
    assert set(rt.namespace((a,))) == {"_x", "_same"}
    with pytest.raises(ValueError, match="two runtime helpers are called _x.*plclab.runtime.rt_b"):
        rt.namespace((a, b))
    del b._x
    assert rt.namespace((a, b))["_same"] is shared
