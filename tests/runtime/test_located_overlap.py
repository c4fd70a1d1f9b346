"""A located variable and the process image agree (ADR 0056): the image is the truth, a
located %Q/%M variable is loaded from its bytes at scan start, writes them back at scan end only
when the program changed it, and is loaded again after the scan."""

import pytest

from plclab.project import loads

WORD_AND_BIT = """PROGRAM Main
VAR
    w AT %QW2 : WORD;
    seen : WORD;
END_VAR
seen := w;
%QX3.0 := TRUE;
END_PROGRAM
"""


def test_a_bit_written_by_address_is_not_wiped_by_the_unchanged_word():
    plc = loads(WORD_AND_BIT, "a.st")
    plc.scan()
    assert plc["%QW2"] == 1
    assert plc["Main.w"] == 1          # loaded again after the scan
    assert plc["Main.seen"] == 0       # inside scan 1 the word still held its start value
    plc.scan()
    assert plc["Main.seen"] == 1       # scan 2 starts with the word read from the image


@pytest.mark.parametrize("first", ["w", "b"])
def test_overlapping_variables_in_either_order_keep_what_the_program_wrote(first):
    decls = {"w": "w AT %QW2 : WORD;", "b": "b AT %QX3.1 : BOOL;"}
    other = "b" if first == "w" else "w"
    plc = loads(f"""PROGRAM Main
VAR
    {decls[first]}
    {decls[other]}
END_VAR
b := TRUE;
END_PROGRAM
""", "b.st")
    plc.scan(2)
    assert plc["%QW2"] == 2 and plc["Main.w"] == 2 and plc["Main.b"] is True


def test_a_changed_word_writes_its_bytes_and_the_bit_variable_follows():
    plc = loads("""PROGRAM Main
VAR
    w AT %QW2 : WORD;
    b AT %QX3.0 : BOOL;
    n : INT;
END_VAR
n := n + 1;
IF n = 2 THEN w := 16#0001; END_IF;
IF n = 3 THEN w := 16#0000; END_IF;
END_PROGRAM
""", "c.st")
    plc.scan()
    assert plc["Main.b"] is False
    plc.scan()
    assert plc["Main.b"] is True and plc["%QX3.0"] is True
    plc.scan()
    assert plc["Main.b"] is False and plc["%QW2"] == 0


def test_an_initial_value_reaches_the_image_and_a_value_set_from_python_stays():
    plc = loads("""PROGRAM Main
VAR
    w AT %QW4 : INT := 5;
    m AT %MW0 : INT := 7;
    count : INT;
END_VAR
count := count + 1;
END_PROGRAM
""", "d.st")
    plc.scan()
    assert plc["Main.w"] == 5 and plc["%QW4"] == 5
    assert plc["Main.m"] == 7 and plc["%MW0"] == 7
    plc["Main.w"] = 9
    plc["Main.m"] = -2
    plc.scan()
    assert plc["Main.w"] == 9 and plc["%QW4"] == 9
    assert plc["Main.m"] == -2


def test_an_address_written_from_outside_reaches_the_variable():
    plc = loads(WORD_AND_BIT.replace("%QX3.0 := TRUE;", ""), "e.st")
    plc["%QW2"] = 300
    plc.scan()
    assert plc["Main.seen"] == 300 and plc["Main.w"] == 300


def test_a_modify_at_scan_start_of_an_output_variable_is_kept():
    plc = loads(WORD_AND_BIT.replace("%QX3.0 := TRUE;", ""), "f.st")
    plc.modify("Main.w", 42, at="scan_start")
    plc.scan()
    assert plc["Main.seen"] == 42 and plc["%QW2"] == 42


def test_a_forced_output_address_drives_the_terminal_not_the_programs_variable():
    plc = loads("""PROGRAM Main
VAR
    run AT %QX0.0 : BOOL;
END_VAR
run := TRUE;
END_PROGRAM
""", "g.st")
    plc.force("%QX0.0", False)
    plc.scan(2)
    assert plc["%QX0.0"] is False      # the terminal obeys the force
    assert plc["Main.run"] is True     # the program's variable keeps what it wrote
    plc.unforce("%QX0.0")
    plc.scan()
    assert plc["%QX0.0"] is True
