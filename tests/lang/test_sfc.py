"""Textual SFC: parsing, checks with codes and places, lowering, and an ST twin.

The timing of every qualifier and the evolution rules are ST TEST blocks in tests/st/sfc.st;
here: what needs Python (diagnostics, the property test against a hand-written state machine,
the S0..S4 example)."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.project import check_sources
from plclab.testing import run_test_files, run_test_sources

ROOT = Path(__file__).parent.parent.parent


def diags(text: str):
    return check_sources([(text, "chart.st")])[1]


def codes(text: str) -> list[str]:
    return [d.code for d in diags(text)]


CHART = """
PROGRAM Main
VAR go, back, lamp : BOOL; n : INT; END_VAR
INITIAL_STEP Idle: END_STEP
STEP Run: lamp(N); Count(N); END_STEP
TRANSITION FROM Idle TO Run := go; END_TRANSITION
TRANSITION FROM Run TO Idle := back; END_TRANSITION
ACTION Count: n := n + 1; END_ACTION
END_PROGRAM
"""


def test_the_s0_s4_example_of_seed_002_passes_its_tests():
    results = run_test_files([str(ROOT / "examples" / "sfc_s0_s4.st")])
    assert len(results) == 3 and all(r.passed for r in results), [str(r) for r in results]


def test_a_chart_runs_through_the_api_and_exposes_step_and_action_flags():
    plc = plclab.loads(CHART, "chart.st")
    assert plc["Main.Idle.X"] is True
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.Run.X"] and plc["Main.lamp"] and plc["Main.Count.Q"]
    assert plc["Main.n"] == 1
    plc["Main.go"] = False
    plc.scan(4)
    assert plc.format("Main.Run.T") == "T#40ms" and plc["Main.n"] == 5


@pytest.mark.parametrize("qualifier,runs", [
    # entering Run at scan 1, leaving it at scan 4 (back), three more scans in Idle
    ("N", 4),   # scans 1-3 active, scan 4 the final scan after Q fell
    ("P", 2),   # the pulse at scan 1, its final scan at scan 2
    ("P1", 1),  # a pulse on activation: exactly one execution, no final scan (ed.2 NOTE 3)
    ("P0", 1),  # a pulse on deactivation: exactly one execution
])
def test_action_executions_per_qualifier(qualifier, runs):
    plc = plclab.loads(CHART.replace("Count(N)", f"Count({qualifier})"), "chart.st")
    plc["Main.go"] = True
    plc.scan()
    plc["Main.go"] = False
    plc.scan(2)
    plc["Main.back"] = True
    plc.scan()
    plc["Main.back"] = False
    plc.scan(3)
    assert plc["Main.n"] == runs


def test_sfc_words_stay_ordinary_names_outside_a_chart():
    text = """
PROGRAM Main
VAR step, action, transition, from : INT; END_VAR
step := 1; action := step + 1; transition := action; from := transition;
END_PROGRAM
"""
    assert not [d for d in diags(text) if d.severity == "error"]


def test_il_action_body_il_transition_and_a_body_assigning_the_name():
    text = """
FUNCTION_BLOCK Seq
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
INITIAL_STEP A: END_STEP
STEP B: Add(N); END_STEP
TRANSITION Up FROM A TO B :
    LD x
    GT 5
END_TRANSITION
TRANSITION Down FROM B TO A
    Down := x < 0;
END_TRANSITION
ACTION Add:
    LD n
    ADD 1
    ST n
END_ACTION
END_FUNCTION_BLOCK
TEST 'IL and body conditions'
  VAR s : Seq; END_VAR
  s(x := 3);
  ASSERT_TRUE(s.A.X);
  s(x := 6);
  ASSERT_TRUE(s.B.X); ASSERT_EQ(s.n, 1);
  s(x := -1);
  ASSERT_TRUE(s.A.X); ASSERT_EQ(s.n, 2);
