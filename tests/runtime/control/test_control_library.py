"""The control library as a whole: every block called from ST with named parameters, the
Python defaults equal the ST declarations, no block raises for any input, and the library
adds no diagnostics to user programs."""

import math
import re
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.compile.real32 import f32 as _f32
from plclab.lang import ast as A
from plclab.lang import types as T
from plclab.project import check_sources
from plclab.runtime import ctrlfb, natives
from plclab.testing import run_test_sources

ST_CALLS = """
TEST 'PID with every input named'
VAR pid : PID; END_VAR
pid(ACTUAL := 20.0, SETPOINT := 25.0, KP := 2.0, TN := 10.0, TV := 0.5, Y_MANUAL := 0.0,
    Y_OFFSET := 5.0, Y_MIN := 0.0, Y_MAX := 100.0, MANUAL := FALSE, RESET := FALSE,
    TM_LAG := T#200ms, DEADBAND := 0.0, REVERSE := FALSE, CYCLE := T#100ms);
ASSERT_NEAR(pid.Y, 15.0, 1.0E-5);
ASSERT_FALSE(pid.LIMITS_ACTIVE);
pid(ACTUAL := 20.0, SETPOINT := 80.0);
ASSERT_NEAR(pid.Y, 100.0, 1.0E-5);
ASSERT_TRUE(pid.LIMITS_ACTIVE);
pid(MANUAL := TRUE, Y_MANUAL := 42.0);
ASSERT_NEAR(pid.Y, 42.0, 1.0E-5);
END_TEST

TEST 'PID_INC with every input named'
VAR pi : PID_INC; END_VAR
pi(ACTUAL := 20.0, SETPOINT := 25.0, KP := 2.0, KI := 0.5, KD := 0.0, Y_MIN := 0.0,
   Y_MAX := 100.0, RESET := FALSE, CYCLE := T#1s);
ASSERT_NEAR(pi.Y, 10.0, 1.0E-5);
pi(ACTUAL := 20.0);
ASSERT_NEAR(pi.Y, 12.5, 1.0E-5);     (* + KI * T * e(n-1) = 0.5 * 1 * 5 *)
pi(RESET := TRUE);
ASSERT_EQ(pi.Y, 0.0);
END_TEST

TEST 'HYST with every input named'
VAR h : HYST; END_VAR
h(IN := 47.0, SP := 50.0, H := 2.0, REVERSE := FALSE, T_MIN_ON := T#0s, T_MIN_OFF := T#0s);
ASSERT_TRUE(h.Q);
ASSERT_EQ(h.SWITCHES, 1);
END_TEST

TEST 'AI_SCALE and AO_SCALE with every input named'
VAR a : AI_SCALE; o : AO_SCALE; END_VAR
a(IN := 27648, LO := 0.0, HI := 160.0, RANGE := '4-20mA', CONVENTION := 's7', BITS := 0,
  LIVE_ZERO := FALSE);
ASSERT_NEAR(a.VALUE, 160.0, 1.0E-4);
ASSERT_FALSE(a.WIRE_BREAK OR a.OVERRANGE OR a.UNDERRANGE OR a.ERROR);
o(IN := 160.0, LO := 0.0, HI := 160.0, RANGE := '4-20mA', CONVENTION := 's7', BITS := 0,
  LIVE_ZERO := FALSE);
ASSERT_EQ(o.OUT, 27648);
ASSERT_FALSE(o.LIMITED OR o.ERROR);
END_TEST

TEST 'NORM_X, SCALE_X, SCALE_R with named parameters'
VAR r : REAL; END_VAR
r := SCALE_X(MIN := 0.0, VALUE := NORM_X(MIN := 0.0, VALUE := 6912.0, MAX := 27648.0),
             MAX := 160.0);
ASSERT_NEAR(r, 40.0, 1.0E-4);
r := SCALE_R(IN := 0.5, IN_MIN := 0.0, IN_MAX := 1.0, OUT_MIN := -10.0, OUT_MAX := 10.0);
ASSERT_NEAR(r, 0.0, 1.0E-6);
END_TEST

TEST 'DEBOUNCE, BLINKER, RAMP, PT1 with every input named'
VAR d : DEBOUNCE; b : BLINKER; rp : RAMP; f : PT1; END_VAR
d(IN := TRUE, T_DEBOUNCE := T#0ms);
ASSERT_TRUE(d.Q);
b(ENABLE := TRUE, T_ON := T#100ms, T_OFF := T#100ms);
ASSERT_TRUE(b.Q);
rp(IN := 1.0, RATE := 0.0, RESET := FALSE);
ASSERT_EQ(rp.OUT, 1.0);
f(IN := 1.0, T := T#0ms, K := 2.0);
ASSERT_NEAR(f.OUT, 2.0, 1.0E-6);
END_TEST

TEST 'MOVING_AVG, LIMIT_ALARM, DEADBAND with every input named'
VAR m : MOVING_AVG; la : LIMIT_ALARM; db : DEADBAND; END_VAR
m(IN := 2.0, N := 2, RESET := FALSE);
m(IN := 4.0, N := 2, RESET := FALSE);
ASSERT_NEAR(m.AVG, 3.0, 1.0E-6);
la(IN := 5.0, HH := 100.0, H := 90.0, L := 10.0, LL := 0.0, DEADBAND := 1.0, PERCENT := FALSE);
ASSERT_TRUE(la.QL);
ASSERT_FALSE(la.QLL OR la.QH OR la.QHH);
db(IN := 1.0, WIDTH := 0.25);
ASSERT_NEAR(db.OUT, 0.75, 1.0E-6);
END_TEST
"""


