"""Broken IL, ladder text and XML only ever produce PlcErrors (diagnostics), never a Python
exception: mutate the examples and feed token soups to each front end."""

import random
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcError
from plclab.runtime.plc import Plc

EXAMPLES = Path(__file__).parent.parent.parent / "examples"
SEEDS = [(p.read_text(encoding="utf-8"), p.name) for p in sorted(EXAMPLES.iterdir())
         if p.suffix in (".il", ".ld", ".xml")]
PIECES = ["|", "-", "+", "[ ]", "[/]", "[P]", "( )", "(S)", "[", "]", "(", ")", "---", "   ",
          "\n", "LD", "ST", "AND(", "JMPC", "L1:", "CAL", "x", "T1", "<", ">", "/>", "localId",
          "\"", "'", "refLocalId=\"1\"", "<coil", "<block", "]]>", "[TON T1 PT:=T#1s]", ":=",
          "END_PROGRAM", "VAR", "END_VAR", ";", "0", "T#5s", "->", "%IX0.0", "\t"]


def _mutate(text: str, rng: random.Random) -> str:
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(len(text))
        op = rng.randrange(4)
        if op == 0:
            text = text[:i] + text[i + rng.randint(1, 10):]
        elif op == 1:
            text = text[:i] + rng.choice(PIECES) + text[i:]
        elif op == 2:
            j = rng.randrange(len(text))
            text = text[:i] + text[j:j + rng.randint(1, 40)] + text[i:]
        else:
            text = text[:i] + chr(rng.randint(32, 126)) + text[i + 1:]
    return text


def _exercise(text: str, name: str) -> None:
    try:
        compiled = plclab.compile_sources([(text, name)])
    except PlcError:
        return
    plc = Plc(compiled, watchdog=20_000)
    try:
        plc.scan(3)
    except PlcError:
        pass


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(0, len(SEEDS) - 1))
def test_mutated_examples_only_raise_plc_errors(seed, which):
    text, name = SEEDS[which]
    _exercise(_mutate(text, random.Random(seed)), name)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(PIECES), max_size=50).map("".join),
       st.sampled_from(["s.il", "s.ld", "s.st"]))
def test_soup_in_a_body_only_raises_plc_errors(text, name):
    _exercise("PROGRAM P\nVAR x, y : BOOL; T1 : TON; END_VAR\n" + text + "\nEND_PROGRAM\n", name)


def test_ladder_drawing_survives_broken_rungs():
    from plclab.viz.ladder_svg import render_ld

    rng = random.Random(7)
    text = (EXAMPLES / "bottle.ld").read_text(encoding="utf-8")
    for _ in range(100):
        render_ld(_mutate(text, rng))
