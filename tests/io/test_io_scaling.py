"""Scaling between engineering units, signals and counts (plclab.io.scaling)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plclab.errors import PlcError
from plclab.io.scaling import (
    SIGNAL_RANGES,
    Status,
    count_format,
    counts_status,
    counts_to_eng,
    counts_to_signal,
    eng_resolution,
    eng_to_counts,
    eng_to_signal,
    resolution,
    signal_range,
    signal_status,
    signal_to_counts,
    signal_to_eng,
)

# ----------------------------------------------------------------- textbook numbers


def test_book_worked_example_512_counts_is_10_degC() -> None:
    # 001 lines 1153-1160: 0-20 mA, -20..+220 degC, 12-bit ADC, N = 512 -> 10 degC
    assert counts_to_eng(512, -20.0, 220.0, convention="book", bits=12) == 10.0
    assert eng_to_counts(10.0, -20.0, 220.0, convention="book", bits=12) == 512


def test_book_divides_by_2_to_the_n() -> None:
    assert count_format("book", bits=8).full == 256
    assert count_format("book", bits=10).full == 1024
    assert count_format("book", bits=12).full == 4096
    assert count_format("full", bits=12).full == 4095


def test_logo_reads_0_to_1000() -> None:
    assert count_format("logo").full == 1000
    assert signal_to_counts(10.0, "0-10V", convention="logo") == 1000
    assert signal_to_counts(12.0, "0-10V", convention="logo") == 1000  # clipped
    assert counts_to_eng(500, 0.0, 50.0, convention="logo") == 25.0


def test_resolution_examples_of_the_book() -> None:
    # 0-10 V, 12 bit: 10 / 4096 = 2.44 mV; +-10 V, 14 bit: 20 / 16384 = 1.22 mV
    assert resolution("0-10V", 12) == pytest.approx(2.44e-3, abs=5e-6)
    assert resolution("+-10V", 14) == pytest.approx(1.22e-3, abs=5e-6)
    assert resolution("0-10V", 12) == 10.0 / 4096
    assert resolution("0-10V", 12, convention="full") == 10.0 / 4095


def test_s7_pressure_transmitter_0_to_160_bar() -> None:
    # 001 lines 3435-3513: 4-20 mA = 0..27648 counts -> 0..160 bar
    assert counts_to_eng(0, 0.0, 160.0, convention="s7") == 0.0
    assert counts_to_eng(13824, 0.0, 160.0, convention="s7") == 80.0
    assert counts_to_eng(27648, 0.0, 160.0, convention="s7") == 160.0
    assert eng_to_counts(80.0, 0.0, 160.0, convention="s7") == 13824
    assert signal_to_counts(eng_to_signal(80.0, 0.0, 160.0, "4-20mA"), "4-20mA") == 13824


def test_book_20_percent_offset_on_a_0_20mA_input() -> None:
    # 001 lines 7300-7325: live zero 4 mA on an S7 0-20 mA input reads 5530 counts,
    # y = (N - 5530) * 100 / 22118
    n4 = signal_to_counts(4.0, "0-20mA", convention="s7")
    n20 = signal_to_counts(20.0, "0-20mA", convention="s7")
    assert (n4, n20) == (5530, 27648)
    assert (n20 - 5530) * 100 / 22118 == 100.0
    n12 = signal_to_counts(12.0, "0-20mA", convention="s7")
    assert (n12 - 5530) * 100 / 22118 == pytest.approx(50.0, abs=0.01)


# ----------------------------------------------------------------- ranges and formats


def test_signal_range_names_are_forgiving() -> None:
    assert signal_range("4-20mA") is SIGNAL_RANGES["4-20mA"]
    assert signal_range("4..20 MA").name == "4-20mA"
    assert signal_range("±10V").name == "+-10V"
    assert signal_range("-10..10V").name == "+-10V"
    assert signal_range("1-5v").live_zero
    assert signal_range("+-10V").bipolar
    assert not signal_range("0-20mA").live_zero


def test_unknown_signal_range_is_a_plc_error_that_lists_the_choices() -> None:
    with pytest.raises(PlcError) as err:
        signal_range("0-24V")
    assert err.value.code == "PLC9101"
    assert "4-20mA" in err.value.message and "0-10V" in err.value.message


@pytest.mark.parametrize(
    ("args", "code"),
    [
        (("s5",), "PLC9102"),
        (("book", 0), "PLC9103"),
        (("book", 32), "PLC9103"),
        (("s7", 16), "PLC9103"),
        (("book", 12.0), "PLC9103"),
    ],
)
def test_bad_count_format(args: tuple, code: str) -> None:
    with pytest.raises(PlcError) as err:
        count_format(*args)
    assert err.value.code == code


def test_empty_engineering_range() -> None:
    with pytest.raises(PlcError) as err:
        eng_to_counts(1.0, 5.0, 5.0)
    assert err.value.code == "PLC9104"


def test_s7_special_codes_for_4_20mA() -> None:
    assert signal_to_counts(22.81, "4-20mA") == 32504  # over-range
    assert signal_to_counts(counts_to_signal(32511, "4-20mA"), "4-20mA") == 32511  # its top
    assert signal_to_counts(22.9, "4-20mA") == 32767  # overflow
    assert signal_to_counts(1.185, "4-20mA") == -4864  # bottom of the under-range
    assert signal_to_counts(1.0, "4-20mA") == 32767  # wire break, S7-1200 with diagnostics
    assert signal_to_counts(1.0, "4-20mA", wire_break_diagnostic=False) == -32768
    assert signal_to_counts(-5.0, "0-20mA") == -32768  # no live zero: plain underflow
    assert counts_to_signal(-4864, "4-20mA") == pytest.approx(1.185, abs=5e-4)
    assert counts_to_signal(32511, "4-20mA") == pytest.approx(22.81, abs=5e-3)


def test_s7_bipolar() -> None:
    assert signal_to_counts(-10.0, "+-10V") == -27648
    assert signal_to_counts(0.0, "+-10V") == 0
    assert signal_to_counts(10.0, "+-10V") == 27648
    assert signal_to_counts(-11.5, "+-10V") == -31795
    assert signal_to_counts(-12.0, "+-10V") == -32768
    assert counts_to_eng(-13824, -100.0, 100.0, convention="s7", bipolar=True) == -50.0


def test_book_bipolar_is_offset_binary() -> None:
    # the book's formula with ymin = -10 V: 0 counts at -10 V, 2**13 at 0 V
    assert signal_to_counts(-10.0, "+-10V", convention="book", bits=14) == 0
    assert signal_to_counts(0.0, "+-10V", convention="book", bits=14) == 8192
    assert signal_to_counts(10.0, "+-10V", convention="book", bits=14) == 16383
    assert counts_to_signal(8192, "+-10V", convention="book", bits=14) == 0.0


def test_s7_resolution_left_justifies() -> None:
    codes = {signal_to_counts(4.0 + k * 0.01, "4-20mA", bits=12) for k in range(1600)}
    assert all(c % 8 == 0 for c in codes)
    assert resolution("4-20mA", 12, convention="s7") == 8 * 16.0 / 27648


def test_quantisation_rounds_to_nearest_and_clips() -> None:
    step = resolution("0-10V", 12)
    assert signal_to_counts(0.49 * step, "0-10V", convention="book", bits=12) == 0
    assert signal_to_counts(0.51 * step, "0-10V", convention="book", bits=12) == 1
    assert signal_to_counts(-1.0, "0-10V", convention="book", bits=12) == 0
    assert signal_to_counts(11.0, "0-10V", convention="book", bits=12) == 4095
    assert signal_to_counts(math.inf, "0-10V", convention="s7") == 32767


def test_limit_clamps_to_the_nominal_range() -> None:
    assert eng_to_counts(-10.0, 0.0, 100.0, convention="s7", limit=True) == 0
    assert eng_to_counts(110.0, 0.0, 100.0, convention="s7", limit=True) == 27648
    assert eng_to_counts(110.0, 0.0, 100.0, convention="s7") == 30413


def test_inverted_engineering_range() -> None:
    # 100 % signal = 0 % opening
    assert counts_to_eng(0, 100.0, 0.0, convention="s7") == 100.0
    assert eng_to_counts(25.0, 100.0, 0.0, convention="s7") == 20736
    assert signal_to_eng(eng_to_signal(30.0, 100.0, 0.0, "0-10V"), 100.0, 0.0, "0-10V") == 30.0


# ----------------------------------------------------------------- status bits


def test_ne43_status_bits() -> None:
    assert signal_status(12.0, "4-20mA").ok
    assert signal_status(3.9, "4-20mA").flags() == ("underrange",)
    assert signal_status(3.6, "4-20mA").flags() == ("wire_break", "underrange")
    assert signal_status(0.0, "4-20mA").wire_break
    assert signal_status(20.5, "4-20mA").flags() == ("overrange",)
    assert signal_status(21.0, "4-20mA").flags() == ("short_circuit", "overrange")
    assert signal_status(0.85, "1-5V").wire_break


def test_voltage_wire_break_is_invisible() -> None:
    # 001 ~7240: with 0-10 V a broken wire just reads as the minimum
    assert signal_status(0.0, "0-10V", convention="book").ok
    assert signal_status(0.0, "0-20mA", convention="s7").ok


def test_status_with_a_convention_reports_under_and_overflow() -> None:
    st_ = signal_status(0.0, "4-20mA", convention="s7")
    assert st_.wire_break and st_.underflow and not st_.overflow
    st_ = signal_status(25.0, "4-20mA", convention="s7")
    assert st_.short_circuit and st_.overflow
    assert signal_status(10.5, "0-10V", convention="book").overflow
    assert not signal_status(10.5, "0-10V").overflow  # no convention, no ADC bits


def test_counts_status() -> None:
    assert counts_status(13824) == Status()
    assert counts_status(-100).flags() == ("underrange",)
    assert counts_status(28000).flags() == ("overrange",)
    assert counts_status(32767).flags() == ("overflow",)
    assert counts_status(32767, live_zero=True).flags() == ("wire_break", "overflow")
    assert counts_status(-32768).flags() == ("underflow",)
    assert counts_status(-30000, bipolar=True).flags() == ("underrange",)
    # a clipping ADC cannot tell a broken wire from the range minimum
    assert counts_status(0, convention="book", live_zero=True).ok


# ----------------------------------------------------------------- properties

conventions = st.sampled_from(["book", "full", "s7", "logo"])
finite = st.floats(min_value=-1e4, max_value=1e4, allow_nan=False)


@st.composite
def eng_cases(draw):
    convention = draw(conventions)
    if convention == "s7":
        bits = draw(st.integers(8, 15))
    elif convention == "logo":
        bits = None
    else:
        bits = draw(st.integers(4, 16))
    lo = draw(finite)
    width = draw(st.floats(min_value=1e-2, max_value=1e4))
    hi = lo + width * draw(st.sampled_from([1.0, -1.0]))
    value = draw(st.floats(min_value=0.0, max_value=1.0)) * (hi - lo) + lo
    bipolar = draw(st.booleans())
    return convention, bits, lo, hi, value, bipolar


@settings(database=None)
@given(eng_cases())
def test_round_trip_eng_counts_eng_within_one_step(case) -> None:
    convention, bits, lo, hi, value, bipolar = case
    kw = {"convention": convention, "bits": bits, "bipolar": bipolar}
    counts = eng_to_counts(value, lo, hi, **kw)
    back = counts_to_eng(counts, lo, hi, **kw)
    step = eng_resolution(lo, hi, **kw)
    assert abs(back - value) <= step * (1 + 1e-9) + 1e-9 * abs(value)
    fmt = count_format(convention, bits, bipolar)
    assert fmt.min_code <= counts <= fmt.max_code
    assert counts % fmt.step == 0


@settings(database=None)
@given(
    st.sampled_from(sorted(SIGNAL_RANGES)),
    conventions,
    st.floats(min_value=0.0, max_value=1.0),
)
def test_round_trip_signal_counts_signal(name: str, convention: str, fraction: float) -> None:
    rng = signal_range(name)
    x = rng.from_fraction(fraction)
    counts = signal_to_counts(x, name, convention=convention)
    assert abs(counts_to_signal(counts, name, convention=convention) - x) <= resolution(
        name, convention=convention
    ) * (1 + 1e-9)


@settings(database=None)
@given(
    st.floats(min_value=-1.0, max_value=2.0),
    st.floats(min_value=-1.0, max_value=2.0),
    conventions,
)
def test_counts_are_monotonic_in_the_signal(a: float, b: float, convention: str) -> None:
    lo, hi = sorted((a, b))
    fmt = count_format(convention)
    ca = signal_to_counts(lo * 20.0, "0-20mA", convention=convention)
    cb = signal_to_counts(hi * 20.0, "0-20mA", convention=convention)
    special = {fmt.overflow_code, fmt.underflow_code}
    if ca not in special and cb not in special:
        assert ca <= cb
