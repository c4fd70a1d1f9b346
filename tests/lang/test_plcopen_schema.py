"""PLCopen XML export against the TC6 v2.01 schema (issue 21, ADR 0036): every example and lab
solution exported (text and FBD forms) validates against ``tests/schema/tc6_xml_v201.xsd``."""

from __future__ import annotations

import importlib.util
from functools import cache
from pathlib import Path

import pytest

xmlschema = pytest.importorskip("xmlschema")

ROOT = Path(__file__).resolve().parents[2]


def _export_tests():
    """The round-trip module's list of programs and its exporter (one list, not two)."""
    spec = importlib.util.spec_from_file_location(
        "plcopen_export_tests", ROOT / "tests" / "lang" / "test_plcopen_export.py")
    module = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    spec.loader.exec_module(module)
    return module


_EXPORT = _export_tests()
PROGRAMS, exported = _EXPORT.PROGRAMS, _EXPORT.exported
XSD = ROOT / "tests" / "schema" / "tc6_xml_v201.xsd"


@cache
def schema():
    return xmlschema.XMLSchema(str(XSD))


def problems(xml: str | Path) -> list[str]:
    source = str(xml)
    return [f"{e.path}: {e.reason}" for e in schema().iter_errors(source)][:5]


@pytest.mark.parametrize("fbd", [False, True], ids=["text", "fbd"])
@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.name)
def test_export_validates_against_the_tc6_schema(path: Path, fbd: bool):
    assert problems(exported(path, fbd)) == []


def test_a_transition_point_has_no_formal_parameter():
    """The schema gives ``formalParameter`` to the ``connectionPointOut`` of a step and of the
    divergences only; the SFC export wrote it on transitions and convergences too."""
    xml = exported(ROOT / "labs/washing-machine/solution/washer.st", fbd=False)
    assert problems(xml) == []
    assert "<transition" in xml


@pytest.mark.parametrize("args", [["examples/sfc_s0_s4.st"], ["examples/motor.ld", "--fbd"],
                                  ["examples/tank.il"], ["labs/washing-machine/solution/washer.st"]],
                         ids=lambda a: " ".join(Path(x).name for x in a))
def test_the_export_command_writes_schema_valid_files(tmp_path, args):
    """``plclab export FILE --to plcopen [--fbd] -o OUT``, the command itself."""
    from plclab.cli import main

    out = tmp_path / "out.xml"
    argv = ["export", str(ROOT / args[0]), "--to", "plcopen", *args[1:], "-o", str(out)]
    assert main(argv) == 0
    assert problems(out) == []
