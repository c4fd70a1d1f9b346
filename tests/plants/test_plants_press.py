"""Plastic press: encoder dosing, end switches, safety events, temperature loop."""

from __future__ import annotations

import pytest

from plants import Press

SAFETY = {"moved_without_two_hands", "curtain_violation", "crash"}


def _safety(p: Press) -> list[str]:
    return [e.kind for e in p.drain_events() if e.kind in SAFETY]


class EdgeCounter:
    def __init__(self) -> None:
        self.prev = False
        self.n = 0

    def __call__(self, x: bool) -> int:
        if x and not self.prev:
            self.n += 1
        self.prev = x
        return self.n


def test_encoder_count_is_exact_when_sampled_fast() -> None:
    p = Press()
    count = EdgeCounter()
    p["HAND_L"] = p["HAND_R"] = True
    p["DOWN"] = True
    target = 57
    while count(p["ENCODER_PULSE"]) < target:
        p.step(0.002)
    p["DOWN"] = False
    for _ in range(200):
        count(p["ENCODER_PULSE"])
        p.step(0.002)
    assert count.n == p.snapshot()["encoder_count"]
    assert p["POSITION"] == pytest.approx(target / p.pulses_per_mm, abs=1.5)
    assert p.snapshot()["dosed_volume"] == pytest.approx(p["POSITION"] * 0.1 * p.piston_area)
    assert _safety(p) == []


def test_slow_sampling_loses_pulses() -> None:
    p = Press(pulses_per_mm=2.0)
    count = EdgeCounter()
    p["HAND_L"] = p["HAND_R"] = True
    p["DOWN"] = True
    for _ in range(100):  # 3 s, sampled every 30 ms: a half period is 10 ms
        count(p["ENCODER_PULSE"])
        p.step(0.03)
    assert count.n < 0.8 * p.snapshot()["encoder_count"]


def test_end_switches_and_crash() -> None:
    p = Press()
    assert p["TOP"] is True and p["BOTTOM"] is False
    p["HAND_L"] = p["HAND_R"] = True
    p["DOWN"] = True
    while not p["BOTTOM"]:
        p.step(0.002)
    p["DOWN"] = False
    p.step(0.5)
    assert p["BOTTOM"] is True
    assert "crash" not in [e.kind for e in p.drain_events()]
    p["UP"] = True
    p.step(10.0)  # ignores TOP: crashes into the top stop
    assert p["TOP"] is True and p["POSITION"] == 0.0
    kinds = [e.kind for e in p.drain_events()]
    assert kinds.count("crash") == 1
    assert p.snapshot()["crashes"] == 1.0


def test_two_hand_and_curtain_violations() -> None:
    p = Press()
    p["HAND_L"] = True
    p["DOWN"] = True
    p.step(0.5)
    assert _safety(p) == ["moved_without_two_hands"]
    p["DOWN"] = False
    p.step(0.5)
    p["HAND_R"] = True
    p["DOWN"] = True
    p.step(0.5)
    assert _safety(p) == []
    p["LIGHT_CURTAIN"] = False
    p.step(0.04)  # within the reaction allowance
    assert _safety(p) == []
    p.step(0.02)
    assert _safety(p) == ["curtain_violation"]
    p["DOWN"] = False
    p["LIGHT_CURTAIN"] = True
    p.step(0.5)
    p["HAND_L"] = False
    p["DOWN"] = True
    p.step(0.03)  # a hand left, the PLC stops within a scan or two: no violation
    p["DOWN"] = False
    p.step(0.5)
    assert _safety(p) == []


def test_estop_is_hardwired() -> None:
    p = Press()
    p["HAND_L"] = p["HAND_R"] = True
    p["DOWN"] = True
    p.step(1.0)
    pos = p["POSITION"]
    p["E_STOP"] = False
    p.step(1.0)
    assert p["POSITION"] == pytest.approx(pos, abs=1.5)
    assert p.snapshot()["velocity"] == 0.0


def test_faults() -> None:
    p = Press()
    p.inject("down_valve_stuck")
    p.step(1.0)
    assert p["POSITION"] > 10.0
    p.clear("down_valve_stuck")
    p.inject("encoder_fail")
    frozen = p["ENCODER_PULSE"]
    p["DOWN"] = True
    for _ in range(500):
        p.step(0.002)
        assert p["ENCODER_PULSE"] == frozen
    p.clear("encoder_fail")
    p.inject("bottom_switch_fail")
    p.step(10.0)
    assert p["BOTTOM"] is False and "crash" in [e.kind for e in p.drain_events()]
    p.inject("heater_fail")
    p["HEATER"] = True
    p.step(100.0)
    assert p["TEMP"] == pytest.approx(p.t_amb)


