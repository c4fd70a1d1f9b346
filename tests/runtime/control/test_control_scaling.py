"""NORM_X, SCALE_X, SCALE_R, AI_SCALE and AO_SCALE with the source texts' numbers.

001_c648febd3bbd6efb.txt:
  1008-1196  ADC resolution span / 2^n (0-10 V, 12 bit: 2.44 mV), y = ymin + N (ymax - ymin) / Nmax
             (the book divides by 2^n), worked example 0-20 mA, -20..+220 degC, 12 bit, N = 512
             -> 10 degC (1153-1160); LOGO!8 10-bit 0..1000
  3435-3513  NORM_X / SCALE_X, S7-1200 4-20 mA = 0..27648 counts -> 0..160 bar
  7290-7325  live zero, wire break
"""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plclab.io import AnalogInput, counts_to_eng, eng_to_counts
from plclab.runtime.ctrlfb import AI_SCALE, AO_SCALE
from plclab.testing import run_test_sources


class Ctx:
    now = 0
    cycle_ms = 10.0


def ai(counts, **kw):
    b = AI_SCALE(Ctx(), double=True)
    for k, v in kw.items():
        setattr(b, k, v)
    b.IN = counts
    b._body()
    return b


def ao(value, **kw):
    b = AO_SCALE(Ctx())
    for k, v in kw.items():
        setattr(b, k, v)
    b.IN = value
    b._body()
    return b


def run_st(src):
    results = run_test_sources([(src, "scaling.st")])
    assert results
    assert all(r.passed for r in results), [str(r) for r in results]


# ------------------------------------------------------------------- textbook numbers


def test_book_example_12_bit_0_20_mA_512_counts_is_10_degC():
    b = ai(512, LO=-20.0, HI=220.0, RANGE="0-20mA", CONVENTION="book", BITS=12)
    assert b.VALUE == 10.0
    assert not (b.ERROR or b.WIRE_BREAK or b.OVERRANGE or b.UNDERRANGE)
    # the other conventions give other numbers for the same word: the convention matters
    assert ai(512, LO=-20.0, HI=220.0, RANGE="0-20mA", CONVENTION="full", BITS=12).VALUE == \
        pytest.approx(-20.0 + 512 * 240.0 / 4095)


def test_s7_4_20_mA_0_27648_is_0_160_bar():
    for counts, bar in ((0, 0.0), (6912, 40.0), (13824, 80.0), (27648, 160.0)):
        assert ai(counts, LO=0.0, HI=160.0).VALUE == pytest.approx(bar, abs=1e-12)
        assert ao(bar, LO=0.0, HI=160.0).OUT == counts


def test_0_10_V_12_bit_resolution_is_2_44_mV():
    step = (ai(1, LO=0.0, HI=10.0, RANGE="0-10V", CONVENTION="book", BITS=12).VALUE
            - ai(0, LO=0.0, HI=10.0, RANGE="0-10V", CONVENTION="book", BITS=12).VALUE)
    assert round(step * 1000, 2) == 2.44
    # +-10 V, 14 bit: 1.22 mV (the book's second example)
    step14 = (ai(1, LO=-10.0, HI=10.0, RANGE="+-10V", CONVENTION="book", BITS=14).VALUE
              - ai(0, LO=-10.0, HI=10.0, RANGE="+-10V", CONVENTION="book", BITS=14).VALUE)
    assert round(step14 * 1000, 2) == 1.22


@pytest.mark.parametrize("bits", [8, 10, 12, 14, 16])
def test_book_bit_widths_half_scale(bits):
    b = ai(2 ** (bits - 1), LO=0.0, HI=100.0, RANGE="0-10V", CONVENTION="book", BITS=bits)
    assert b.VALUE == 50.0 and not b.ERROR


def test_logo_0_1000():
    assert ai(500, LO=0.0, HI=50.0, RANGE="0-10V", CONVENTION="logo").VALUE == 25.0
    assert ai(1000, LO=0.0, HI=50.0, RANGE="0-10V", CONVENTION="logo").VALUE == 50.0


# ------------------------------------------------------------------- status bits


def test_s7_overrange_is_still_a_measurement():
    b = ai(29000, LO=0.0, HI=160.0)  # 20.78 mA
    assert b.OVERRANGE and not b.ERROR
    assert b.VALUE == pytest.approx(29000 * 160.0 / 27648)
    b.IN = 30000  # 21.36 mA: NE43 says >= 21 mA is a failure (short circuit)
    b._body()
    assert b.OVERRANGE and b.ERROR and not b.WIRE_BREAK
    assert b.VALUE == pytest.approx(29000 * 160.0 / 27648)  # held
    b = ai(-2000, LO=0.0, HI=100.0, RANGE="0-10V")
    assert b.UNDERRANGE and not b.ERROR and b.VALUE < 0.0


