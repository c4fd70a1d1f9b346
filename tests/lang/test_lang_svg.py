"""Ladder networks as SVG: from the text format and from PLCopen XML; well-formed, with the
variable names in it."""

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plclab.viz.ladder_svg import Svg, render, render_ld, render_xml

EXAMPLES = Path(__file__).parent.parent.parent / "examples"
SVG = "{http://www.w3.org/2000/svg}"


def texts(svg: str) -> list[str]:
    root = ET.fromstring(svg)
    assert root.tag == SVG + "svg"
    return [t.text for t in root.iter(SVG + "text")]


@pytest.mark.parametrize("name,names", [
    ("motor.ld", ["START", "STOP", "MOTOR"]),
    ("bottle.ld", ["X1", "X2", "REJECT", "T1.Q", "CYL"]),
    ("motor.xml", ["START", "STOP", "MOTOR"]),
    ("bottle.xml", ["X1", "X2", "T1", "TON", "T#300ms"]),
    ("tank_fbd.xml", ["LS1", "LS2", "M", "AND", "OR"]),
])
def test_examples_render_with_their_names(name, names):
    svg = render(EXAMPLES / name)
    assert isinstance(svg, Svg) and svg._repr_svg_() == svg
    got = texts(svg)
    for n in names:
        assert any(t and n in t for t in got), (n, got)


def test_text_ladder_elements_are_drawn():
    svg = render_ld("""PROGRAM P
VAR a, b, c, x, y : BOOL; t : TON; END_VAR
|   a       b              x   |
|---[P]--+--[/]------------( )-|
|   c    |                 y   |
|---[ ]--+--[TON t PT:=T#1s]-(S)|
END_PROGRAM
""")
    root = ET.fromstring(svg)
    assert len(root.findall(f".//{SVG}path")) >= 4  # two coils, two arcs each
    assert len(root.findall(f".//{SVG}rect")) >= 2  # background + the TON box
    got = texts(svg)
    assert {"a", "b", "c", "x", "y"} <= set(got) and "P" in got and "S" in got
    assert any("TON t" in t for t in got if t)


def test_special_characters_are_escaped():
    svg = render_ld("PROGRAM P VAR a, q : BOOL; END_VAR\n(* <&> *)\n|   a   q  |\n"
                    "|---[ ]--( )|\nEND_PROGRAM\n")
    ET.fromstring(svg)
    svg = render_xml((EXAMPLES / "motor.xml").read_text(encoding="utf-8"), pou="Motor")
    assert "seal-in" in svg


def test_only_the_chosen_pou_and_saving(tmp_path):
    text = (EXAMPLES / "bottle.ld").read_text(encoding="utf-8")
    assert "REJECT" not in render_ld(text, pou="Other")
    out = tmp_path / "b.svg"
    render_ld(text, pou="Bottle").save(out)
    ET.parse(out)