def test_every_block_is_callable_from_st_with_named_parameters():
    results = run_test_sources([(ST_CALLS, "calls.st")])
    assert len(results) == 7
    assert all(r.passed for r in results), [str(r) for r in results]


# ---------------------------------------------------------------- defaults and diagnostics


class Ctx:
    now = 0
    cycle_ms = 10.0


def _library():
    project, diags = check_sources([])
    assert not diags
    return {name: pou for name, pou in project.pous.items()
            if pou.native in natives.CONTROL_BLOCKS}


def _literal(e):
    if isinstance(e, A.Unary) and e.op == "-":
        return -_literal(e.operand)
    assert isinstance(e, A.Literal), e
    if e.kind == "TIME":
        return e.value // 1_000_000
    return e.value


def test_python_defaults_equal_the_st_declarations():
    lib = _library()
    assert set(lib) == {"PID", "PID_INC", "HYST", "AI_SCALE", "AO_SCALE", "DEBOUNCE", "BLINKER",
                        "RAMP", "PT1", "MOVING_AVG", "LIMIT_ALARM"}
    for name, pou in lib.items():
        cls = natives.resolve(pou.native)
        inst = cls(Ctx())
        for d in pou.decls:
            want = T.default_value(d.ty) if d.init is None else _literal(d.init)
            got = getattr(inst, d.name)
            assert type(got) is type(want), (name, d.name, got, want)
            if isinstance(want, float):
                got, want = _f32(got), _f32(want)
            assert got == want, (name, d.name, got, want)
        # and nothing else is public: the ST interface is the whole interface
        public = {s for c in cls.__mro__ for s in getattr(c, "__slots__", ())
                  if not s.startswith("_")}
        assert public == {d.name for d in pou.decls}, name


def test_the_library_adds_no_diagnostics_and_user_names_can_reuse_block_names():
    src = """
    PROGRAM Blink
    VAR pid : PID; ramp : RAMP; deadband : REAL := 1.0; hyst : BOOL; END_VAR
    pid(ACTUAL := deadband, SETPOINT := 2.0);
    ramp(IN := pid.Y);
    hyst := ramp.BUSY;
    END_PROGRAM
    """
    project, diags = check_sources([(src, "user.st")])
    assert project is not None and diags == []
    plc = plclab.loads(src)
    plc.run(seconds=0.1)
    assert plc["Blink.hyst"] is True


# ------------------------------------------------------------------------ never raise

_TIMES = st.integers(-(2**31), 2**31 - 1)


