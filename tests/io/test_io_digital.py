"""Digital input and output channels (plclab.io.digital)."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plclab.errors import PlcError
from plclab.io import IEC_TYPE1_24V, DigitalInput, DigitalOutput

MS = 0.001


def press(di: DigitalInput, t_press: float, t_end: float, dt: float = 0.0001) -> None:
    """Contact open until t_press, closed afterwards; sampled every dt until t_end."""
    k = 0
    while k * dt <= t_end + 1e-12:
        t = k * dt
        di.sample(t, t >= t_press - 1e-12)
        k += 1


# ----------------------------------------------------------------- input filter


def test_filter_delays_both_edges() -> None:
    di = DigitalInput(filter_ms=3.0)
    di.sample(0.0, False)
    di.sample(0.010, True)
    di.sample(0.020, False)
    di.sample(0.040, False)
    assert di.filtered_transitions == [(0.010 + 0.003, True), (0.020 + 0.003, False)]


def test_pulse_shorter_than_the_filter_is_lost() -> None:
    di = DigitalInput(filter_ms=3.0)
    assert di.sample(0.0, False) is False
    di.sample(0.010, True)
    di.sample(0.012, False)  # a 2 ms pulse
    for k in range(13, 40):
        assert di.sample(k * MS, False) is False
    assert di.filtered_transitions == []
    assert di.raw_transitions == [(0.010, True), (0.012, False)]


def test_pulse_longer_than_the_filter_passes_with_its_width() -> None:
    di = DigitalInput(filter_ms=3.0)
    di.sample(0.0, False)
    di.sample(0.010, True)
    di.sample(0.014, False)  # a 4 ms pulse
    di.sample(0.050, False)
    (t_on, v_on), (t_off, v_off) = di.filtered_transitions
    assert (v_on, v_off) == (True, False)
    assert t_off - t_on == pytest.approx(0.004)


def test_filter_zero_passes_everything() -> None:
    di = DigitalInput(filter_ms=0.0)
    di.sample(0.0, False)
    assert di.sample(0.001, True) is True
    assert di.sample(0.0011, False) is False


def test_initial_state_has_no_edge() -> None:
    di = DigitalInput()
    assert di.sample(0.0, True) is True
    assert di.raw_transitions == [] and di.filtered_transitions == []
    assert di.initial is True


# ----------------------------------------------------------------- contact bounce


def test_one_press_bounces_but_the_plc_sees_one_edge() -> None:
    di = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=1)
    t_press = 0.010
    press(di, t_press, 0.030)
    raw = di.raw_transitions
    assert len(raw) >= 3  # several raw toggles...
    assert len(raw) % 2 == 1  # ...ending at the new value
    assert [v for _, v in raw] == [i % 2 == 0 for i in range(len(raw))]
    assert raw[0][0] == pytest.approx(t_press)
    assert all(t_press - 1e-12 <= t <= t_press + 0.005 for t, _ in raw)  # within bounce_ms
    # exactly one filtered transition, after bounce + filter delay, at an exact time
    assert di.filtered_transitions == [(raw[-1][0] + 0.003, True)]
    assert di.filtered_transitions[0][0] <= t_press + 0.005 + 0.003 + 1e-12


def test_without_the_filter_the_plc_sees_every_bounce() -> None:
    di = DigitalInput(filter_ms=0.0, bounce_ms=5.0, seed=1)
    press(di, 0.010, 0.030)
    edges = di.filtered_transitions
    assert edges == di.raw_transitions
    rising = [t for t, v in edges if v]
    assert len(rising) >= 2  # a counter would count this one press several times


def test_release_bounces_too() -> None:
    di = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=4)
    di.sample(0.0, True)
    di.sample(0.010, False)
    di.sample(0.050, False)
    raw = di.raw_transitions
    assert len(raw) >= 3 and raw[-1][1] is False
    assert di.filtered_transitions == [(raw[-1][0] + 0.003, False)]


def test_result_does_not_depend_on_how_often_sample_is_called() -> None:
    fine = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=9)
    press(fine, 0.010, 0.050, dt=0.0001)
    coarse = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=9)
    coarse.sample(0.0, False)
    coarse.sample(0.010, True)
    coarse.sample(0.050, True)
    assert coarse.raw_transitions == fine.raw_transitions
    assert coarse.filtered_transitions == fine.filtered_transitions


def test_scan_sees_the_bit_at_the_exact_time() -> None:
    di = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=9)
    di.sample(0.0, False)
    di.sample(0.010, True)
    di.sample(0.100, True)
    t_edge = di.filtered_transitions[0][0]
    other = DigitalInput(filter_ms=3.0, bounce_ms=5.0, seed=9)
    other.sample(0.0, False)
    other.sample(0.010, True)
    assert other.sample(t_edge - 1e-6, True) is False
    assert other.sample(t_edge, True) is True


@settings(max_examples=60, deadline=None, database=None)
@given(
    seed=st.integers(0, 10_000),
    bounce_ms=st.floats(min_value=0.5, max_value=5.0),
    extra_ms=st.floats(min_value=0.0, max_value=5.0),
)
def test_a_filter_longer_than_the_bounce_gives_one_edge(
    seed: int, bounce_ms: float, extra_ms: float
) -> None:
    filter_ms = bounce_ms + extra_ms
    di = DigitalInput(filter_ms=filter_ms, bounce_ms=bounce_ms, seed=seed)
    di.sample(0.0, False)
    di.sample(0.010, True)
    di.sample(0.100, True)
    raw = di.raw_transitions
    assert 3 <= len(raw) <= 9
    assert raw[-1][0] - raw[0][0] <= bounce_ms * MS + 1e-12
    ((t_edge, value),) = di.filtered_transitions
    assert value is True
    assert t_edge == pytest.approx(raw[-1][0] + filter_ms * MS, abs=1e-12)


def test_press_during_a_bounce_cuts_it_short() -> None:
    di = DigitalInput(filter_ms=3.0, bounce_ms=5.0, bounces=4, seed=0)
    di.sample(0.0, False)
    di.sample(0.010, True)
    di.sample(0.0105, False)  # released after 0.5 ms
    di.sample(0.050, False)
    raw = di.raw_transitions
    values = [v for _, v in raw]
    assert all(a != b for a, b in zip(values, values[1:], strict=False))  # alternating
    assert all(t2 > t1 for (t1, _), (t2, _) in zip(raw, raw[1:], strict=False))
    assert raw[-1][1] is False
    assert di.value is False
    assert all(v is False for _, v in di.filtered_transitions)  # never a stable TRUE


def test_bounces_fixed_count() -> None:
    di = DigitalInput(bounce_ms=2.0, bounces=2, filter_ms=3.0)
    di.sample(0.0, False)
    di.sample(0.01, True)
    di.sample(0.02, True)
    assert len(di.raw_transitions) == 5


def test_raw_series_at_1ms() -> None:
    di = DigitalInput(filter_ms=3.0)
    di.sample(0.0, False)
    di.sample(0.0025, True)
    di.sample(0.010, True)
    series = di.raw_series(0.0, 0.005)
    assert [v for _, v in series] == [False, False, False, True, True, True]
    assert di.raw_at(0.0025) is True and di.raw_at(0.0024) is False


# ----------------------------------------------------------------- threshold


def test_threshold_with_hysteresis() -> None:
    di = DigitalInput(filter_ms=0.0, threshold=IEC_TYPE1_24V)
    assert di.sample(0.0, 0.0) is False
    assert di.sample(0.01, 10.0) is False  # undefined band: keeps its state
    assert di.sample(0.02, 24.0) is True
    assert di.sample(0.03, 10.0) is True
    assert di.sample(0.04, 4.0) is False


def test_single_threshold() -> None:
    di = DigitalInput(filter_ms=0.0, threshold=2.0)
    assert di.sample(0.0, 1.9) is False
    assert di.sample(0.1, 2.0) is True


# ----------------------------------------------------------------- faults and errors


def test_open_and_stuck_faults() -> None:
    di = DigitalInput(filter_ms=3.0, bounce_ms=5.0)
    di.sample(0.0, True)
    di.inject("open")
    di.sample(0.010, True)
    assert di.raw_transitions[-1] == (0.010, False)  # no bounce on a broken wire
    assert di.sample(0.0129, True) is True  # the filter still delays it
    assert di.sample(0.020, True) is False
    di.inject("stuck_1")
    di.sample(0.030, False)
    assert di.sample(0.040, False) is True
    di.clear()
    di.sample(0.050, False)
    assert di.sample(0.060, False) is False


@pytest.mark.parametrize(
    ("kwargs", "code"),
    [
        ({"filter_ms": -1.0}, "PLC9105"),
        ({"bounce_ms": -1.0}, "PLC9105"),
        ({"bounces": (3, 1)}, "PLC9105"),
        ({"threshold": (15.0, 5.0)}, "PLC9105"),
    ],
)
def test_bad_input_configuration(kwargs: dict, code: str) -> None:
    with pytest.raises(PlcError) as err:
        DigitalInput(**kwargs)
    assert err.value.code == code


def test_input_errors() -> None:
    di = DigitalInput()
    with pytest.raises(PlcError) as err:
        di.inject("stuck_0")
    assert err.value.code == "PLC9106"
    di.sample(1.0, False)
    with pytest.raises(PlcError) as err:
        di.sample(0.0, False)
    assert err.value.code == "PLC9109"


# ----------------------------------------------------------------- outputs


def test_transistor_is_instant() -> None:
    do = DigitalOutput()
    assert do.apply(0.0, True) is True
    assert do.apply(0.001, False) is False
    assert do.switch_times == [(0.0, True), (0.001, False)]


def test_relay_delays_and_counts_operations() -> None:
    do = DigitalOutput("relay", close_ms=10.0, open_ms=5.0)
    assert do.apply(0.0, True) is False
    assert do.apply(0.0099, True) is False
    assert do.apply(0.010, True) is True
    assert do.apply(0.100, False) is True
    assert do.apply(0.1049, False) is True
    assert do.apply(0.105, False) is False
    assert do.operations == 1
    assert do.switch_times == [(0.010, True), (pytest.approx(0.105), False)]


def test_relay_is_exact_for_coarse_calls() -> None:
    do = DigitalOutput("relay")
    do.apply(0.0, True)
    do.apply(0.5, False)  # closed at 0.010 although nobody looked
    do.apply(1.0, False)
    assert do.switch_times == [(0.010, True), (0.505, False)]


def test_relay_wear_over_many_cycles() -> None:
    do = DigitalOutput("relay")
    for k in range(1000):
        do.apply(k * 0.1, k % 2 == 0)  # 100 ms on, 100 ms off
    do.apply(100.0, False)
    assert do.operations == 500
    stats = do.chatter_stats()
    assert stats.switchings == 1000
    assert stats.per_minute == pytest.approx(600.0)
    assert stats.min_on == pytest.approx(0.1 - 0.010 + 0.005)
    assert stats.min_off == pytest.approx(0.1 - 0.005 + 0.010)


def test_relay_swallows_pulses_shorter_than_its_delay() -> None:
    do = DigitalOutput("relay")
    for k in range(100):
        do.apply(k * 0.008, k % 2 == 0)  # chattering at 4 ms: faster than 10 ms pull-in
    assert do.operations == 0


def test_welded_and_open_coil() -> None:
    do = DigitalOutput("relay")
    do.apply(0.0, True)
    do.apply(0.05, True)
    do.inject("welded")
    do.apply(0.1, False)
    assert do.apply(0.5, False) is True
    do.clear()
    do.apply(0.6, False)
    assert do.apply(0.7, False) is False
    do.inject("open_coil")
    assert do.apply(0.8, True) is False
    assert do.apply(0.9, True) is False
    assert do.operations == 1  # fault changes are not wear
    do.clear()
    do.apply(1.0, True)
    assert do.apply(1.1, True) is True
    assert do.operations == 2


def test_welded_closes_an_open_contact() -> None:
    do = DigitalOutput()
    do.apply(0.0, False)
    do.inject("welded")
    assert do.apply(0.1, False) is True
    assert do.operations == 0


def test_chatter_stats_empty() -> None:
    stats = DigitalOutput().chatter_stats()
    assert (stats.switchings, stats.per_minute, stats.min_on, stats.min_off) == (0, 0.0, None, None)


def test_output_errors() -> None:
    with pytest.raises(PlcError) as err:
        DigitalOutput("thyristor")
    assert err.value.code == "PLC9107"
    with pytest.raises(PlcError) as err:
        DigitalOutput("relay", close_ms=-1.0)
    assert err.value.code == "PLC9105"
    with pytest.raises(PlcError) as err:
        DigitalOutput().inject("melted")
    assert err.value.code == "PLC9106"
