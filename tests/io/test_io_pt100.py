"""Platinum RTDs and the RTD transmitter (plclab.io.pt100)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plclab.errors import PlcError
from plclab.io import AnalogInput, signal_status
from plclab.io.pt100 import A, B, RtdTransmitter, resistance, temperature


def test_textbook_coefficients() -> None:
    # 001 ~7145: R = R0 (1 + A T + B T^2), A = 3.9083e-3, B = -5.775e-7
    assert (A, B) == (3.9083e-3, -5.775e-7)


def test_pt100_table_values() -> None:
    assert resistance(0.0) == 100.0
    assert resistance(100.0) == pytest.approx(138.5055, abs=1e-9)
    # IEC 60751 table values
    assert resistance(-200.0) == pytest.approx(18.52, abs=0.01)
    assert resistance(-100.0) == pytest.approx(60.26, abs=0.01)
    assert resistance(850.0) == pytest.approx(390.48, abs=0.01)
    assert resistance(100.0, r0=1000.0) == pytest.approx(1385.055, abs=1e-9)


def test_inverse_of_known_values() -> None:
    assert temperature(100.0) == 0.0
    assert temperature(138.5055) == pytest.approx(100.0, abs=1e-9)
    assert temperature(1385.055, r0=1000.0) == pytest.approx(100.0, abs=1e-9)


@settings(database=None)
@given(st.floats(min_value=-200.0, max_value=850.0), st.sampled_from([100.0, 500.0, 1000.0]))
def test_inverse_round_trip(t: float, r0: float) -> None:
    assert temperature(resistance(t, r0), r0) == pytest.approx(t, abs=1e-9)


@pytest.mark.parametrize("r", [0.0, -1.0, math.inf, math.nan, 1e6])
def test_impossible_resistance(r: float) -> None:
    with pytest.raises(ValueError):
        temperature(r)


def test_transmitter_is_linear_in_temperature_and_saturates() -> None:
    tx = RtdTransmitter(-50.0, 150.0)
    assert tx.output(-50.0) == pytest.approx(4.0, abs=1e-9)
    assert tx.output(50.0) == pytest.approx(12.0, abs=1e-9)
    assert tx.output(150.0) == pytest.approx(20.0, abs=1e-9)
    assert tx.output(-100.0) == 3.8  # NE43 low saturation
    assert tx.output(300.0) == 20.5  # NE43 high saturation
    assert signal_status(tx.output(-100.0), "4-20mA").flags() == ("underrange",)


@pytest.mark.parametrize("fault", ["open", "short"])
def test_sensor_fault_drives_the_fault_current(fault: str) -> None:
    tx = RtdTransmitter(-50.0, 150.0)
    tx.inject(fault)
    assert tx.output(20.0) == 3.5
    assert signal_status(tx.output(20.0), "4-20mA").wire_break
    tx.clear()
    assert tx.output(50.0) == pytest.approx(12.0, abs=1e-9)


def test_open_sensor_is_infinite_resistance() -> None:
    tx = RtdTransmitter(fault="open")
    assert tx.measured_resistance(20.0) == math.inf
    assert math.isnan(tx.measured_temperature(20.0))


def test_upscale_burnout() -> None:
    tx = RtdTransmitter(0.0, 100.0, fault_signal=21.5)
    tx.inject("open")
    assert signal_status(tx.output(20.0), "4-20mA").short_circuit


def test_two_wire_leads_read_hot_three_wire_compensates() -> None:
    two = RtdTransmitter(0.0, 100.0, wires=2, lead_ohm=0.5)
    three = RtdTransmitter(0.0, 100.0, wires=3, lead_ohm=0.5)
    assert two.measured_temperature(20.0) == pytest.approx(20.0 + 1.0 / (100 * 0.00385), abs=0.05)
    assert three.measured_temperature(20.0) == pytest.approx(20.0, abs=1e-9)


def test_voltage_output_fault_is_range_minimum() -> None:
    tx = RtdTransmitter(0.0, 100.0, signal="0-10V", fault="open")
    assert tx.output(50.0) == 0.0


@pytest.mark.parametrize(
    ("kwargs", "code"),
    [
        ({"t_lo": 100.0, "t_hi": 0.0}, "PLC9104"),
        ({"r0": 0.0}, "PLC9104"),
        ({"wires": 5}, "PLC9104"),
        ({"signal": "4-25mA"}, "PLC9101"),
        ({"fault": "melted"}, "PLC9106"),
    ],
)
def test_bad_transmitter_configuration(kwargs: dict, code: str) -> None:
    with pytest.raises(PlcError) as err:
        RtdTransmitter(**kwargs)
    assert err.value.code == code


def test_rtd_transmitter_on_an_analog_input() -> None:
    tx = RtdTransmitter(-50.0, 150.0)
    ai = AnalogInput(lo=-50.0, hi=150.0, signal="4-20mA", convention="s7", transmitter=tx)
    assert ai.sample(0.0, 50.0) == 13824
    assert ai.eng == pytest.approx(50.0)
    tx.inject("open")
    assert ai.sample(0.1, 50.0) == -864  # 3.5 mA: (3.5 - 4) / 16 * 27648
    assert ai.status.wire_break and ai.status.underrange
    assert not ai.status.underflow  # the ADC still measures 3.5 mA
