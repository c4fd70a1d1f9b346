"""Analog input and output channels (plclab.io.analog)."""

import math
import statistics

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plclab.errors import PlcError
from plclab.io import AnalogInput, AnalogOutput, LinearTransmitter, counts_status

# ----------------------------------------------------------------- the chain


def test_s7_pressure_channel() -> None:
    ai = AnalogInput(lo=0.0, hi=160.0, signal="4-20mA", convention="s7")
    assert ai.sample(0.0, 80.0) == 13824
    assert ai.signal == 12.0
    assert ai.eng == 80.0
    assert ai.status.ok
    assert ai.sample(0.1, 0.0) == 0
    assert ai.sample(0.2, 160.0) == 27648


def test_book_example_as_a_channel() -> None:
    ai = AnalogInput(lo=-20.0, hi=220.0, signal="0-20mA", convention="book", bits=12)
    assert ai.sample(0.0, 10.0) == 512
    assert ai.eng == 10.0
    assert ai.resolution == pytest.approx(240.0 / 4096)


def test_transmitter_saturates_before_the_adc_overflows() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0)
    ai.sample(0.0, 200.0)
    assert ai.signal == 20.5
    assert ai.status.flags() == ("overrange",)
    ai2 = AnalogInput(lo=0.0, hi=100.0, transmitter=LinearTransmitter(0, 100, saturate=False))
    assert ai2.sample(0.0, 200.0) == 32767
    assert ai2.status.overflow


def test_4_20mA_transmitter_on_a_0_20mA_input() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, signal="0-20mA", convention="s7", transmitter="4-20mA")
    assert ai.sample(0.0, 0.0) == 5530
    assert ai.sample(0.1, 100.0) == 27648
    assert ai.resolution == pytest.approx(100.0 * 20.0 / 16.0 / 27648)


def test_signal_kinds_must_match() -> None:
    with pytest.raises(PlcError) as err:
        AnalogInput(signal="0-10V", transmitter="4-20mA")
    assert err.value.code == "PLC9108"
    with pytest.raises(PlcError) as err:
        AnalogInput(transmitter=42)  # type: ignore[arg-type]
    assert err.value.code == "PLC9108"


@pytest.mark.parametrize(
    ("kwargs", "code"),
    [
        ({"signal": "4-40mA"}, "PLC9101"),
        ({"convention": "s5"}, "PLC9102"),
        ({"convention": "book", "bits": 40}, "PLC9103"),
        ({"lo": 1.0, "hi": 1.0}, "PLC9104"),
        ({"hi": math.inf}, "PLC9104"),
        ({"noise": -1.0}, "PLC9105"),
        ({"tau": -0.1}, "PLC9105"),
        ({"sample_period": math.nan}, "PLC9105"),
    ],
)
def test_bad_configuration(kwargs: dict, code: str) -> None:
    with pytest.raises(PlcError) as err:
        AnalogInput(**kwargs)
    assert err.value.code == code


def test_time_must_not_go_backwards() -> None:
    ai = AnalogInput()
    ai.sample(1.0, 0.0)
    with pytest.raises(PlcError) as err:
        ai.sample(0.5, 0.0)
    assert err.value.code == "PLC9109"
    ai.reset()
    ai.sample(0.5, 0.0)  # fine after a reset


# ----------------------------------------------------------------- noise


def test_noise_statistics() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, noise=2.0, seed=3)
    values = []
    for k in range(20000):
        ai.sample(k * 0.01, 50.0)
        values.append(ai.eng)
    assert statistics.fmean(values) == pytest.approx(50.0, abs=0.1)
    assert statistics.stdev(values) == pytest.approx(2.0, rel=0.03)


def test_noise_is_seeded_and_reproducible() -> None:
    def run(ai: AnalogInput) -> list[int]:
        return [ai.sample(k * 0.01, 50.0) for k in range(200)]

    a = run(AnalogInput(noise=1.0, seed=5))
    assert a == run(AnalogInput(noise=1.0, seed=5))
    assert a != run(AnalogInput(noise=1.0, seed=6))
    ai = AnalogInput(noise=1.0, seed=6)
    run(ai)
    ai.reset(5)
    assert run(ai) == a
    assert len(set(a)) > 20


def test_noise_depends_on_conversions_not_on_calls() -> None:
    coarse = AnalogInput(noise=1.0, sample_period=0.01, seed=2)
    fine = AnalogInput(noise=1.0, sample_period=0.01, seed=2)
    a = [coarse.sample(k * 0.01, 50.0) for k in range(100)]
    b = []
    for k in range(1000):
        counts = fine.sample(k * 0.001, 50.0)
        if k % 10 == 0:
            b.append(counts)
    assert a == b


