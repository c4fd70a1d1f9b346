"""Pictures show a located word as the student declared it: ``X AT %MW0 : INT`` holding -1 is
drawn as -1, not as the WORD 65535 the process image reads (issue 32)."""

from __future__ import annotations

import numpy as np
import pytest

import plclab
from plclab.grade.feedback import declared_types, timing_png
from plclab.trace import Trace
from plclab.trace.typed import declared_view

PROGRAM = """
PROGRAM Main
VAR
    NEG AT %MW0 : INT;
    RAW AT %MW2 : WORD;
    SMALL AT %MB5 : SINT;
    R AT %MD8 : REAL;
    LIM AT %MW12 : INT(-100..100);
    k : INT;
END_VAR
k := k + 1;
NEG := -k;
RAW := 16#FFFF;
SMALL := -3;
R := -1.5;
LIM := -7;
END_PROGRAM
"""
ADDRS = ["%MW0", "%MW2", "%MB5", "%MD8", "%MW12"]


def _run() -> tuple[object, Trace]:
    """The program's addresses read as the simulator's watch reads them (``plc.var``)."""
    plc = plclab.loads(PROGRAM)
    getters = {a: plc.var(a).get for a in ADDRS}
    rows = []
    for _ in range(3):
        plc.scan()
        rows.append([getters[a]() for a in ADDRS])
    cols = {a: np.array([r[i] for r in rows]) for i, a in enumerate(ADDRS)}
    return plc, Trace(np.arange(3) * 0.01, cols, {a: "int" for a in ADDRS})


def test_the_raw_trace_reads_words_unsigned():
    # the premise: without the view a negative INT is a large WORD
    _, tr = _run()
    assert tr.columns["%MW0"].tolist() == [65535, 65534, 65533]


def test_declared_types_come_from_the_program_and_the_io_table():
    plc, _ = _run()

    class Row:
        def __init__(self, address, type):
            self.address, self.type = address, type

    types = declared_types(plc, [Row("%MW0", "UINT"), Row("%MW40", "DINT")])
    assert types["%MW0"] == "INT"  # the program's declaration wins over the table
    assert types["%MW2"] == "WORD" and types["%MB5"] == "SINT" and types["%MD8"] == "REAL"
    assert types["%MW12"] == "INT"  # a subrange: its base type
    assert types["%MW40"] == "DINT"  # not in the program: the I/O table's type


def test_the_view_shows_each_address_as_its_declared_type():
    plc, tr = _run()
    view = declared_view(tr, declared_types(plc))
    assert view.columns["%MW0"].tolist() == [-1, -2, -3]
    assert view.columns["%MW2"].tolist() == [65535] * 3  # a WORD stays unsigned
    assert view.columns["%MB5"].tolist() == [-3] * 3
    assert view.columns["%MW12"].tolist() == [-7] * 3
    assert view.kinds["%MD8"] == "float" and view.columns["%MD8"].tolist() == [-1.5] * 3
    assert tr.columns["%MW0"].tolist() == [65535, 65534, 65533]  # grading's trace untouched


@pytest.mark.parametrize("types", [{}, {"%MW0": "WORD"}, {"%MW0": "DINT"}, {"%MW0": "BOOL"}])
def test_nothing_to_change_gives_the_same_trace(types):
    # no declaration, the unsigned type, a type of another size: the raw values stay
    _, tr = _run()
    assert declared_view(tr, types) is tr


def test_a_signed_read_of_an_unsigned_word_is_made_unsigned():
    # a wired %QW is read signed; a UINT there is shown 0..65535
    tr = Trace([0.0, 1.0], {"%QW2": np.array([-1, 5])}, {"%QW2": "int"})
    assert declared_view(tr, {"%QW2": "UINT"}).columns["%QW2"].tolist() == [65535, 5]


def _texts(svg) -> list[str]:
    import re

    return re.findall(r"<text[^>]*>([^<]*)</text>", svg.read_text(encoding="utf-8"))


def test_the_timing_diagram_writes_minus_one(tmp_path):
    """The failure diagram (SVG, read back): the value boxes say -1, -2 and -3; drawn from the
    raw trace they said 65535 and 253, which the same reading catches."""
    pytest.importorskip("matplotlib")
    plc, tr = _run()
    typed, raw = tmp_path / "typed.svg", tmp_path / "raw.svg"
    timing_png(declared_view(tr, declared_types(plc)), ["%MW0", "%MB5"], typed, 0.0, 0.02, [],
               "neg")
    timing_png(tr, ["%MW0", "%MB5"], raw, 0.0, 0.02, [], "neg")
    assert {"-1", "-2", "-3"} <= set(_texts(typed))
    assert not {"65535", "253"} & set(_texts(typed))
    assert {"65535", "253"} <= set(_texts(raw))
