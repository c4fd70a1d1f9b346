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
ALL_PROGRAMS = sorted(
    [p for p in (ROOT / "examples").rglob("*") if p.suffix in (".st", ".il", ".ld", ".xml")]
    + [p for p in (ROOT / "labs").glob("*/solution/*") if p.suffix in (".st", ".il", ".ld")])


def object_oriented(path: Path) -> bool:
    """Uses METHOD/INTERFACE/EXTENDS/IMPLEMENTS, which TC6 v2.01 cannot express (PLC4043)."""
    files, _ = parse_sources([(path.read_text(encoding="utf-8"), path.name)])
    return any(p.kind == "INTERFACE" or p.methods or p.extends or p.implements
               for p in files[-1].pous)


OBJECT_ORIENTED = [p for p in ALL_PROGRAMS if object_oriented(p)]
PROGRAMS = [p for p in ALL_PROGRAMS if p not in OBJECT_ORIENTED]


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


# -- SFC charts ---------------------------------------------------------------------------
# every element the SFC export draws: a selection divergence and convergence (Branches), a
# simultaneous divergence and convergence, jump steps back, a priority, a rival declared before
# a transition leaving two steps (the branches then get one column each), named transitions in
# ST statements, ST ':=' and IL, an IL action, timed and stored qualifiers, and charts in FBs
EVERY_SFC = """\
FUNCTION_BLOCK Seq
VAR_INPUT go, a, b, c : BOOL; END_VAR
VAR_OUTPUT n, m : INT; lamp, busy : BOOL; END_VAR
INITIAL_STEP Idle: END_STEP
STEP Split: Count(N); lamp(L, T#30ms); END_STEP
STEP Left: Late(P); END_STEP
STEP Right: busy(S); END_STEP
STEP Join: Late(D, T#20ms); busy(R); END_STEP
TRANSITION FROM Idle TO Split := go; END_TRANSITION
TRANSITION Fork FROM Split TO (Left, Right)
    Fork := a AND NOT c;
END_TRANSITION
TRANSITION (PRIORITY := 1) FROM Split TO Idle := c; END_TRANSITION
TRANSITION FROM Right TO Idle := c AND b; END_TRANSITION
TRANSITION Both FROM (Left, Right) TO Join :
    LD b
    OR a
END_TRANSITION
TRANSITION Back FROM Join TO Idle := NOT go; END_TRANSITION
TRANSITION FROM Join TO Split := b AND go; END_TRANSITION
ACTION Count:
    LD n
    ADD 1
    ST n
END_ACTION
ACTION Late:
    m := m + 1;
    IF Back THEN m := m + 10; END_IF;
END_ACTION
END_FUNCTION_BLOCK

FUNCTION_BLOCK Branches
VAR_INPUT a, b, c : BOOL; END_VAR
VAR_OUTPUT k : INT; END_VAR
INITIAL_STEP Idle: END_STEP
STEP L: Tick(N); END_STEP
STEP R: Tick(N); END_STEP
STEP Done: END_STEP
TRANSITION FROM Idle TO L := a; END_TRANSITION
TRANSITION FROM Idle TO R := b; END_TRANSITION
TRANSITION FROM L TO Done := c; END_TRANSITION
TRANSITION FROM R TO Done := c OR a; END_TRANSITION
TRANSITION FROM Done TO Idle := NOT a; END_TRANSITION
ACTION Tick: k := k + 1; END_ACTION
END_FUNCTION_BLOCK

(* rivals on both sides of a transition leaving two steps: no column order keeps them all,
   every transition gets a column of its own *)
FUNCTION_BLOCK Crossed
VAR_INPUT a, b, c : BOOL; END_VAR
VAR_OUTPUT k : INT; END_VAR
INITIAL_STEP Idle: END_STEP
STEP S1: Tock(N); END_STEP
STEP S2: END_STEP
TRANSITION FROM Idle TO (S1, S2) := a OR b; END_TRANSITION
TRANSITION FROM S2 TO Idle := b; END_TRANSITION
TRANSITION FROM (S1, S2) TO Idle := a; END_TRANSITION
TRANSITION FROM S1 TO Idle := c; END_TRANSITION
ACTION Tock: k := k + 1; END_ACTION
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    go, a, b, c : BOOL;
    n, m, k : INT;
    lamp, busy : BOOL;
    s : Seq;
    br : Branches;
    cr : Crossed;
    kc : INT;
END_VAR
s(go := go, a := a, b := b, c := c);
n := s.n; m := s.m; lamp := s.lamp; busy := s.busy;
br(a := a, b := b, c := c);
k := br.k;
cr(a := a, b := b, c := c);
kc := cr.k;
END_PROGRAM
"""
STEP_FLAGS = [f"Main.s.{s}.X" for s in ("Idle", "Split", "Left", "Right", "Join")] + \
    [f"Main.br.{s}.X" for s in ("Idle", "L", "R", "Done")] + ["Main.s.Back"] + \
    [f"Main.cr.{s}.X" for s in ("Idle", "S1", "S2")]


