"""The playground's Python side (what the page calls under Pyodide), run in CPython."""

import pytest

from plclab.errors import PlcError
from plclab.site import playground_api as api


def test_tank_program_switches_the_pump_within_a_minute():
    s = api.Session(api.TANK_EXAMPLE, "st", "tank")
    assert s.ok and s.diagnostics == []
    rows = s.advance(60.0, every=0.1)
    assert len(rows) == 600 and s.scans == 3000
    pumps = [r["PUMP"] for r in rows]
    assert pumps[0] is True and pumps[-1] is False  # on from the start, off at LS2
    assert max(r["LEVEL"] for r in rows) >= 1.45
    assert set(rows[0]) == {"t", "LEVEL", "LS1", "LS2", "PUMP"}


def test_a_variable_named_like_the_signal_is_wired_without_an_address():
    text = ("PROGRAM P\nVAR LS1, LS2, PUMP : BOOL; END_VAR\n"
            "PUMP := ((NOT LS1) OR PUMP) AND (NOT LS2);\nEND_PROGRAM\n")
    s = api.Session(text, "st", "tank")
    assert s.mapped == {"LS1": "LS1", "LS2": "LS2", "PUMP": "PUMP"}
    assert s.advance(1.0)[-1]["PUMP"] is True


def test_syntax_error_is_a_diagnostic_at_its_line():
    text = "PROGRAM P\nVAR x : INT; END_VAR\nx := 1 +;\nEND_PROGRAM\n"
    s = api.Session(text, "st", "tank")
    assert not s.ok and s.advance(1.0) == []
    assert s.diagnostics[0]["code"] == "PLC0010" and s.diagnostics[0]["line"] == 3
    assert api.check(text)[0]["line"] == 3


def test_a_program_that_drives_nothing_gets_a_warning():
    s = api.Session("PROGRAM P\nVAR x : BOOL; END_VAR\nx := TRUE;\nEND_PROGRAM\n", "st", "tank")
    assert s.ok
    assert [d["code"] for d in s.diagnostics] == ["PLC3044"]
    assert "PUMP (%QX0.0)" in s.diagnostics[0]["message"]


def test_motor_buttons_pressed_from_the_page_start_and_stop_it():
    text = ("PROGRAM M\nVAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;\n"
            "K1 AT %QX0.0 : BOOL; END_VAR\nK1 := (START OR K1) AND STOP;\nEND_PROGRAM\n")
    s = api.Session(text, "st", "motor", scan_ms=10)
    s.advance(0.5)
    s.set_input("START", True)
    s.advance(0.2)
    s.release("START")
    s.set_input("START", False)
    s.release("START")
    rows = s.advance(2.0)
    assert rows[-1]["K1"] is True and rows[-1]["RUN"] is True
    s.set_input("STOP", False)  # the NC button pressed
    rows = s.advance(1.0)
    assert rows[-1]["K1"] is False


def test_il_and_ld_programs_run_too():
    il = api.Session(open("labs/tank-two-position/solution/tank.il").read(), "il", "tank")
    ld = api.Session(open("labs/tank-two-position/solution/tank.ld").read(), "ld", "tank")
    assert il.ok and ld.ok
    assert [r["PUMP"] for r in il.advance(60, 1)] == [r["PUMP"] for r in ld.advance(60, 1)]


def test_unknown_plant_is_plc3044():
    with pytest.raises(PlcError) as e:
        api.make_plant("boiler")
    assert e.value.code == "PLC3044"


def test_a_runtime_fault_stops_the_session_with_its_code():
    text = ("PROGRAM P\nVAR PUMP AT %QX0.0 : BOOL; a : ARRAY[1..3] OF INT; i : INT := 5; "
            "END_VAR\na[i] := 1;\nEND_PROGRAM\n")
    s = api.Session(text, "st", "tank")
    assert s.ok
    s.advance(1.0)
    assert not s.ok
    assert s.diagnostics[-1]["code"].startswith("PLC2")


def test_a_program_without_a_plant_runs_alone_and_shows_its_variables():
    s = api.Session("PROGRAM P VAR x : INT; w : WORD; t : TON; s : STRING; END_VAR\n"
                    "t(IN := TRUE, PT := T#1s); x := x + 1; w := 16#F0;\nEND_PROGRAM", "st",
                    api.NO_PLANT)
    assert s.ok and not s.diagnostics  # no "drives no plant" warning it did not ask for
    s.advance(1.0)
    watch = {w["path"]: w for w in s.watch()}
    assert watch["P.x"]["value"] == "50" and watch["P.x"]["trendable"]
    assert watch["P.w"]["value"] == "240" and watch["P.w"]["trendable"]
    assert not watch["P.t"]["trendable"] and not watch["P.s"]["trendable"]
    assert s.write("P.x", "1000") == [] and s.force("P.w", "16#0001") == []
    s.set_trend(["P.x", "P.w"])
    rows = s.advance(0.04)
    assert [r["P.x"] for r in rows] == [1001.0, 1002.0]  # written once, then counted on
    assert [r["P.w"] for r in rows] == [1.0, 1.0]  # forced every scan
    assert {w["path"]: w["forced"] for w in s.watch()}["P.w"]
    s.unforce("P.w")
    assert s.advance(0.02)[-1]["P.w"] == 240.0
    bad = s.write("P.x", "TRUE OR")
    assert bad and bad[0]["code"] == "PLC3002"


