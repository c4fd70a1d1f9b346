"""What a student's program says never reaches the terminal raw (issue 30): ASSERT messages,
string tokens quoted in diagnostics and printed values go through one escaping function
(``plclab.errors.printable``), so no text can erase a line, colour the screen or fake the
test summary; a lone surrogate in a WSTRING prints; a block instance prints as its type."""

from plclab.cli import main
from plclab.errors import Diagnostic, printable

SPOOF = """
PROGRAM Main
VAR t : TON; w : WSTRING := "$D800"; s : STRING := 'a$1B[2Kb'; END_VAR
t(IN := TRUE, PT := T#1s);
END_PROGRAM
TEST 'controller works'
ASSERT_TRUE(FALSE, '$0D$1B[2KPASS controller works$0A2 passed, 0 failed$1B[8m');
END_TEST
TEST 'wide'
VAR w : WSTRING := "$D800"; END_VAR
ASSERT_EQ(w, "x");
END_TEST
"""


def _raw(text: str) -> list[str]:
    return [ch for ch in text if not ch.isprintable() and ch != "\n"]


def test_assert_messages_cannot_fake_the_summary(tmp_path, capsys):
    f = tmp_path / "spoof.st"
    f.write_text(SPOOF, encoding="utf-8")
    assert main(["test", str(f)]) == 1
    out = capsys.readouterr().out
    assert _raw(out) == []
    lines = out.strip().splitlines()
    assert lines[-1] == "0 passed, 2 failed"
    assert not any(line.startswith("2 passed") for line in lines)
    assert "FAIL controller works" in out and "\\x1b[2K" in out


def test_run_print_shows_iec_values(tmp_path, capsys):
    f = tmp_path / "spoof.st"
    f.write_text(SPOOF, encoding="utf-8")
    assert main(["run", str(f), "--cycles", "1"]) == 0
    out = capsys.readouterr().out
    assert _raw(out) == [] and " object at 0x" not in out
    # a block instance: a structured literal of its inputs and outputs (issue 40)
    assert "Main.t = (IN := TRUE, PT := T#1s, Q := FALSE, ET := T#0ms)" in out
    assert "Main.w = '$D800'" in out and "Main.s = 'a$1B[2Kb'" in out


AGGREGATES = """TYPE Pt : STRUCT x : INT; s : STRING; END_STRUCT; END_TYPE
PROGRAM Main
VAR
    names : ARRAY[1..3] OF STRING := ['a', 'b$N', 'c'];
    grid : ARRAY[0..1, 0..1] OF TIME;
    ps : ARRAY[1..2] OF Pt;
    big : ARRAY[1..1500] OF BOOL;
END_VAR
ps[2].s := 'q$1B';
grid[1, 1] := T#2s;
END_PROGRAM
"""


def test_run_print_shows_arrays_and_structures_element_by_element(tmp_path, capsys):
    f = tmp_path / "agg.st"
    f.write_text(AGGREGATES, encoding="utf-8")
    assert main(["run", str(f), "--cycles", "1", "--print", "names,grid,ps,big"]) == 0
    out = capsys.readouterr().out
    assert _raw(out) == [] and " object at 0x" not in out
    assert "names = ['a', 'b$N', 'c']" in out
    assert "grid = [T#0ms, T#0ms, T#0ms, T#2s]" in out
    assert "ps = [(x := 0, s := ''), (x := 0, s := 'q$1B')]" in out
    assert "FALSE, ... 500 more]" in out


def test_diagnostics_escape_what_they_quote():
    d = Diagnostic("PLC0001", "unexpected character '\x1b'\r")
    assert _raw(str(d)) == [] and "\\x1b" in str(d)
    assert printable("plain text") == "plain text"


def test_watch_tables_print_iec_values(tmp_path, capsys):
    """run --watch goes through the same escaping: a STRING with an escape sequence prints
    as an IEC literal, a block instance as its type."""
    f = tmp_path / "spoof.st"
    f.write_text(SPOOF, encoding="utf-8")
    w = tmp_path / "w.toml"
    w.write_text('name = "w"\n[[row]]\nname = "Main.s"\n[[row]]\nname = "Main.t"\n'
                 '[[row]]\nname = "Main.w"\n', encoding="utf-8")
    assert main(["run", str(f), "--cycles", "2", "--watch", str(w)]) == 0
    out = capsys.readouterr().out
    assert _raw(out) == [] and " object at 0x" not in out
    assert "'a$1B[2Kb'" in out and "(TON instance)" in out and "'$D800'" in out


def test_a_file_name_cannot_rewrite_the_line(tmp_path, capsys):
    f = tmp_path / "x\x1b[2K\rok.st"
    f.write_text("PROGRAM Main\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n", encoding="utf-8")
    assert main(["check", str(f)]) != 0
    captured = capsys.readouterr()
    text = captured.out + captured.err
    assert _raw(text) == [] and "x\\x1b[2K\\rok.st" in text


def test_a_terminal_that_cannot_show_a_character_gets_an_escape(tmp_path):
    """On an ASCII console (PYTHONIOENCODING=ascii) 'café' prints as caf\\xe9: no
    UnicodeEncodeError traceback from run --print or test."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    import plclab

    f = tmp_path / "cafe.st"
    f.write_text("PROGRAM Main\nVAR s : STRING := 'caf$E9'; END_VAR\nEND_PROGRAM\n"
                 "TEST 'caf\u00e9'\nASSERT_TRUE(FALSE, 'caf\u00e9');\nEND_TEST\n",
                 encoding="utf-8")
    env = {**os.environ, "PYTHONIOENCODING": "ascii",
           "PYTHONPATH": str(Path(plclab.__file__).resolve().parent.parent)}
    for args, status in ((["run", str(f), "--cycles", "1"], 0), (["test", str(f)], 1)):
        r = subprocess.run([sys.executable, "-m", "plclab", *args], capture_output=True,
                           text=True, encoding="ascii", errors="strict", env=env, timeout=120)
        assert r.returncode == status, r.stderr
        assert "Traceback" not in r.stderr and "caf\\xe9" in r.stdout