def test_s7_wire_break_code_holds_the_last_value():
    b = ai(13824, LO=0.0, HI=160.0)
    b.IN = 32767  # 7FFF: wire break on a live-zero S7 channel (or overflow)
    b._body()
    assert b.WIRE_BREAK and b.OVERRANGE and b.ERROR
    assert b.VALUE == 80.0  # last good value
    b.IN = 13824
    b._body()
    assert not (b.WIRE_BREAK or b.ERROR)


def test_s7_underflow_and_ne43_wire_break_from_the_signal():
    b = ai(-32768, LO=0.0, HI=100.0, RANGE="0-10V")
    assert b.UNDERRANGE and b.ERROR and not b.WIRE_BREAK
    # 4-20 mA, -1000 counts = 3.42 mA: below NE43's 3.6 mA -> wire break
    b = ai(-1000, LO=0.0, HI=160.0)
    assert b.WIRE_BREAK and b.UNDERRANGE and b.ERROR
    # 3.8 mA: under-range but no failure
    b = ai(round(-0.2 / 16 * 27648), LO=0.0, HI=160.0)
    assert b.UNDERRANGE and not b.WIRE_BREAK and not b.ERROR


def test_live_zero_transmitter_on_a_0_20_mA_book_input():
    """The book's "20 % offset": a 4-20 mA transmitter on a 0-20 mA 12-bit input."""
    kw = dict(LO=0.0, HI=160.0, RANGE="0-20mA", CONVENTION="book", BITS=12, LIVE_ZERO=True)
    assert ai(2458, **kw).VALUE == pytest.approx(80.0, abs=0.05)
    assert ai(4095, **kw).VALUE == pytest.approx(160.0, abs=0.05)
    b = ai(0, **kw)  # 0 mA: the loop is open
    assert b.WIRE_BREAK and b.ERROR
    b = ai(800, **kw)  # 3.9 mA: under-range, still a reading
    assert b.UNDERRANGE and not b.ERROR
    # a live-zero range needs no flag; a bipolar range ignores it
    assert ai(13824, LO=0.0, HI=10.0, RANGE="1-5V", LIVE_ZERO=True).VALUE == 5.0
    assert ai(0, LO=-1.0, HI=1.0, RANGE="+-10V", CONVENTION="book", BITS=12,
              LIVE_ZERO=True).VALUE == -1.0


def test_agrees_with_an_analog_input_channel():
    ch = AnalogInput(lo=-20.0, hi=220.0, signal="0-20mA", convention="book", bits=12)
    for t, temp in enumerate((-20.0, 10.0, 55.5, 219.0)):
        counts = ch.sample(float(t), temp)
        assert ai(counts, LO=-20.0, HI=220.0, RANGE="0-20mA", CONVENTION="book",
                  BITS=12).VALUE == pytest.approx(ch.eng)


def test_bad_configuration_is_an_error_not_an_exception():
    assert ai(100, RANGE="banana").ERROR
    assert ai(100, CONVENTION="s5").ERROR
    assert ai(100, CONVENTION="book", BITS=40).ERROR
    assert ao(1.0, RANGE="banana").ERROR
    assert ao(1.0, LO=5.0, HI=5.0).ERROR
    assert ao(math.nan).ERROR
    b = ai(100, RANGE="banana")
    b.RANGE = "4-20mA"
    b._body()
    assert not b.ERROR  # the configuration is read again when it changes


# ------------------------------------------------------------------------- AO_SCALE


def test_ao_scale_clamps_and_flags():
    b = ao(200.0, LO=0.0, HI=160.0)
    assert b.OUT == 27648 and b.LIMITED
    b = ao(-5.0, LO=0.0, HI=160.0)
    assert b.OUT == 0 and b.LIMITED
    assert ao(10.0, LO=0.0, HI=10.0, RANGE="0-10V", CONVENTION="book", BITS=12).OUT == 4095
    assert ao(0.0, LO=0.0, HI=160.0, RANGE="0-20mA", CONVENTION="book", BITS=12,
              LIVE_ZERO=True).OUT == 819  # 4 mA
    assert ao(-1.0, LO=-1.0, HI=1.0, RANGE="+-10V").OUT == -27648
    assert ao(100.0, LO=0.0, HI=100.0, RANGE="0-10V", CONVENTION="book", BITS=16).OUT == -1
    assert ao(math.inf, LO=0.0, HI=160.0).OUT == 27648


