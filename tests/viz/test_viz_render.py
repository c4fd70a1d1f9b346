"""plclab render: LD and FBD networks drawn from the elements of either front end (text LD and
PLCopen XML), boxes with pins on both sides, the right rail aligned, power flow from values;
ST and IL listings; the command line with SVG, PNG, a trace's values, and plclab export."""

import re
from pathlib import Path

import pytest

from plclab.cli import main
from plclab.errors import PlcError
from plclab.viz.network_layout import NetworkLayout as _Layout
from plclab.viz.render_listing import render_listing
from plclab.viz.render_network import network_pous, parse_source, render_source

ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"


def source(name: str) -> tuple[str, str]:
    return (EX / name).read_text(encoding="utf-8"), name


def texts(svg: str) -> list[str]:
    return re.findall(r">([^<>]+)</text>", svg)


@pytest.mark.parametrize("name", ["motor.ld", "motor.xml"])
def test_motor_is_drawn_the_same_from_text_and_xml(name):
    svg = render_source(*source(name))
    words = texts(svg)
    for w in ("START", "STOP", "MOTOR"):
        assert w in words
    assert "/" in words  # the normally closed STOP contact


def test_text_ladder_box_has_pins_on_both_sides():
    svg = render_source(*source("bottle.ld"))
    words = texts(svg)
    assert {"TON", "IN", "PT", "Q"} <= set(words)
    assert "<rect" in svg


def test_the_rung_enters_a_text_box_at_its_first_pin():
    [(_, elems)] = network_pous(*source("bottle.ld"))
    lay = _Layout(elems, None)
    lay.columns()
    lay.rows()
    box = next(e for e in elems if e.kind == "fb")
    feeder = next(i for i, _ in box.inputs[""] if i >= 0)
    assert lay.in_pins(box)[:2] == ["IN", "PT"]
    assert lay.row[feeder] == lay.row[box.id] + lay.pin_off[box.id]["IN"]


def test_coils_share_the_last_column_so_the_right_rail_is_straight():
    for name in ("bottle.ld", "bottle.xml"):
        [(_, elems)] = network_pous(*source(name))
        lay = _Layout(elems, None)
        last = lay.columns()
        assert {lay.col[e.id] for e in elems if e.kind == "coil"} == {last}


def test_power_flow_is_green_only_where_power_flows():
    off = render_source(*source("motor.ld"), values={"START": False, "STOP": True,
                                                     "MOTOR": False})
    on = render_source(*source("motor.ld"), values={"START": True, "STOP": False,
                                                    "MOTOR": True})
    assert "MOTOR = TRUE" in texts(on) and "START = FALSE" in texts(off)
    assert on.count("#1a7f37") > off.count("#1a7f37")


def test_fbd_blocks_show_values_and_negated_pins():
    svg = render_source(*source("tank_fbd.xml"), values={"LS1": False, "LS2": False, "M": True})
    words = texts(svg)
    assert {"NOT", "OR", "AND", "IN1", "IN2", "OUT"} <= set(words)
    assert "M = TRUE" in words


def test_listing_highlights_keywords_and_comments():
    text, name = source("tank.il")
    svg = render_listing(text, name, {"M": True}, 1, 15)
    assert "font-weight='bold'>LDN<" in svg and "fill='#2e7d32'" in svg
    assert "M = TRUE" in svg


def test_render_command_writes_svg_png_and_stdout(tmp_path, capsys):
    out = tmp_path / "m.svg"
    assert main(["render", str(EX / "motor.xml"), "-o", str(out)]) == 0
    assert out.read_text().startswith("<svg")
    assert main(["render", str(EX / "tank_level.st")]) == 0
    assert capsys.readouterr().out.startswith("<svg")
    assert main(["render", str(EX / "tank.il"), "--png"]) == 1
    assert "PLC4044" in capsys.readouterr().err


def test_an_st_body_of_an_xml_project_is_listed_without_the_xml(capsys):
    assert main(["render", str(EX / "project.xml"), "--pou", "Clamp"]) == 0
    svg = capsys.readouterr().out
    assert "Clamp (ST)" in svg and "&lt;pou" not in svg and "pouType" not in svg


def test_render_command_writes_png(tmp_path):
    try:
        import cairosvg  # noqa: F401
    except (ImportError, OSError):
        pytest.skip("PNG output needs cairosvg and the cairo library")
    png = tmp_path / "t.png"
    assert main(["render", str(EX / "tank.il"), "--png", "-o", str(png)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_render_shows_the_values_of_a_trace_at_a_time(tmp_path, capsys):
    from plclab.trace.trace import Trace

    tr = Trace([0.0, 1.0, 2.0], {"Motor.START": [False, True, False],
                                 "Motor.MOTOR": [False, True, True]})
    path = tmp_path / "run.json"
    tr.save(path)
    assert main(["render", str(EX / "motor.ld"), "--at", str(path), "--time", "1.5"]) == 0
    svg = capsys.readouterr().out
    assert "START = TRUE" in svg and "MOTOR = TRUE" in svg
    assert main(["render", str(EX / "motor.ld"), "--at", str(path)]) == 1
    assert "PLC4045" in capsys.readouterr().err


def test_unknown_pou_is_plc4040(capsys):
    assert main(["render", str(EX / "motor.ld"), "--pou", "Nope"]) == 1
    assert "PLC4040" in capsys.readouterr().err


def test_sfc_body_goes_to_the_sfc_renderer(capsys):
    code = main(["render", str(EX / "sfc_s0_s4.st")])
    assert code == 0 and capsys.readouterr().out.startswith("<svg")


def test_export_command_writes_xml_that_imports(tmp_path):
    import plclab

    out = tmp_path / "motor.xml"
    assert main(["export", str(ROOT / "labs/motor-start-stop/solution/motor.st"), "--fbd",
                 "-o", str(out)]) == 0
    plc = plclab.load(out)
    assert "<FBD>" in out.read_text()
    plc["Motor.START"] = True
    plc.scan()


def test_render_rejects_a_broken_file(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("<oops>")
    with pytest.raises(PlcError) as exc:
        render_source(bad.read_text(), "bad.xml")
    assert exc.value.code == "PLC0180"


ALL = sorted([p for p in EX.rglob("*") if p.suffix in (".st", ".il", ".ld", ".xml")]
             + [p for p in (ROOT / "labs").glob("*/solution/*")
                if p.suffix in (".st", ".il", ".ld", ".xml")])


@pytest.mark.parametrize("path", ALL, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_pou_of_every_example_and_lab_solution_is_drawn(path):
    from plclab.viz.diagram_commands import render_file

    pous = parse_source(path.read_text(encoding="utf-8"), path.name).pous
    assert pous
    for p in pous:
        svg = render_file(str(path), p.name)
        assert svg.startswith("<svg") and (p.spelling or p.name) in svg