def test_every_sfc_element_round_trips_with_the_same_steps_scan_by_scan():
    files, diags = parse_sources([(EVERY_SFC, "every.st")])
    assert not [d for d in diags if d.severity == "error"]
    xml = export_plcopen(files[-1:], sources={"every.st": EVERY_SFC})
    kinds = {_tag(el) for el in ET.fromstring(xml).iter()}
    assert {"selectionDivergence", "selectionConvergence", "simultaneousDivergence",
            "simultaneousConvergence", "jumpStep", "actionBlock", "actions",
            "transitions"} <= kinds
    again = plclab.loads(xml, "every_export.xml")
    original = plclab.loads(EVERY_SFC, "every.st")
    names = original.variables() + STEP_FLAGS
    for seed in range(4):
        assert trace(again, names, 120, seed) == trace(original, names, 120, seed)


def test_an_sfc_chart_drawn_in_ld_inside_a_plcopen_file_is_refused_with_plc4042():
    path = ROOT / "labs/washing-machine/solution/washer.xml"
    text = path.read_text(encoding="utf-8")
    files, _ = parse_sources([(text, path.name)])
    with pytest.raises(PlcError) as exc:
        export_plcopen(files[-1:], sources={path.name: text})
    assert exc.value.code == "PLC4042"
    assert "FullCotton" in str(exc.value) or "FullSilk" in str(exc.value)


# -- the washing-machine lab ----------------------------------------------------------------
WASHER = ROOT / "labs/washing-machine/solution/washer.st"


def _washer_xml() -> str:
    return exported(WASHER, fbd=False)


def _chart(files) -> tuple[list, dict]:
    """Steps (name, initial, associations) and, per step, the transitions leaving it in the
    order they are tried (sources, targets, priority, condition)."""
    from plclab.lang.lower.sfc import transition_order
    from plclab.lang.unparse import expr

    chart = next(p.sfc for f in files for p in f.pous if p.sfc is not None)
    steps = sorted((s.text, s.initial, [(a.text, a.qualifier) for a in s.assocs])
                   for s in chart.steps)
    leaving: dict[str, list] = {}
    for k in transition_order(chart):
        t = chart.transitions[k]
        row = (sorted(n for n, _ in t.sources), sorted(n for n, _ in t.targets), t.priority,
               expr(t.cond))
        for n, _ in t.sources:
            leaving.setdefault(n, []).append(row)
    return steps, leaving


