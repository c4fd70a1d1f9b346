"""The facts of issue 34's list (items 1-11): each fix in the text, and the behaviour of plclab
or the run that shows it. A check reads the chapter text where the fact is wording; where the
fact is behaviour, plclab is run."""

import re
import tomllib

import pytest

from plclab.course.model import find_chapter
from plclab.process.watch import WatchTable
from plclab.project import check_sources, loads


def _text(n: int) -> str:
    return " ".join(find_chapter(n).text.split())


def _errors(src: str, dialect: str | None = None) -> list[str]:
    _, diags = check_sources([(src, "fact.st")], dialect)
    return [d.code for d in diags if d.severity == "error"]


# 1. %QW2: vendor addressing taught; plclab's variables and image agree (ADR 0056)
def test_word_addressing_is_taught_per_vendor_and_plclab_follows_its_table():
    text = _text(5)
    assert "covers the same 16 bits as `%QX0.0 .. %QX1.7`" not in text
    row = next(ln for ln in find_chapter(5).text.splitlines() if ln.startswith("| `%QW2` |"))
    s7, codesys, ours = (c.strip() for c in row.strip("|").split("|")[1:])
    assert "bytes 2-3" in s7 and "bytes 4-5" in codesys and ours == "bytes 2-3"
    plc = loads("PROGRAM P\nVAR w AT %QW2 : WORD; END_VAR\n%QX3.0 := TRUE;\n%QX4.0 := TRUE;\n"
                "END_PROGRAM\n", "p.st")
    plc.scan()
    assert plc["P.w"] == plc["%QW2"] == 1  # bytes 2-3 only: %QX4.0 is not in it


# 2. the load input of CTD is LD in TIA Portal too
@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7"])
def test_ctd_loads_with_ld_in_every_dialect_and_the_text_says_so(dialect):
    src = "PROGRAM P\nVAR c : CTD; x : BOOL; y : BOOL; END_VAR\nc(CD := x, {} := y, PV := 3);" \
          "\nEND_PROGRAM\n"
    assert _errors(src.format("LD"), dialect) == []
    assert _errors(src.format("LOAD"), dialect) == ["PLC0107"]
    assert "S7 calls this input `LOAD`" not in _text(10)


# 3. the OB30..OB38 default intervals are S7-300/400
def test_ob_defaults_are_said_to_be_s7_300_400():
    text = _text(2)
    assert re.search(r"S7-300 and S7-400 each number has a default interval", text)
    assert "S7-1200 and S7-1500 the number no longer fixes the rate" in text
    quiz = tomllib.loads((find_chapter(2).folder / "quiz.toml").read_text(encoding="utf-8"))
    ob35 = next(i for i in quiz["item"] if i.get("id") == "ob35")
    assert "S7-300 or S7-400" in ob35["question"]


# 4. PROPERTY is not ed.3; IEC's default access is stated
def test_properties_and_default_access_are_placed_in_their_editions():
    text = _text(13)
    assert "the third edition of the standard took most of it" not in text
    assert "Properties are not in the third edition of IEC 61131-3" in text
    assert "makes PROTECTED the default" in text


# 5. outputs in STOP: the snippet of chapter 16, run as it is printed
def test_the_outputs_in_stop_snippet_switches_the_output():
    ch = find_chapter(16)
    block = next(b for b in ch.blocks if "enable_outputs_in_stop" in b.text)
    code = "\n".join(ln.split("#")[0] for ln in block.text.splitlines())
    plc = loads((ch.folder / "examples" / "tank.st").read_text(encoding="utf-8"), "tank.st")
    exec(compile(code, "chapter16", "exec"), {"plc": plc})  # noqa: S102 - our own course text
    assert plc["%QX0.0"] is True
    without = loads((ch.folder / "examples" / "tank.st").read_text(encoding="utf-8"), "tank.st")
    exec(compile(code.replace("plc.scan()", ""), "chapter16", "exec"), {"plc": without})  # noqa: S102
    assert without["%QX0.0"] is False  # the mistake the issue found: no scan, no output


