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