END_TEST
"""
    from plclab.testing import run_test_sources
    results = run_test_sources([(text, "seq.st")])
    assert results and all(r.passed for r in results), [str(r) for r in results]


@pytest.mark.parametrize("snippet, code, line", [
    ("TRANSITION FROM Idle TO Rnu := go; END_TRANSITION", "PLC0150", 9),
    ("STEP Spare: END_STEP", "PLC0151", 9),
    # a second initial step linked to the chart (a separate network may have its own)
    ("INITIAL_STEP Two: END_STEP TRANSITION FROM Two TO Run := go; END_TRANSITION", "PLC0152",
     9),
])
def test_structural_checks_point_at_the_element(snippet, code, line):
    text = CHART.replace("END_PROGRAM", snippet + "\nEND_PROGRAM")
    found = [d for d in diags(text) if d.code == code]
    assert found and found[0].location.line == line, [str(d) for d in diags(text)]
    assert not [d for d in diags(text) if d.code == "PLC0200"]


def test_undeclared_step_suggests_the_close_name():
    text = CHART.replace("TO Run := go", "TO Rnu := go")
    (d,) = [d for d in diags(text) if d.code == "PLC0150"]
    assert "'Rnu'" in d.message and "did you mean Run?" in d.message and d.location.line == 6


@pytest.mark.parametrize("assoc, code", [
    ("lamp(Q)", "PLC0153"), ("lamp(L)", "PLC0154"), ("lamp(N, T#1s)", "PLC0154"),
    ("Lmap(N)", "PLC0157"), ("n(N)", "PLC0157"), ("Idle(N)", "PLC0157"),
    ("lamp(S)", "PLC0156"), ("lamp(N); lamp(P)", "PLC0156"),
])
def test_association_checks(assoc, code):
    text = CHART.replace("lamp(N); Count(N);", assoc + ";")
    found = [d for d in diags(text) if d.code == code]
    assert found and found[0].location.line == 5, [str(d) for d in diags(text)]
    assert found[0].severity == ("warning" if code == "PLC0156" else "error")


def test_names_clash_and_statements_outside_actions():
    assert "PLC0158" in codes(CHART.replace("n : INT;", "n : INT; Run : BOOL;"))
    bad = CHART.replace("ACTION Count:", "n := 2;\nACTION Count:")
    found = [d for d in diags(bad) if d.code == "PLC0010"]
    assert found and found[0].location.line == 8
    assert "STEP, INITIAL_STEP, TRANSITION or ACTION" in found[0].message


def test_parallel_branches_joined_by_an_alternative_convergence_warn():
    text = """
PROGRAM Main
VAR go : BOOL; END_VAR
INITIAL_STEP I: END_STEP
STEP A: END_STEP
STEP B: END_STEP
STEP C: END_STEP
STEP D: END_STEP
TRANSITION FROM I TO (A, B) := go; END_TRANSITION
TRANSITION FROM A TO D := go; END_TRANSITION
TRANSITION FROM B TO D := go; END_TRANSITION
TRANSITION FROM I TO C := NOT go; END_TRANSITION
TRANSITION FROM (C, D) TO I := go; END_TRANSITION
END_PROGRAM
"""
    found = [d for d in diags(text) if d.code == "PLC0155"]
    assert [d.location.line for d in found] == [10, 11, 13]
    assert "activates step D while it may still be active" in found[0].message
    assert "C, D are never active together" in found[2].message
    assert all(d.severity == "warning" for d in found)


# -- the property: an SFC program and its hand-written ST state machine ---------------------
TWINS = """
VAR_GLOBAL a, b, c : BOOL; END_VAR

PROGRAM Sfc
VAR motor, lamp, buzz : BOOL; count : INT; END_VAR
INITIAL_STEP Idle: END_STEP
STEP Fill: motor(N); Tally(N); END_STEP
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
ACTION Tally: count := count + 1; END_ACTION
END_PROGRAM

PROGRAM Twin
VAR
    xIdle : BOOL := TRUE;
    xFill, xHeat, xWait, xP1, xP1b, xP2 : BOOL;
    t1, t2, t3, t4, t5, t6, t7 : BOOL;
    heatTmr, buzzTmr : TON;
    motor, lamp, buzz, prevFill : BOOL;
    count : INT;