# 6. the watch table says when it modifies; at scan end an input modify is useless
def test_the_commissioning_table_modifies_at_scan_start_and_scan_end_would_be_useless():
    ch = find_chapter(16)
    path = ch.folder / "examples" / "commissioning.toml"
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    assert raw["modify_at"] == "scan_start" and 'modify_at = "scan_start"' in ch.text
    src = (ch.folder / "examples" / "tank.st").read_text(encoding="utf-8")
    seen = {}
    for at in ("scan_start", "scan_end"):
        plc = loads(src, "tank.st")
        table = WatchTable.load(path)
        table.modify_at = at
        table.attach(plc)
        plc.scan(3)
        seen[at] = plc["Main.Starts"], table.samples[0].values
    # at scan start the program saw the modified low switch and left the pump off in scan 0;
    # at scan end the next input read wiped it: the pump started in scan 0
    assert seen["scan_start"][1][1] is False and seen["scan_end"][1][1] is True


# 7. the 5..15 V band is undefined by IEC 61131-2; keeping the state is plclab's choice
def test_the_undefined_band_is_not_called_what_every_module_does():
    text = _text(3)
    assert "a real module keeps its previous state there" not in text
    assert "the standard leaves the state undefined" in text


# 8. IEC 61499 adoption and edition 4 of IEC 61131-3
def test_edition_4_and_iec_61499_are_up_to_date():
    assert "the fourth (2025) leaves it out" in _text(5)
    assert "the fourth (2025) removes it" in _text(8)
    assert "had not adopted when it was written" in _text(17)


# 9. exercise 1 of chapter 9 works in every dialect as now written
@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7", "matiec"])
def test_the_power_exercise_compiles_with_real_operands(dialect):
    text = find_chapter(9).text
    expr = re.search(r"`n := (2\.0 \+ 3\.0 \* 4\.0 \*\* 2\.0 / 8\.0);`", text).group(1)
    assert _errors(f"PROGRAM P\nVAR n : REAL; END_VAR\nn := {expr};\nEND_PROGRAM\n",
                   dialect) == []
    int_form = "PROGRAM P\nVAR n : INT; END_VAR\nn := 2 + 3 * 4 ** 2 / 8;\nEND_PROGRAM\n"
    assert bool(_errors(int_form, dialect)) == (dialect != "codesys")  # what the text asks why


# 10. TONR is not IEC; the TIME range is per maker, plclab's as S7
def test_tonr_and_time_range_are_attributed():
    text = _text(10)
    assert "`TONR`, which is Siemens' and not in the standard" in text
    assert "0 .. 49d17h2m47s295ms" in text  # CODESYS
    ok = "PROGRAM P\nVAR t : TIME; END_VAR\nt := {};\nEND_PROGRAM\n"
    assert _errors(ok.format("T#24d20h31m23s647ms")) == []
    assert _errors(ok.format("T#24d20h31m23s648ms")) == ["PLC0126"]


# 11. smaller slips: 872.7 bytes/s, "Boiling", Start re-enables, the chapter 5 figure
def test_the_byte_rate_agrees_between_text_and_quiz():
    quiz = tomllib.loads((find_chapter(14).folder / "quiz.toml").read_text(encoding="utf-8"))
    item = next(i for i in quiz["item"] if i.get("id") == "frame-rate")
    rate = 9600 / 11
    assert item["answer"] == pytest.approx(rate, abs=0.05)
    assert f"= {rate:.1f}" in _text(14) and f"{rate:.1f} bytes per second" in item["explain"]


def test_boiling_is_said_not_to_boil():
    assert "cannot bring a full tub to the boil" in _text(11)


def test_the_oop_test_title_says_what_start_does():
    ch = find_chapter(13)
    assert "Start cannot override" not in ch.text
    assert "ASSERT_TRUE(p.Enabled);" in ch.text


def test_chapter_5_figure_plots_only_what_its_text_shows():
    ch = find_chapter(5)
    spec = next(s for s in ch.figure_specs if s["file"] == "instances.svg")
    block = next(b for b in ch.blocks if "FUNCTION_BLOCK HourMeter" in b.text)
    words = {w.upper() for w in re.findall(r"\w+", block.text)}
    for signal in spec["signals"]:
        assert {p.upper() for p in signal.split(".")} <= words, signal