def test_the_exported_washer_imports_with_the_same_chart():
    text = WASHER.read_text(encoding="utf-8")
    original, _ = parse_sources([(text, WASHER.name)])
    again, diags = parse_sources([(_washer_xml(), "washer_export.xml")])
    assert not [d for d in diags if d.severity == "error"]
    steps, leaving = _chart(original)
    assert len(steps) == 7 and len(leaving["FILL"]) == 3
    assert _chart(again) == (steps, leaving)
    root = ET.fromstring(_washer_xml())
    assert [s.get("name") for s in root.iter(f"{{{NS}}}step") if s.get("initialStep")] == \
        ["Start"]
    y = {s.get("name"): int(s.find(f"{{{NS}}}position").get("y"))
         for s in root.iter(f"{{{NS}}}step")}
    jumps = [(j.get("targetName"), int(j.find(f"{{{NS}}}position").get("y")))
             for j in root.iter(f"{{{NS}}}jumpStep")]
    assert {n for n, _ in jumps} == {"Abort", "Start"}  # Drain and Abort go back to Start
    assert all(y[n] < at for n, at in jumps)  # a jump step leads up the chart, never down


def test_the_exported_washer_runs_the_labs_scenarios_like_the_textual_one():
    import numpy as np

    from plclab.grade.engine import _simulate
    from plclab.grade.lab import load_lab
    from plclab.project import compile_sources

    lab = load_lab(ROOT / "labs/washing-machine")
    text_form = compile_sources([(WASHER.read_text(encoding="utf-8"), WASHER.name)])
    xml_form = compile_sources([(_washer_xml(), "washer_export.xml")])
    assert len(lab.scenarios) >= 3
    for sc in lab.scenarios:
        a, b = _simulate(lab, text_form, sc), _simulate(lab, xml_form, sc)
        assert list(a.columns) == list(b.columns)
        assert any(c.endswith(".X") for c in a.columns)  # the steps are in the trace
        for c in a.columns:
            assert np.array_equal(a[c], b[c]), (sc.name, c)


def test_a_plcopen_chart_in_st_exports_again_with_legal_names():
    """A transition referenced twice in the source XML: its copy has a generated name, which
    the export makes a legal identifier; the chart runs the same after export."""
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from test_plcopen_sfc import TRANSITIONS, jump, project, step, trans

    xml = project("\n".join([
        step(1, "Idle", initial=True), trans(2, 1, '<reference name="Stmts"/>'),
        step(3, "Mid", 2), trans(4, 3, '<reference name="Stmts"/>'), step(5, "End", 4),
        trans(6, 5, '<inline name=""><ST><xhtml:p><![CDATA[NOT a]]></xhtml:p></ST></inline>'),
        jump(7, 6, "Idle")]), TRANSITIONS)
    files, _ = parse_sources([(xml, "chart.xml")])
    out = export_plcopen(files[-1:], sources={"chart.xml": xml})
    assert "__" not in out.replace("xmlns", "")
    original, again = plclab.loads(xml, "chart.xml"), plclab.loads(out, "chart_export.xml")
    names = original.variables() + [f"Main.{s}.X" for s in ("Idle", "Mid", "End")]
    assert trace(again, names, 80, 3) == trace(original, names, 80, 3)


@pytest.mark.parametrize("path", OBJECT_ORIENTED, ids=lambda p: p.name)
def test_an_object_oriented_program_is_refused_clearly(path):
    with pytest.raises(PlcError) as e:
        exported(path, fbd=False)
    assert e.value.code == "PLC4043" and "object-oriented" in str(e.value)


def test_variadic_pins_are_numbered_on_from_the_blocks_own():
    # MUX K, IN0, IN1 goes on with IN2, IN3 (it used to jump to IN4, IN5); ADD with IN3, IN4
    from plclab.lang.frontends.st import parse_st
    from plclab.lang.plcopen_elements import call_pins

    f = parse_st("PROGRAM P VAR x, a, b, c, d : INT; END_VAR x := MUX(1, a, b, c, d); "
                 "x := ADD(a, b, c, d); END_PROGRAM")
    mux, add = (s.value for s in f.pous[0].body)
    assert call_pins(mux, {}) == ["K", "IN0", "IN1", "IN2", "IN3"]
    assert call_pins(add, {}) == ["IN1", "IN2", "IN3", "IN4"]
