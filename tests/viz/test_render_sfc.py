"""SFC charts drawn as SVG (plclab/viz/render_sfc.py): the initial step's double frame, the
active steps, transitions with their conditions, action blocks with qualifiers, both kinds of
branches, jumps; the textual and the PLCopen XML washer draw alike."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.lang.frontends.st import parse
from plclab.project import check_sources
from plclab.viz.render_sfc import render_sfc_svg

ROOT = Path(__file__).parent.parent.parent
LAB = ROOT / "labs" / "washing-machine" / "solution"
SVG = "{http://www.w3.org/2000/svg}"
PARALLEL = """PROGRAM Par
VAR a, b, c, motor, lamp, buzz : BOOL; END_VAR
INITIAL_STEP Idle: END_STEP
STEP Fill: motor(N); END_STEP
STEP Heat: lamp(S); END_STEP
STEP Wait: lamp(R); buzz(L, T#30ms); END_STEP
STEP P1: END_STEP
STEP P1b: END_STEP
STEP P2: END_STEP
TRANSITION FROM Idle TO Fill := a; END_TRANSITION
TRANSITION FROM Idle TO Heat := b; END_TRANSITION
TRANSITION FROM Fill TO (P1, P2) := b; END_TRANSITION
TRANSITION FROM P1 TO P1b := c; END_TRANSITION
TRANSITION FROM (P1b, P2) TO Idle := a AND NOT b; END_TRANSITION
TRANSITION FROM Heat TO Wait := Heat.T >= T#20ms; END_TRANSITION
TRANSITION FROM Wait TO Idle := c; END_TRANSITION
END_PROGRAM
"""


def pou_of(text: str, name: str):
    project, diags = check_sources([(text, name)])
    assert project is not None, diags
    return next(p for p in project.pous.values() if p.sfc is not None)


def tree(svg: str) -> ET.Element:
    return ET.fromstring(svg)


def texts(root: ET.Element, cls: str | None = None) -> list[str]:
    return [t.text or "" for t in root.iter(f"{SVG}text")
            if cls is None or cls in (t.get("class") or "").split()]


def step_group(root: ET.Element, name: str) -> ET.Element:
    return next(g for g in root.iter(f"{SVG}g") if g.get("data-step") == name)


def test_steps_initial_double_frame_and_the_active_step():
    svg = tree(render_sfc_svg(pou_of(PARALLEL, "par.st"), values={"P2.X": True, "Par.P1b.X": 1}))
    assert texts(svg, "name")[:7] == ["Idle", "Fill", "Heat", "Wait", "P1", "P1b", "P2"]
    assert len(step_group(svg, "Idle").findall(f"{SVG}rect")) == 2, "double frame"
    assert len(step_group(svg, "Fill").findall(f"{SVG}rect")) == 1
    active = [g.get("data-step") for g in svg.iter(f"{SVG}g") if "active" in g.get("class")]
    assert active == ["P1b", "P2"], "names with or without the POU prefix"


def test_transitions_actions_and_both_kinds_of_branches():
    root = tree(render_sfc_svg(pou_of(PARALLEL, "par.st")))
    assert {"a", "b", "c", "a AND NOT b", "Heat.T >= T#20ms"} <= set(texts(root, "cond"))
    assert {"N", "S", "R", "L"} <= set(texts(root, "qual"))
    assert "buzz, T#30ms" in texts(root)
    wires = [(float(ln.get("x1")), float(ln.get("y1")), float(ln.get("x2")),
              float(ln.get("y2"))) for ln in root.iter(f"{SVG}line")
             if ln.get("class") == "wire"]
    flat = [w for w in wires if w[1] == w[3] and w[0] != w[2]]
    ys = sorted({w[1] for w in flat})
    doubles = [y for y in ys if y + 3 in ys]
    assert len(doubles) == 2, "a simultaneous divergence and convergence: double lines"
    bars = [ln for ln in root.iter(f"{SVG}line") if "bar" in ln.get("class")]
    assert len(bars) == 7
    assert texts(root, "name").count("Idle") == 3, "two jumps back to Idle"


def test_values_mark_the_enabled_transition_and_its_condition_value():
    root = tree(render_sfc_svg(pou_of(PARALLEL, "par.st"),
                               values={"P1b.X": True, "P2.X": True, "a": True, "b": False}))
    enabled = [t.text for t in root.iter(f"{SVG}text") if "enabled" in (t.get("class") or "")]
    assert enabled == ["a AND NOT b = TRUE"]
    assert "b = FALSE" in texts(root, "cond")


@pytest.mark.parametrize("name, full", [
    ("washer.st", ["LEVEL_SW AND COTTON", "LEVEL_SW AND SILK"]),
    ("washer.xml", ["FullCotton (IL)", "FullSilk (LD/FBD)"])])  # referenced transitions
def test_the_washer_draws_with_its_abort_priorities(name, full):
    path = LAB / name
    root = tree(render_sfc_svg(pou_of(path.read_text("utf-8"), path.name),
                               values={"Warming.X": True}))
    conds = " ".join(texts(root, "cond"))
    assert all(f in conds for f in full) and "Warming.T >= T#5m" in conds
    assert "[0] NOT STOP_PB OR" in conds, "a PRIORITY is shown before the condition"
    assert "TEMP_RAW <= 11059" in conds


def test_an_unlowered_chart_draws_too_and_a_body_without_chart_is_plc4050():
    f, _ = parse(PARALLEL, "par.st")
    assert render_sfc_svg(f.pous[0]).count("<g class=\"step") == 7
    plain, _ = parse("PROGRAM P VAR x : BOOL; END_VAR x := TRUE; END_PROGRAM", "p.st")
    with pytest.raises(PlcError) as e:
        render_sfc_svg(plain.pous[0])
    assert e.value.code == "PLC4050"


def test_names_and_conditions_are_escaped():
    text = PARALLEL.replace("a AND NOT b", "a AND (c OR b) AND NOT (b <> c)")
    svg = render_sfc_svg(pou_of(text, "par.st"))
    assert "&lt;&gt;" in svg and "<>" not in svg
    tree(svg)