def test_closed_loop_heat_then_dose_by_pulses() -> None:
    """Two concurrent tasks: keep 200 +- 5 degC, and run dosing strokes of 40 pulses."""
    p = Press()
    dt = 0.002
    count = EdgeCounter()
    state = "wait"
    start = 0
    doses = []
    for _ in range(int(600 / dt)):
        t = p["TEMP"]
        if t < 195.0:
            p["HEATER"] = True
        elif t > 205.0:
            p["HEATER"] = False
        n = count(p["ENCODER_PULSE"])
        if state == "wait" and t > 195.0 and p["TOP"]:
            p["HAND_L"] = p["HAND_R"] = True  # the operator
            state, start = "down", n
            p["DOWN"] = True
        elif state == "down" and n - start >= 40:
            p["DOWN"] = False
            p["HAND_L"] = p["HAND_R"] = False
            state = "settle"
            settle = 0
        elif state == "settle":
            settle += 1
            if settle > 100:
                doses.append(p["POSITION"])
                state = "up"
                p["UP"] = True
        elif state == "up" and p["TOP"]:
            p["UP"] = False
            state = "wait"
        p.step(dt)
    assert len(doses) >= 3
    for d in doses:
        assert d == pytest.approx(40.0, abs=1.5)
    bad = {"crash", "moved_without_two_hands", "curtain_violation", "cold_extrusion", "overheat"}
    assert not [e for e in p.drain_events() if e.kind in bad]


def test_initial_temperature_t0() -> None:
    """t0 starts the plastic at its own temperature; without it the press starts at ambient."""
    p = Press(t_amb=20.0)
    p.reset()
    assert p["TEMP"] == pytest.approx(20.0)
    p = Press(t_amb=20.0, t0=150.0, heat_capacity=1000.0)
    p.reset()
    assert p["TEMP"] == pytest.approx(150.0)
    p.step(1.0)  # no heating: it cools towards ambient, ua (150 - 20) / C = 0.52 K/s
    assert p["TEMP"] == pytest.approx(150.0 - 0.52, abs=0.01)


def test_lab_heat_balance_matches_the_readme_rates_and_the_energy_integral() -> None:
    """The press-safety lab's container (1 kJ/K, 1.5 kW, 4 W/K to 20 degC) at 210 degC: it
    cools by 4 * 190 / 1000 = 0.76 K/s with the heater off and warms by (1500 - 760) / 1000 =
    0.74 K/s with it on (the README's 'about 0.75 K/s'). Over 20 s the energy balance holds:
    C * dT = P * t_on - UA * integral(T - T_amb) dt."""
    import math

    kw = dict(heat_capacity=1000.0, heater_power=1500.0, ua=4.0, t_amb=20.0, t0=210.0)
    p = Press(**kw)
    p.reset()
    p.step(0.1)
    assert (p["TEMP"] - 210.0) / 0.1 == pytest.approx(-0.76, abs=0.005)
    p = Press(**kw)
    p.reset()
    p["HEATER"] = True
    p.step(0.1)
    assert (p["TEMP"] - 210.0) / 0.1 == pytest.approx(0.74, abs=0.005)
    # 10 s on, 10 s off: sum the losses step by step and compare with the stored heat
    p = Press(**kw)
    p.reset()
    loss, dt = 0.0, 0.01
    for k in range(2000):
        p["HEATER"] = k < 1000
        t_before = p["TEMP"]
        p.step(dt)
        loss += 4.0 * ((t_before + p["TEMP"]) / 2 - 20.0) * dt
    stored = 1000.0 * (p["TEMP"] - 210.0)
    assert stored == pytest.approx(1500.0 * 10.0 - loss, rel=1e-4)
    # and the closed form of the cooling half: T = T_amb + (T1 - T_amb) exp(-UA t / C)
    p = Press(**kw)
    p.reset()
    p.step(10.0)
    assert p["TEMP"] == pytest.approx(20.0 + 190.0 * math.exp(-0.04), abs=1e-6)


def test_lab_dose_is_sixty_pulses_for_sixty_mm_and_its_time_at_25_mm_per_s() -> None:
    """60 mm at 25 mm/s take 2.4 s (+ the 30 ms valve lag); the encoder gives one rising edge
    per mm, so a PLC sampling every 10 ms (half a pulse lasts 20 ms) counts all 60."""
    p = Press(end_switch_margin=5.0)
    p.reset()
    count = EdgeCounter()
    p["DOWN"] = True
    t = 0.0
    while count(bool(p["ENCODER_PULSE"])) < 60:
        p.step(0.01)
        t += 0.01
    assert t == pytest.approx(60.0 / 25.0 + 0.03, abs=0.03)
    assert p["POSITION"] == pytest.approx(60.0, abs=0.6)