# ----------------------------------------------------------------- filter and sampling


def test_filter_step_response_is_exact_for_any_call_pattern() -> None:
    tau = 0.5
    for dt in (0.001, 0.01, 0.1, 0.25):
        ai = AnalogInput(lo=0.0, hi=100.0, tau=tau)
        ai.sample(0.0, 0.0)
        t = 0.0
        while t < 2.0 - 1e-12:
            t = round(t + dt, 9)
            ai.sample(t, 100.0)
            expected = 100.0 * (1.0 - math.exp(-t / tau))
            assert ai.eng == pytest.approx(expected, abs=ai.resolution)
    one_jump = AnalogInput(lo=0.0, hi=100.0, tau=tau)
    one_jump.sample(0.0, 0.0)
    one_jump.sample(tau, 100.0)
    assert one_jump.eng == pytest.approx(100.0 * (1.0 - math.exp(-1.0)), abs=one_jump.resolution)


def test_filter_starts_settled() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, tau=10.0)
    assert ai.sample(0.0, 40.0) == eng_counts(40.0)


def eng_counts(value: float) -> int:
    return round(value / 100.0 * 27648)


def test_filter_reduces_noise_as_an_ar1_process() -> None:
    period, tau, sigma = 0.01, 0.01, 2.0
    ai = AnalogInput(lo=0.0, hi=100.0, noise=sigma, tau=tau, sample_period=period, seed=11)
    values = []
    for k in range(30000):
        ai.sample(k * period, 50.0)
        values.append(ai.eng)
    a = math.exp(-period / tau)
    expected = sigma * math.sqrt((1 - a) / (1 + a))
    assert statistics.stdev(values[100:]) == pytest.approx(expected, rel=0.05)


def test_sample_and_hold() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, sample_period=0.1)
    readings = {}
    for k in range(0, 35):
        t = k * 0.01
        readings[round(t, 3)] = ai.sample(t, t * 100.0)  # a ramp of 100 %/s
    assert readings[0.0] == readings[0.05] == readings[0.09] == 0
    assert readings[0.1] == readings[0.19] == eng_counts(10.0)
    assert readings[0.2] == eng_counts(20.0)
    assert readings[0.3] == readings[0.34] == eng_counts(30.0)


# ----------------------------------------------------------------- faults


def test_wire_break_on_a_live_zero_s7_channel() -> None:
    ai = AnalogInput(lo=0.0, hi=160.0)
    ai.sample(0.0, 80.0)
    ai.inject("wire_break")
    assert ai.sample(0.01, 80.0) == 32767
    assert ai.signal == 0.0
    assert ai.status.wire_break and ai.status.underflow and ai.status.underrange
    assert counts_status(ai.counts, live_zero=True).wire_break
    ai.clear()
    assert ai.sample(0.02, 80.0) == 13824
    assert ai.status.ok


def test_wire_break_without_the_s7_diagnostic_reads_underflow() -> None:
    ai = AnalogInput(lo=0.0, hi=160.0, wire_break_diagnostic=False)
    ai.inject("wire_break")
    assert ai.sample(0.0, 80.0) == -32768


def test_wire_break_on_a_0_10V_channel_reads_the_minimum() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, signal="0-10V", convention="book", bits=12)
    ai.sample(0.0, 50.0)
    ai.inject("wire_break")
    assert ai.sample(0.01, 50.0) == 0
    assert ai.eng == 0.0
    assert ai.status.ok  # nothing tells it from a real 0 %


def test_wire_break_on_a_book_4_20mA_channel() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, signal="4-20mA", convention="book", bits=12)
    ai.inject("wire_break")
    assert ai.sample(0.0, 50.0) == 0  # clipped: reads the range minimum
    assert ai.status.wire_break and ai.status.underflow  # the module's diagnostics know


def test_wire_break_through_the_filter() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0, tau=0.1)
    ai.sample(0.0, 50.0)  # 12 mA
    ai.inject("wire_break")
    ai.sample(0.05, 50.0)
    assert ai.signal == pytest.approx(12.0 * math.exp(-0.5))
    assert not ai.status.wire_break
    ai.sample(0.2, 50.0)  # 12 * e^-2 = 1.62 mA <= 3.6 mA
    assert ai.status.wire_break


