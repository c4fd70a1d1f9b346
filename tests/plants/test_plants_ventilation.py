"""Ventilation: two of three fans, standby fan, power-off on double fault, thermal model."""

from __future__ import annotations

import pytest

from plants import Ventilation


class FanLogic:
    """The textbook's fan control (Fig. 119) as a Python 'PLC'."""

    def __init__(self) -> None:
        self.cyclek = False

    def scan(self, p: Ventilation) -> None:
        f1, f2, f3 = p["FAULT1"], p["FAULT2"], p["FAULT3"]
        n_faults = f1 + f2 + f3
        self.cyclek = (p["START"] or self.cyclek) and p["STOP"] and p["MS"] and n_faults < 2
        on = self.cyclek
        p["MAIN_POWER"] = on
        p["FAN2"] = on and not f2
        p["FAN3"] = on and not f3
        p["FAN1"] = on and (f2 or f3) and not f1
        for i in (1, 2, 3):
            p[f"FAN{i}_LAMP"] = p[f"FAN{i}"]
        p["RUN_LAMP"] = on
        blink = int(p.time * 10) % 2 == 0  # 5 Hz
        p["FAULT_LAMP"] = n_faults == 1 or (n_faults >= 2 and blink)


def _run(p: Ventilation, plc: FanLogic | None, seconds: float, dt: float = 0.1) -> None:
    for _ in range(int(round(seconds / dt))):
        if plc is not None:
            plc.scan(p)
        p.step(dt)


def _start(p: Ventilation, plc: FanLogic) -> None:
    p["MS"] = True
    p["START"] = True
    _run(p, plc, 0.5)
    p["START"] = False


def test_two_fans_run_and_standby_takes_over() -> None:
    p = Ventilation()
    plc = FanLogic()
    _start(p, plc)
    _run(p, plc, 30.0)
    s = p.snapshot()
    speeds = (s["fan1_speed"], s["fan2_speed"], s["fan3_speed"])
    assert speeds == pytest.approx((0.0, 1.0, 1.0), abs=1e-3)
    assert p["CURRENT2"] == pytest.approx(p.fan_current, rel=1e-3)
    p.inject("fan2_fail")
    assert p["FAULT2"] is True
    _run(p, plc, 60.0)
    s = p.snapshot()
    speeds = (s["fan1_speed"], s["fan2_speed"], s["fan3_speed"])
    assert speeds == pytest.approx((1.0, 0.0, 1.0), abs=0.01)
    assert p["CURRENT2"] == 0.0 and p["FAULT_LAMP"] is True
    p.inject("fan3_fail")
    _run(p, plc, 1.0)
    assert p["MAIN_POWER"] is False
    _run(p, plc, 60.0)
    assert p.snapshot()["airflow"] == pytest.approx(p.infiltration, abs=0.05)
    assert "fans_stopped" in [e.kind for e in p.drain_events()]


def test_inrush_current_on_start() -> None:
    p = Ventilation()
    p["MAIN_POWER"] = True
    p["FAN3"] = True
    p.step(0.1)
    assert p["CURRENT3"] > 3 * p.fan_current
    _run(p, None, 60.0)
    assert p["CURRENT3"] == pytest.approx(p.fan_current)


def test_no_main_power_no_fans() -> None:
    p = Ventilation()
    for i in (1, 2, 3):
        p[f"FAN{i}"] = True
    _run(p, None, 30.0)
    assert p.snapshot()["airflow"] == p.infiltration
    assert p["CURRENT1"] == 0.0


def test_more_fans_keep_it_cooler_and_no_fans_overheat() -> None:
    temps = {}
    for n in (0, 1, 2, 3):
        p = Ventilation(weather_sigma=0.0, start_hour=10.0)
        p["MAIN_POWER"] = True
        for i in range(1, n + 1):
            p[f"FAN{i}"] = True
        _run(p, None, 6 * 3600, dt=1.0)
        temps[n] = p["TEMP_IN"]
        if n == 0:
            assert "overheat" in [e.kind for e in p.drain_events()]
    assert temps[0] > temps[1] > temps[2] > temps[3]
    assert temps[2] > p["TEMP_OUT"]


def test_steady_state_against_the_heat_balance() -> None:
    p = Ventilation(solar_peak=0.0, t_out_amp=0.0, weather_sigma=0.0)
    p["MAIN_POWER"] = True
    p["FAN2"] = p["FAN3"] = True
    _run(p, None, 12 * 3600, dt=5.0)
    g = p.ua + 1.2 * 1005.0 * (p.infiltration + 2 * p.fan_flow)
    assert p["TEMP_IN"] == pytest.approx(p.t_out_mean + p.heat_animals / g, rel=0.01)


def test_daily_profile_and_weather_seed() -> None:
    p = Ventilation(start_hour=0.0)
    out = []
    for _ in range(24):
        _run(p, None, 3600.0, dt=10.0)
        out.append(p["TEMP_OUT"])
    hottest = out.index(max(out))
    assert 13 <= hottest <= 16
    assert max(out) - min(out) == pytest.approx(2 * p.t_out_amp, rel=0.1)
    a, b = Ventilation(), Ventilation()
    a.reset(1)
    b.reset(2)
    assert a["TEMP_OUT"] != b["TEMP_OUT"]