def _strategy(ty):
    t = T.resolve(ty)
    if t is T.BOOL:
        return st.booleans()
    if t is T.REAL:
        return st.one_of(st.floats(width=32), st.sampled_from([0.0, -0.0, 1e-38, 3.4e38]))
    if t is T.TIME:
        return st.one_of(_TIMES, st.sampled_from([0, 1, 10, 100]))
    if isinstance(t, T.StringType):
        return st.one_of(st.sampled_from(["4-20mA", "0-10V", "+-10V", "1-5V", "0-20mA",
                                          "s7", "book", "full", "logo"]), st.text(max_size=8))
    return st.integers(t.lo, t.hi)


_LIB = _library()
_INPUTS = {name: [d for d in pou.decls if d.section == "VAR_INPUT"] for name, pou in _LIB.items()}


@st.composite
def _calls(draw):
    name = draw(st.sampled_from(sorted(_LIB)))
    steps = []
    for _ in range(draw(st.integers(1, 4))):
        values = {d.name: draw(_strategy(d.ty)) for d in _INPUTS[name]
                  if draw(st.booleans())}
        steps.append((draw(st.sampled_from([0, 1, 10, 1000, 10**7])), values))
    return name, steps


@settings(max_examples=600, deadline=None)
@given(_calls(), st.sampled_from([0.5, 10.0, 100.0]))
def test_no_block_raises_and_no_output_becomes_nan(call, cycle_ms):
    name, steps = call
    ctx = type("Ctx", (), {})()
    ctx.now, ctx.cycle_ms = 0, cycle_ms
    cls = natives.resolve(_LIB[name].native)
    inst = cls(ctx)
    outs = [d for d in _LIB[name].decls if d.section == "VAR_OUTPUT"]
    for dt, values in steps:
        ctx.now += dt
        for k, v in values.items():
            setattr(inst, k, v)
        inst._body()
        for d in outs:
            v = getattr(inst, d.name)
            t = T.resolve(d.ty)
            if t is T.REAL:
                assert isinstance(v, float) and not math.isnan(v), (name, d.name, v)
                assert v == _f32(v)  # a REAL output is a single-precision value
            elif t is T.BOOL:
                assert isinstance(v, bool), (name, d.name, v)
            else:
                assert isinstance(v, int) and t.lo <= v <= t.hi, (name, d.name, v)


# ------------------------------------------------------------------ docs/blocks.md examples

_DOCS = Path(__file__).resolve().parents[3] / "docs" / "blocks.md"


def test_every_example_in_docs_blocks_md_compiles_and_runs():
    snippets = re.findall(r"```iecst\n(.*?)```", _DOCS.read_text(encoding="utf-8"), re.S)
    assert len(snippets) >= 14
    for i, body in enumerate(snippets):
        src = f"PROGRAM Doc{i}\n{body}END_PROGRAM\n"
        project, diags = check_sources([(src, f"blocks_md_{i}.st")])
        errors = [str(d) for d in diags if d.severity == "error"]
        assert project is not None and not errors, (body, errors)
        plc = plclab.loads(src)
        plc.run(seconds=0.05)
        assert plc.state == "RUN", body


def test_blocks_are_callable_from_il_too():
    plc = plclab.loads("""
    PROGRAM Il
    VAR pid : PID; hy : HYST; pv : REAL := 1.0; sp : REAL := 3.0; y : REAL; heat : BOOL;
        raw : INT := 13824; frac : REAL; END_VAR
    CAL pid(ACTUAL := pv, SETPOINT := sp, KP := 2.0)
    LD pid.Y
    ST y
    CAL hy(IN := pv, SP := sp, H := 1.0)
    LD hy.Q
    ST heat
    LD 0.0
    NORM_X raw, 27648.0
    ST frac
    END_PROGRAM""")
    plc.scan()
    assert plc["Il.y"] == 4.0 and plc["Il.heat"] is True and plc["Il.frac"] == 0.5


def test_ctrlfb_docstring_examples():
    import doctest

    result = doctest.testmod(ctrlfb)
    assert result.attempted > 0 and result.failed == 0
