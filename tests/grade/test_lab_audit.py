"""``plclab lab audit``: mutants of a solution, and a rubric measured by the mutants it catches
(issue 31 item 2). The audit must be able to fail: a rubric with its criteria removed catches
fewer behaviour-changing mutants than the lab's own."""

import copy

import pytest

from plclab.grade.audit import CAUGHT, audit, mutants, sites
from plclab.grade.lab import load_lab
from plclab.lang.frontends.st import parse_st

PROGRAM = """PROGRAM Main
VAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL; K1 AT %QX0.0 : BOOL; t : TON;
    trig : R_TRIG; latch : RS; n : INT; END_VAR
trig(CLK := START);
IF trig.Q AND n < 10 THEN n := n + 1; END_IF;
latch(S := START, R1 := NOT STOP);
t(IN := K1, PT := T#5s);
K1 := (START OR K1) AND STOP AND NOT t.Q;
END_PROGRAM
"""


def test_every_operator_of_the_issue_has_sites():
    ops = {op for op, *_ in sites(parse_st(PROGRAM, "p.st"))}
    assert {"negate", "and-or", "drop-term", "comparison", "remove-not", "constant",
            "delete", "latch", "edge"} <= ops


def test_mutants_are_valid_st_that_differ_from_the_solution():
    import plclab

    ms = mutants(PROGRAM, "p.st")
    assert len(ms) > 20
    texts = {m.text for m in ms}
    assert len(texts) == len(ms)  # each mutant is its own change
    compiled = 0
    for m in ms:
        assert m.text != PROGRAM and m.line > 0 and m.description
        try:
            plclab.compile_sources([(m.text, "m.st")])
            compiled += 1
        except plclab.PlcError:
            pass
    assert compiled >= 0.8 * len(ms)
    sample = mutants(PROGRAM, "p.st", limit=8, seed=1)
    assert len(sample) == 8 and len({m.operator for m in sample}) >= 6


@pytest.fixture(scope="module")
def motor():
    return load_lab("motor-start-stop")


def test_a_weak_rubric_catches_fewer_mutants(motor):
    full = audit(motor, limit=24, jobs=1)
    weak = copy.copy(motor)
    weak.criteria = [c for c in motor.criteria if c.name == "starts"]
    weak.mistakes = []
    weaker = audit(weak, limit=24, jobs=1)
    assert full.counted() and weaker.counted()
    assert weaker.mutation_score < full.mutation_score
    assert weaker.mutation_score <= 0.5
    for m in full.counted():
        assert (m.status == "caught") == (m.score <= CAUGHT * m.max_score + 1e-9)
    assert full.mistakes and full.mistakes_ok
    assert "mutation score" in full.text()


def test_the_audit_of_a_small_lab_runs_end_to_end(motor):
    rep = audit(motor, limit=6, seed=3, jobs=1)
    assert 0.0 <= rep.mutation_score <= 1.0
    assert rep.to_json()["variants_ok"] in (True, False)


AUDIT_ALL = pytest.mark.skipif(not __import__("os").environ.get("PLCLAB_AUDIT"),
                               reason="opt-in: PLCLAB_AUDIT=1 audits every lab (minutes)")


@pytest.mark.slow
@AUDIT_ALL
@pytest.mark.parametrize("lab_id", [p.name for p in __import__(
    "plclab.grade.lab", fromlist=["list_labs"]).list_labs()])
def test_every_lab_passes_its_audit(lab_id):
    """Issue 31's target: mutation score >= 90 %, every mistake within bound, variants >= 95 %."""
    rep = audit(load_lab(lab_id), limit=60, seed=0, jobs=2)
    assert rep.mutation_score >= 0.9 and rep.mistakes_ok and rep.variants_ok, rep.text()


SFC = """PROGRAM Main
VAR START AT %IX0.0 : BOOL; LAMP AT %QX0.0 : BOOL; END_VAR
    INITIAL_STEP Idle: END_STEP
    TRANSITION FROM Idle TO Lit := START; END_TRANSITION
    STEP Lit: LAMP(N); END_STEP
    TRANSITION (PRIORITY := 0) FROM Lit TO Idle := Lit.T >= T#2s; END_TRANSITION
END_PROGRAM
"""


def test_sfc_steps_and_transitions_are_mutated():
    import plclab

    ms = [m for m in mutants(SFC, "s.st") if m.operator.startswith("sfc")]
    ops = {m.operator for m in ms}
    assert ops == {"sfc-action", "sfc-transition"}
    assert any("LAMP(N)" in m.description and "LAMP(N)" not in m.text for m in ms)
    assert any(m.line == 4 and ":= NOT (START);" in m.text for m in ms)
    assert any(m.line == 6 and ":= TRUE;" in m.text for m in ms)
    for m in ms:
        plclab.compile_sources([(m.text, "m.st")])


def test_a_survivor_shows_the_mutated_expression():
    descs = {m.description for m in mutants(PROGRAM, "p.st") if m.operator in ("and-or",
                                                                               "comparison")}
    assert "START OR K1 -> START AND K1" in descs
    assert "n < 10 -> n <= 10" in descs


def test_an_sfc_solution_gets_valid_mutants_of_its_conditions():
    import plclab

    ms = mutants(SFC, "s.st")
    assert ms and all(m.operator.startswith("sfc") or "TRANSITION" in m.description for m in ms)
    assert any(m.description.endswith("-> Lit.T > T#2s") for m in ms)
    assert any(m.description.endswith("-> Lit.T >= T#4s") for m in ms)
    for m in ms:
        plclab.compile_sources([(m.text, "m.st")])
    assert len(mutants(SFC, "s.st", limit=3, seed=2)) == 3