def test_analyse_names_the_plant_a_program_needs_and_its_tests():
    motor = ("PROGRAM M VAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;\n"
             "K1 AT %QX0.0 : BOOL; END_VAR K1 := (START OR K1) AND STOP; END_PROGRAM")
    assert api.analyse(motor)["plant"] == "motor"
    assert api.analyse(api.TANK_EXAMPLE)["plant"] == "tank"
    bare = "PROGRAM P VAR q AT %QX0.0 : BOOL; END_VAR q := TRUE; END_PROGRAM"
    assert api.analyse(bare)["plant"] == "tank"  # the default plant of %QX0.0
    tested = ("FUNCTION F : INT F := 1; END_FUNCTION\n"
              "TEST 'one' ASSERT_EQ(F(), 1); END_TEST\n")
    assert api.analyse(tested) == {"plant": "none", "tests": 1, "ok": True}
    assert api.analyse("PROGRAM")["ok"] is False


def test_tests_run_in_the_page_print_what_plclab_test_prints(tmp_path, capsys):
    from plclab.cli import main

    text = ("FUNCTION F : INT F := 1; END_FUNCTION\n"
            "TEST 'one' ASSERT_EQ(F(), 1); END_TEST\n"
            "TEST 'two' ASSERT_EQ(F(), 2, 'not two'); END_TEST\n")
    res = api.run_tests(text)
    assert res["summary"] == "1 passed, 1 failed" and res["lines"][0] == "PASS one"
    f = tmp_path / "playground.st"
    f.write_text(text)
    main(["test", "-v", str(f)])
    cli = capsys.readouterr().out.splitlines()
    assert cli[-1] == res["summary"]
    assert [ln.replace(str(f), "playground.st") for ln in cli[:-1]] == res["lines"]
    broken = api.run_tests("TEST 'x' y := ; END_TEST")
    assert broken["diagnostics"] and broken["summary"] == ""


def test_a_run_in_slices_samples_at_the_same_moments_as_one_call():
    """The page's worker advances a run in slices of any length; the samples still fall on
    the session's clock (every 0.1 s of virtual time), so a 60 s run ends with t = 60.0."""
    whole = api.Session(api.TANK_EXAMPLE, "st", "tank")
    rows = whole.advance(60.0, 0.1)
    sliced = api.Session(api.TANK_EXAMPLE, "st", "tank")
    got = []
    for chunk in (0.14, 0.3, 1.02, 0.06, 7.0, 0.48) * 6 + (6.0,):  # 60 s in all
        got += sliced.advance(chunk, 0.1)
    assert sliced.scans == whole.scans == 3000
    assert [r["t"] for r in got] == [r["t"] for r in rows]
    assert got[-1]["t"] == 60.0 and got == rows


def test_slices_sized_by_the_wall_clock_add_up_to_the_run():
    """The worker sizes its slices by how fast the machine is (any float, and a last sliver
    left by float subtraction): a 60 s run is still 3000 scans, sampled as one call samples it.
    Rounding each slice on its own ran 3001 scans on a loaded machine."""
    import random

    whole = api.Session(api.TANK_EXAMPLE, "st", "tank")
    rows = whole.advance(60.0, 0.1)
    for seed in range(3):
        rng = random.Random(seed)
        sliced = api.Session(api.TANK_EXAMPLE, "st", "tank")
        got, left = [], 60.0
        while left > 1e-9:  # as advanceSliced in site/playground/worker.js
            chunk = min(left, rng.uniform(0.02, 0.5))
            got += sliced.advance(chunk, 0.1)
            left -= chunk
        assert sliced.scans == 3000, seed
        assert got == rows


def test_a_step_is_one_scan_whatever_a_run_left_over():
    """Step runs exactly one scan, also after a run that left half a scan over either way
    (0.03 s and 0.01 s at 20 ms): through ``advance`` it ran 0 and 2 scans."""
    for seconds in (0.03, 0.01, 0.025, 0.0):
        s = api.Session(api.TANK_EXAMPLE, "st", "tank")
        s.advance(seconds, 0.1)
        before, t = s.scans, s.time
        s.step()
        assert s.scans == before + 1, seconds
        assert abs(s.time - t - 0.02) < 1e-12
    s.plc = None  # a session stopped by a fault: Step does nothing
    s.step()