END_VAR
heatTmr(IN := xHeat, PT := T#20ms);
t1 := xIdle AND a;
t2 := xIdle AND NOT t1 AND b;
t3 := xFill AND b;
t4 := xP1 AND c;
t5 := xP1b AND xP2 AND a AND NOT b;
t6 := xHeat AND heatTmr.Q;
t7 := xWait AND c;
IF t1 OR t2 THEN xIdle := FALSE; END_IF;
IF t3 THEN xFill := FALSE; END_IF;
IF t4 THEN xP1 := FALSE; END_IF;
IF t5 THEN xP1b := FALSE; xP2 := FALSE; END_IF;
IF t6 THEN xHeat := FALSE; END_IF;
IF t7 THEN xWait := FALSE; END_IF;
IF t1 THEN xFill := TRUE; END_IF;
IF t2 THEN xHeat := TRUE; heatTmr(IN := FALSE); heatTmr(IN := TRUE, PT := T#20ms); END_IF;
IF t3 THEN xP1 := TRUE; xP2 := TRUE; END_IF;
IF t4 THEN xP1b := TRUE; END_IF;
IF t5 OR t7 THEN xIdle := TRUE; END_IF;
IF t6 THEN xWait := TRUE; END_IF;
motor := xFill;
IF xFill OR prevFill THEN count := count + 1; END_IF;
prevFill := xFill;
lamp := NOT xWait AND (xHeat OR lamp);
buzzTmr(IN := xWait, PT := T#30ms);
buzz := xWait AND NOT buzzTmr.Q;
END_PROGRAM
"""
PAIRS = [("Idle.X", "xIdle"), ("Fill.X", "xFill"), ("Heat.X", "xHeat"), ("Wait.X", "xWait"),
         ("P1.X", "xP1"), ("P1b.X", "xP1b"), ("P2.X", "xP2"), ("motor", "motor"),
         ("lamp", "lamp"), ("buzz", "buzz"), ("count", "count")]


@settings(max_examples=60, deadline=None, database=None)
@given(st.lists(st.tuples(st.booleans(), st.booleans(), st.booleans()), min_size=1,
                max_size=60))
def test_an_sfc_and_its_st_state_machine_twin_give_identical_traces(inputs):
    plc = plclab.loads(TWINS, "twins.st")
    for scan, (a, b, c) in enumerate(inputs):
        plc["a"], plc["b"], plc["c"] = a, b, c
        plc.scan()
        sfc = [plc[f"Sfc.{s}"] for s, _ in PAIRS]
        twin = [plc[f"Twin.{t}"] for _, t in PAIRS]
        names = [s for s, _ in PAIRS]
        assert sfc == twin, f"scan {scan}: {list(zip(names, sfc, twin, strict=True))}"


def test_a_chart_in_a_function_and_jumps_in_an_il_action_are_errors_at_their_place():
    fn = "FUNCTION F : INT\nINITIAL_STEP A: END_STEP\nEND_FUNCTION\n"
    (d,) = [d for d in diags(fn) if d.code == "PLC0010"]
    assert d.location.line == 2 and "FUNCTION_BLOCK or a PROGRAM" in d.message
    il = CHART.replace("ACTION Count: n := n + 1; END_ACTION",
                       "ACTION Count:\n  LD n\n  JMPC skip\nskip:\nEND_ACTION")
    found = [d for d in diags(il) if d.code == "PLC0145"]
    assert found and found[0].location.line == 10 and "IL action" in found[0].message


TWO_NETWORKS = """
PROGRAM Main
VAR go, back, fill, full : BOOL; END_VAR
INITIAL_STEP Idle: END_STEP
STEP Run: END_STEP
TRANSITION FROM Idle TO Run := go; END_TRANSITION
TRANSITION FROM Run TO Idle := back; END_TRANSITION
INITIAL_STEP Empty: END_STEP
STEP Filling: END_STEP
TRANSITION FROM Empty TO Filling := fill; END_TRANSITION
TRANSITION FROM Filling TO Empty := full; END_TRANSITION
END_PROGRAM
"""


def test_one_initial_step_per_sfc_network():
    """Two networks in one body (Annex F's gravel example has two), each with its own initial
    step: both start active and evolve independently (ADR 0053)."""
    assert not [d for d in diags(TWO_NETWORKS) if d.severity == "error"]
    plc = plclab.loads(TWO_NETWORKS, "two.st")
    assert plc["Main.Idle.X"] and plc["Main.Empty.X"]
    plc["Main.fill"] = True
    plc.scan()
    assert plc["Main.Idle.X"] and plc["Main.Filling.X"] and not plc["Main.Empty.X"]
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.Run.X"] and plc["Main.Filling.X"]


@pytest.mark.parametrize("link", [
    "TRANSITION FROM Run TO Filling := back; END_TRANSITION",    # joins the two networks
    "TRANSITION FROM (Run, Filling) TO Idle := back; END_TRANSITION",
])
def test_two_initial_steps_in_one_connected_chart_are_refused(link):
    text = TWO_NETWORKS.replace("END_PROGRAM", link + "\nEND_PROGRAM")
    found = [d for d in diags(text) if d.code == "PLC0152"]
    assert len(found) == 1 and "Empty" in found[0].message and found[0].location.line == 8



STEP_TIME_FROM_CREATION = """
FUNCTION_BLOCK Seq
VAR_INPUT go : BOOL; END_VAR
INITIAL_STEP S0: END_STEP
STEP S1: END_STEP
TRANSITION FROM S0 TO S1 := go; END_TRANSITION
TRANSITION FROM S1 TO S0 := NOT go; END_TRANSITION
END_FUNCTION_BLOCK
"""


def test_initial_step_time_counts_from_the_instance_creation_in_a_test():
    """IEC 61131-3 ed.2 2.6.2 / ed.3 6.7.2: the initial step is active from the POU's
    initialisation, so its elapsed time is counted from there, not from the first call."""
    text = STEP_TIME_FROM_CREATION + """
TEST 'S0.T from creation'
  VAR s : Seq; END_VAR
  ADVANCE_TIME(T#1s);
  s();
  ASSERT_EQ(s.S0.T, T#1s);
  ADVANCE_TIME(T#500ms);
  s(go := TRUE);
  ASSERT_TRUE(s.S1.X); ASSERT_EQ(s.S1.T, T#0s); ASSERT_EQ(s.S0.T, T#1500ms);
  ADVANCE_TIME(T#200ms);
  s(go := TRUE);
  ASSERT_EQ(s.S1.T, T#200ms);
  s(go := FALSE);
  ADVANCE_TIME(T#300ms);
  s(go := FALSE);
  ASSERT_TRUE(s.S0.X); ASSERT_EQ(s.S0.T, T#300ms);
END_TEST
"""
    results = run_test_sources([(text, "seq.st")])
    assert [r.passed for r in results] == [True], [str(r) for r in results]


def test_initial_step_time_of_a_chart_first_called_after_a_second_of_scans():
    text = """
FUNCTION_BLOCK Seq
VAR_OUTPUT t : TIME; END_VAR
INITIAL_STEP S0: Rec(N); END_STEP
STEP S1: END_STEP
TRANSITION FROM S0 TO S1 := FALSE; END_TRANSITION
ACTION Rec: t := S0.T; END_ACTION
END_FUNCTION_BLOCK
PROGRAM Main
VAR s : Seq; n : INT; t : TIME; END_VAR
n := n + 1;
IF n > 100 THEN s(); t := s.t; END_IF;
END_PROGRAM
"""
    plc = plclab.loads(text, "seq.st", cycle_time="10ms")
    plc.scan(101)
    assert plc["Main.n"] == 101
    assert plc["Main.t"] == 100 * 10  # ms: the 101st scan runs 100 cycles of 10 ms after start
