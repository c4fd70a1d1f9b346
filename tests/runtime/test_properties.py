"""Property tests (hypothesis): equivalent programs agree, arithmetic matches the hardware,
and no input at all makes the toolchain fail with anything but a PlcError."""

import random
import struct
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcError
from plclab.runtime.plc import Plc
from plclab.testing import run_compiled_tests

TWO_FORMS = """
PROGRAM Expr
VAR LS1, LS2 : BOOL; M : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM
PROGRAM WithIf
VAR LS1, LS2 : BOOL; M : BOOL; END_VAR
IF NOT LS1 THEN
    M := TRUE;
ELSIF LS2 THEN
    M := FALSE;
END_IF
IF LS2 THEN M := FALSE; END_IF
END_PROGRAM
"""
_TANK = plclab.compile_sources([(TWO_FORMS, "tank.st")])


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.booleans()), min_size=1, max_size=60))
def test_two_position_tank_forms_agree(seq):
    """001 gives the tank level both as an expression and as IF statements: same outputs."""
    plc = Plc(_TANK)
    for ls1, ls2 in seq:
        for prog in ("Expr", "WithIf"):
            plc[f"{prog}.LS1"] = ls1
            plc[f"{prog}.LS2"] = ls2
        plc.scan()
        assert plc["Expr.M"] == plc["WithIf.M"]


_ARITH = plclab.compile_sources([("""
PROGRAM P
VAR a, b : INT; s, d, p : INT; ua, ub : USINT; us : USINT; ra, rb : REAL; rs : REAL;
    q, m : INT; END_VAR
s := a + b; d := a - b; p := a * b; us := ua + ub; rs := ra * rb;
IF b <> 0 THEN q := a / b; m := a MOD b; END_IF
END_PROGRAM""", "arith.st")])


def _wrap(v, bits, signed):
    v &= (1 << bits) - 1
    return v - (1 << bits) if signed and v >= 1 << (bits - 1) else v


def _f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


@settings(max_examples=300, deadline=None)
@given(st.integers(-32768, 32767), st.integers(-32768, 32767), st.integers(0, 255),
       st.integers(0, 255), st.floats(-1e6, 1e6, width=32), st.floats(-1e6, 1e6, width=32))
def test_arithmetic_matches_the_hardware(a, b, ua, ub, ra, rb):
    plc = Plc(_ARITH)
    for k, v in dict(a=a, b=b, ua=ua, ub=ub, ra=ra, rb=rb).items():
        plc[k] = v
    plc.scan()
    assert plc["s"] == _wrap(a + b, 16, True)
    assert plc["d"] == _wrap(a - b, 16, True)
    assert plc["p"] == _wrap(a * b, 16, True)
    assert plc["us"] == (ua + ub) % 256
    assert plc["rs"] == _f32(_f32(ra) * _f32(rb))
    if b:
        q = abs(a) // abs(b) * (1 if (a >= 0) == (b > 0) else -1)
        assert plc["q"] == _wrap(q, 16, True)
        assert plc["m"] == a - b * q


SEEDS = [p.read_text() for p in sorted((Path(__file__).parent.parent / "st").glob("*.st"))]
TOKENS = [":=", ";", "(", ")", "[", "]", "END_IF", "IF", "THEN", "WHILE", "DO", "END_WHILE", "x",
          "1", "T#5s", "'s'", "+", "/", "0", "..", ",", ".", "FOR", "TO", "REPEAT", "UNTIL",
          "END_VAR", "VAR", "=>", "CASE", "OF", "TRUE", "%IX0.0", "16#", "(*", "*)", "ARRAY",
          "INT", "REAL", "RETURN", "EXIT", "FUNCTION_BLOCK", "$", '"', "\n"]


def _mutate(text: str, rng: random.Random) -> str:
    for _ in range(rng.randint(1, 4)):
        if not text:
            break
        i = rng.randrange(len(text))
        op = rng.randrange(4)
        if op == 0:
            text = text[:i] + text[i + rng.randint(1, 12):]
        elif op == 1:
            text = text[:i] + " " + rng.choice(TOKENS) + " " + text[i:]
        elif op == 2:
            j = rng.randrange(len(text))
            text = text[:i] + text[j:j + rng.randint(1, 30)] + text[i:]
        else:
            text = text[:i] + chr(rng.randint(32, 126)) + text[i + 1:]
    return text


def _exercise(text: str) -> None:
    try:
        compiled = plclab.compile_sources([(text, "fuzz.st")])
    except PlcError:
        return
    plc = Plc(compiled, watchdog=20_000)
    try:
        plc.scan(3)
    except PlcError:
        pass
    compiled.tests = compiled.tests[:5]
    for r in run_compiled_tests(compiled):
        assert r.passed or r.code.startswith("PLC"), r


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(0, len(SEEDS) - 1))
def test_mutated_programs_only_raise_plc_errors(seed, which):
    _exercise(_mutate(SEEDS[which], random.Random(seed)))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(TOKENS + list("abcxyz0123456789:;=<>()")), max_size=60).map(
    " ".join))
def test_random_token_soup_only_raises_plc_errors(text):
    _exercise("PROGRAM P VAR x : INT; END_VAR\n" + text + "\nEND_PROGRAM")
    _exercise(text)
