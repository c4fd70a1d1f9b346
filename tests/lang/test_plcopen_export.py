"""PLCopen XML export: every example and lab solution exported (ST/IL bodies, and FBD networks
where the body allows), imported again, and run: the same trace as the original, scan by scan,
with the same pseudo-random inputs."""

import random
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.plcopen_export import NS, export_plcopen
from plclab.project import parse_sources

ROOT = Path(__file__).resolve().parents[2]
PROGRAMS = sorted(
    [p for p in (ROOT / "examples").iterdir() if p.suffix in (".st", ".il", ".ld", ".xml")]
    + [p for p in (ROOT / "labs").glob("*/solution/*") if p.suffix in (".st", ".il", ".ld")])


def exported(path: Path, fbd: bool) -> str:
    text = path.read_text(encoding="utf-8")
    files, diags = parse_sources([(text, path.name)])
    assert not [d for d in diags if d.severity == "error"]
    return export_plcopen(files[-1:], fbd=fbd, sources={path.name: text})


def trace(plc, names: list[str], scans: int = 60, seed: int = 7) -> list[tuple]:
    """Flip BOOL variables among ``names`` pseudo-randomly before each scan; every scalar of ``names`` after
    every scan."""
    rng = random.Random(seed)
    inputs = [n for n in names if isinstance(plc[n], bool)]  # outputs too: a harder test
    rows = []
    for _ in range(scans):
        for n in inputs:
            if rng.random() < 0.3:
                plc[n] = not plc[n]
        plc.scan()
        rows.append(tuple((n, plc[n]) for n in names
                          if isinstance(plc[n], bool | int | float | str)))
    return rows


@pytest.mark.parametrize("fbd", [False, True], ids=["text", "fbd"])
@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.name)
def test_round_trip_gives_the_same_trace(path, fbd):
    xml = exported(path, fbd)
    again = plclab.loads(xml, path.stem + "_export.xml")
    original = plclab.load(path)
    names = original.variables()  # the exported hidden variables are extra: not compared
    assert trace(again, names) == trace(original, names)


def test_fbd_export_draws_networks_with_blocks_and_negated_pins():
    xml = exported(ROOT / "labs/ventilation-fans/solution/ventilation.st", fbd=True)
    root = ET.fromstring(xml)
    body = root.find(f".//{{{NS}}}pou/{{{NS}}}body/{{{NS}}}FBD")
    assert body is not None
    types = {b.get("typeName") for b in body.iter(f"{{{NS}}}block")}
    assert {"AND", "OR", "ADD", "LT", "BOOL_TO_INT", "BLINKER"} <= types
    negated = [v.get("formalParameter") for v in body.iter(f"{{{NS}}}variable")
               if v.get("negated") == "true"]
    assert negated  # NOT FAULT2 -> a negated pin, not a NOT block
    orders = [int(e.get("executionOrderId")) for e in body if e.get("executionOrderId")]
    assert orders == sorted(orders) and len(set(orders)) == len(orders)


def test_st_body_with_if_else_stays_st_even_when_fbd_is_asked():
    files, _ = parse_sources([("PROGRAM P VAR a, b : BOOL; END_VAR\nIF a THEN b := TRUE; "
                               "ELSE b := a; END_IF\nEND_PROGRAM\n", "p.st")])
    xml = export_plcopen(files[-1:], fbd=True)
    assert "<ST>" in xml and "<FBD" not in xml


@pytest.mark.parametrize("name", ["examples/bottle.ld", "labs/ventilation-fans/solution/"
                                  "ventilation.ld", "examples/motor.xml"])
def test_ladder_is_exported_as_a_ladder(name):
    root = ET.fromstring(exported(ROOT / name, fbd=False))
    ld = root.find(f".//{{{NS}}}body/{{{NS}}}LD")
    assert ld is not None
    kinds = {_tag(el) for el in ld}
    assert {"leftPowerRail", "contact", "coil", "rightPowerRail"} <= kinds
    for block in ld.iter(f"{{{NS}}}block"):
        pins = [v.get("formalParameter") for v in block.iter(f"{{{NS}}}variable")]
        assert all(pins), block.get("typeName")  # every pin named (a text box's too)
    ids = [el.get("localId") for el in ld]
    assert len(ids) == len(set(ids))


def _tag(el) -> str:
    return el.tag.rsplit("}", 1)[-1]


def test_generated_names_become_legal_identifiers():
    files, _ = parse_sources([((ROOT / "examples/motor.ld").read_text(encoding="utf-8"),
                               "motor.ld")])
    xml = export_plcopen(files[-1:])
    assert "__" not in xml.replace("xmlns", "")


def test_sfc_body_is_refused_with_plc4042():
    files, _ = parse_sources([((ROOT / "examples/sfc_s0_s4.st").read_text(encoding="utf-8"),
                               "sfc.st")])
    sfc = [p for p in files[-1].pous if p.language == "SFC"]
    if not sfc:
        pytest.skip("the example has no SFC body")
    with pytest.raises(PlcError) as exc:
        export_plcopen(files[-1:])
    assert exc.value.code == "PLC4042"