def test_short_reads_overflow() -> None:
    ai = AnalogInput(lo=0.0, hi=160.0)
    ai.inject("short")
    assert ai.sample(0.0, 80.0) == 32767
    assert ai.status.short_circuit and ai.status.overflow and ai.status.overrange
    book = AnalogInput(lo=0.0, hi=100.0, signal="0-10V", convention="book", bits=12)
    book.inject("short")
    assert book.sample(0.0, 50.0) == 4095
    assert book.status.overflow


def test_stuck_holds_the_reading_and_looks_healthy() -> None:
    ai = AnalogInput(lo=0.0, hi=100.0)
    ai.sample(0.0, 30.0)
    ai.inject("stuck")
    readings = {ai.sample(k * 0.1, 30.0 + k) for k in range(1, 20)}
    assert readings == {eng_counts(30.0)}
    assert ai.status.ok
    ai.inject("stuck", value=75.0)
    assert ai.sample(2.0, 10.0) == eng_counts(75.0)
    ai.clear()
    assert ai.sample(2.1, 10.0) == eng_counts(10.0)


def test_unknown_fault() -> None:
    with pytest.raises(PlcError) as err:
        AnalogInput().inject("flooded")
    assert err.value.code == "PLC9106"
    assert "wire_break" in err.value.message


# ----------------------------------------------------------------- analog output


def test_analog_output_0_10V_valve() -> None:
    ao = AnalogOutput(lo=0.0, hi=100.0, signal="0-10V", convention="s7")
    assert ao.apply(0.0, 0) == 0.0
    assert ao.apply(0.1, 13824) == 50.0
    assert ao.signal == 5.0
    assert ao.apply(0.2, 27648) == 100.0
    assert ao.apply(0.3, 32767) == 100.0  # clipped at the end stop
    assert ao.signal == pytest.approx(32511 / 27648 * 10.0)
    assert ao.apply(0.4, -5000) == 0.0
    assert ao.signal == 0.0  # a unipolar output cannot go negative
    assert ao.eng_to_counts(25.0) == 6912


def test_analog_output_resolution() -> None:
    ao = AnalogOutput(lo=0.0, hi=100.0, signal="0-10V", convention="book", bits=8)
    assert ao.resolution == 100.0 / 256
    assert ao.apply(0.0, 1) == pytest.approx(100.0 / 256)
    assert ao.apply(0.1, 300) == pytest.approx(100.0 * 255 / 256)  # clipped to 255
    s7 = AnalogOutput(lo=0.0, hi=100.0, convention="s7", bits=12)
    s7.apply(0.0, 13827)
    assert s7.signal == 13824 / 27648 * 10.0  # 12-bit DAC: steps of 8 counts


def test_analog_output_faults() -> None:
    ao = AnalogOutput(lo=0.0, hi=100.0, signal="4-20mA")
    assert ao.apply(0.0, 13824) == 50.0
    ao.inject("open")
    assert ao.apply(0.1, 13824) == 0.0
    assert ao.signal == 0.0
    ao.clear()
    assert ao.apply(0.2, 13824) == 50.0
    ao.inject("stuck")
    assert ao.apply(0.3, 27648) == 50.0
    ao.inject("stuck", value=10.0)
    assert ao.apply(0.4, 27648) == 10.0
    with pytest.raises(PlcError):
        ao.inject("melted")


@settings(max_examples=300, deadline=None)
@given(values=st.lists(st.floats(-50.0, 250.0, allow_nan=False), min_size=1, max_size=20),
       conv=st.sampled_from(["s7", "book", "full", "logo"]),
       signal=st.sampled_from(["4-20mA", "0-20mA", "0-10V", "+-10V", "1-5V"]),
       wbd=st.booleans(), saturate=st.booleans())
def test_memoryless_sample_is_the_general_conversion(values: list[float], conv: str,
                                                     signal: str, wbd: bool,
                                                     saturate: bool) -> None:
    """The unrolled path of a noise-free, unfiltered channel (issue 19) converts like the
    module's general steps: transmitter -> signal_code, state included."""
    from plclab.io.scaling import signal_code

    tx = LinearTransmitter(0.0, 200.0, signal, saturate=saturate)
    ai = AnalogInput(0.0, 200.0, signal=signal, convention=conv, transmitter=tx,
                     wire_break_diagnostic=wbd)
    rng = ai.range
    for i, v in enumerate(values):
        x = rng.from_fraction((v - 0.0) / (200.0 - 0.0))
        if saturate:
            x = min(rng.sat_hi, max(rng.sat_lo, x))
        assert tx.output(v) == x
        want = signal_code(x, rng, ai.format, wbd)[0]
        assert ai.sample(i * 0.01, v) == want == ai.counts
        assert ai.signal == x
        assert ai.status == ai._diagnose(x)