@settings(max_examples=200, deadline=None)
@given(st.floats(0.0, 160.0))
def test_ao_then_ai_round_trip_within_one_count(value):
    counts = ao(value, LO=0.0, HI=160.0).OUT
    assert counts == eng_to_counts(value, 0.0, 160.0, convention="s7", limit=True)
    back = ai(counts, LO=0.0, HI=160.0).VALUE
    assert back == counts_to_eng(counts, 0.0, 160.0, convention="s7")
    assert abs(back - value) <= 160.0 / 27648 / 2 + 1e-9


# -------------------------------------------------------------------------- from ST

ST_SCALING = """
TEST 'NORM_X / SCALE_X: 4-20 mA on an S7-1200, 13824 counts = 80 bar (001 L3435-3513)'
VAR raw : INT := 13824; temp_value : REAL; out_value : REAL; END_VAR
temp_value := NORM_X(MIN := 0, VALUE := raw, MAX := 27648);
ASSERT_NEAR(temp_value, 0.5, 1.0E-6);
out_value := SCALE_X(MIN := 0.0, VALUE := temp_value, MAX := 160.0);
ASSERT_NEAR(out_value, 80.0, 1.0E-4);
END_TEST

TEST 'NORM_X / SCALE_X are not limited; MIN = MAX gives 0'
VAR r : REAL; END_VAR
r := NORM_X(MIN := 0.0, VALUE := 30000.0, MAX := 27648.0);
ASSERT_TRUE(r > 1.0);
r := NORM_X(MIN := 5.0, VALUE := 7.0, MAX := 5.0);
ASSERT_EQ(r, 0.0);
r := SCALE_X(MIN := 100.0, VALUE := -0.5, MAX := 200.0);
ASSERT_NEAR(r, 50.0, 1.0E-4);
END_TEST

TEST 'MIN and MAX as parameter names do not hide the functions MIN() and MAX()'
VAR r : REAL; a : REAL := 3.0; b : REAL := 7.0; END_VAR
r := SCALE_X(MIN := MIN(a, b), VALUE := 0.5, MAX := MAX(a, b));
ASSERT_NEAR(r, 5.0, 1.0E-5);
r := NORM_X(0.0, 2.5, 10.0);      (* positional: MIN, VALUE, MAX *)
ASSERT_NEAR(r, 0.25, 1.0E-6);
END_TEST

TEST 'SCALE_R maps IN_MIN..IN_MAX to OUT_MIN..OUT_MAX'
VAR r : REAL; END_VAR
r := SCALE_R(IN := 12.0, IN_MIN := 4.0, IN_MAX := 20.0, OUT_MIN := 0.0, OUT_MAX := 160.0);
ASSERT_NEAR(r, 80.0, 1.0E-4);
r := SCALE_R(IN := 25.0, IN_MIN := 0.0, IN_MAX := 100.0, OUT_MIN := 100.0, OUT_MAX := 0.0);
ASSERT_NEAR(r, 75.0, 1.0E-4);
r := SCALE_R(IN := 1.0, IN_MIN := 2.0, IN_MAX := 2.0, OUT_MIN := 9.0, OUT_MAX := 10.0);
ASSERT_EQ(r, 9.0);
END_TEST

TEST 'AI_SCALE: the textbook example and the S7 pressure transmitter'
VAR ai : AI_SCALE; tx : AI_SCALE; word : INT := 13824; END_VAR
ai(IN := 512, LO := -20.0, HI := 220.0, RANGE := '0-20mA', CONVENTION := 'book', BITS := 12);
ASSERT_NEAR(ai.VALUE, 10.0, 1.0E-5);
ASSERT_FALSE(ai.ERROR);
tx(IN := word, LO := 0.0, HI := 160.0, RANGE := '4-20mA', CONVENTION := 's7');
ASSERT_NEAR(tx.VALUE, 80.0, 1.0E-4);
tx(IN := 32767);
ASSERT_TRUE(tx.WIRE_BREAK);
ASSERT_TRUE(tx.ERROR);
ASSERT_NEAR(tx.VALUE, 80.0, 1.0E-4);
END_TEST

TEST 'AO_SCALE: 80 bar -> 13824, clamped above 160 bar'
VAR ao : AO_SCALE; q : INT; END_VAR
ao(IN := 80.0, LO := 0.0, HI := 160.0, RANGE := '4-20mA', CONVENTION := 's7');
q := ao.OUT;
ASSERT_EQ(q, 13824);
ao(IN := 170.0);
ASSERT_EQ(ao.OUT, 27648);
ASSERT_TRUE(ao.LIMITED);
END_TEST
"""


def test_scaling_from_st():
    run_st(ST_SCALING)
