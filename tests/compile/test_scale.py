"""Programs that once made a stage grow much faster than the program (issue 30): an EXTENDS
chain, thousands of ACTIONs, a huge SFC chart. Each compiles, or stops with a documented code
(PLC0310, PLC0311) at the limit; the seconds are measured in benchmarks/size_bench.py."""

import importlib.util
from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.limits import MAX_EXTENDS_DEPTH, MAX_SFC_STEPS
from plclab.runtime.plc import Plc

_spec = importlib.util.spec_from_file_location(
    "size_bench", Path(__file__).resolve().parents[2] / "benchmarks" / "size_bench.py")
size_bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(size_bench)


def _codes(src: str) -> set[str]:
    with pytest.raises(PlcError) as e:
        plclab.compile_sources([(src, "big.st")])
    return {d.code for d in e.value.diagnostics} | {e.value.code}


def test_an_extends_chain_at_the_limit_compiles_and_beyond_is_plc0310():
    plc = Plc(plclab.compile_sources([(size_bench.extends_chain(MAX_EXTENDS_DEPTH), "e.st")]))
    plc.scan()
    assert plc[f"P.b.x{MAX_EXTENDS_DEPTH}"] == 1  # the derived body only (no SUPER^() call)
    assert "PLC0310" in _codes(size_bench.extends_chain(MAX_EXTENDS_DEPTH + 1))
    assert "PLC0310" in _codes(size_bench.extends_chain(1000))


def _diags(src: str) -> list:
    with pytest.raises(PlcError) as e:
        plclab.compile_sources([(src, "big.st")])
    return list(e.value.diagnostics) or [e.value]


def test_a_long_chain_is_reported_once_where_it_crosses_the_limit():
    """The chain is cut one block beyond the limit (a chain of 1,500 must not cost 1,500
    squared): one PLC0310, at the first block too deep, naming the limit."""
    deep = [d for d in _diags(size_bench.extends_chain(1500)) if d.code == "PLC0310"]
    assert len(deep) == 1
    assert f"B{MAX_EXTENDS_DEPTH + 1} " in deep[0].message
    assert f"more than {MAX_EXTENDS_DEPTH} levels" in deep[0].message


@pytest.mark.parametrize("n, code", [(10, "PLC0232"), (MAX_EXTENDS_DEPTH + 2, "PLC0232"),
                                     (MAX_EXTENDS_DEPTH + 3, "PLC0310"), (300, "PLC0310")])
def test_an_extends_ring_stops_with_a_code(n, code):
    """A ring of blocks inheriting from each other: a circle (PLC0232) while the whole ring
    fits under the limit, else the depth limit (the cut chain hides the circle); never a
    crash and never silence."""
    ring = "".join(f"FUNCTION_BLOCK B{i} EXTENDS B{(i + 1) % n}\nVAR x{i} : INT; END_VAR\n"
                   "END_FUNCTION_BLOCK\n" for i in range(n))
    assert code in _codes(ring + "PROGRAM P VAR b : B0; END_VAR b(); END_PROGRAM\n")


def test_four_thousand_actions_compile_and_run():
    plc = Plc(plclab.compile_sources([(size_bench.actions(4000), "a.st")]))
    plc.scan()
    assert plc["P.k"] == 4000


def test_a_chart_at_the_limit_compiles_and_beyond_is_plc0311():
    plc = Plc(plclab.compile_sources([(size_bench.sfc_steps(MAX_SFC_STEPS), "s.st")]))
    plc["P.go"] = True
    plc.scan(3)
    assert plc["P.S3.X"] is True
    assert "PLC0311" in _codes(size_bench.sfc_steps(MAX_SFC_STEPS + 1))
