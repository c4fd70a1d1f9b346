"""heater-pid's own checks (labs/heater-pid/checks.py) on hand-made traces: each failure names
what the temperature did (a steady error, a swing, the old set point, an overshoot coming down,
a creep, a value held far away), and each of them fails where it must."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]


def _checks():
    return lab_checks("heater-pid")


C = _checks()
T = np.arange(0.0, 1200.0, 1.0)


def _trace(**cols):
    return Trace(T, {k: np.asarray(v, dtype=float) for k, v in cols.items()},
                 meta={"t_end": float(T[-1]) + 1.0})


def _settles(temp, sp=None, **kw):
    cols = {"TEMP": temp} | ({"SP": sp} if sp is not None else {})
    args = {"target": 50.0, "band": 0.5, "after": 0.0, "within": 600.0} | kw
    return C.settles_diagnosed(_trace(**cols), **args)


def test_a_settled_loop_passes():
    temp = 50.0 + 30.0 * np.exp(-T / 100.0) * -1.0
    assert _settles(temp)[0]


def test_a_steady_error_below_is_a_steady_state_error():
    ok, msg, tf, sig = _settles(np.full(len(T), 49.4))
    assert not ok and "steady-state error" in msg and "0.60 °C below" in msg and tf == 600.0


def test_a_swing_is_named_a_swing():
    ok, msg = _settles(50.0 + 1.2 * np.sin(T / 40.0))[:2]
    assert not ok and "swings" in msg and "steady-state" not in msg


def test_the_old_set_point_is_recognised():
    sp = np.where(T < 300.0, 50.0, 60.0)
    ok, msg = _settles(np.full(len(T), 50.0), sp=sp, target=60.0, after=300.0, within=360.0)[:2]
    assert not ok and "set point before the change (50 °C)" in msg


def test_a_value_held_far_away_points_at_the_set_point_and_the_scaling():
    ok, msg = _settles(np.full(len(T), 38.0))[:2]
    assert not ok and "scaled right" in msg and "steady-state" not in msg


def test_an_overshoot_coming_down_is_windup_not_slowness():
    temp = 50.0 + 15.0 * np.exp(-(T - 250.0).clip(0) / 250.0)
    temp[T < 250.0] = 20.0 + T[T < 250.0] * 0.18
    ok, msg = _settles(temp)[:2]
    assert not ok and "overshoot" in msg and "windup" in msg


def test_a_slow_creep_from_below_is_too_slow():
    temp = 50.0 - 20.0 * np.exp(-T / 400.0)
    ok, msg = _settles(temp)[:2]
    assert not ok and "too slow" in msg


def test_heats_up_tells_the_three_ways_of_not_heating():
    cold = np.full(len(T), 20.0)
    ok, msg = C.heats_up(_trace(TEMP=cold, POWER=np.zeros(len(T))))[:2]
    assert not ok and "direct acting" in msg
    ok, msg = C.heats_up(_trace(TEMP=cold, POWER=np.full(len(T), 0.36)))[:2]
    assert not ok and "not scaled" in msg and "0.36 %" in msg
    ok, msg = C.heats_up(_trace(TEMP=np.minimum(20.0 + T * 0.05, 38.0),
                                POWER=np.full(len(T), 20.0)))[:2]
    assert not ok and "scaled right" in msg
    assert C.heats_up(_trace(TEMP=20.0 + T * 0.1, POWER=np.full(len(T), 100.0)))[0]


def test_holds_diagnosed_counts_the_share_in_the_band():
    start = 600.0
    good = np.where(T < 650.0, 49.0, 50.05)
    assert C.holds_diagnosed(_trace(TEMP=good), start=start)[0]  # 50 of 600 s outside
    ok, msg = C.holds_diagnosed(_trace(TEMP=np.full(len(T), 48.3)), start=start)[:2]
    assert not ok and "0 %" in msg and "steady-state error" in msg
    late = np.where(T < 700.0, 49.0, 50.0)  # 100 of 600 s outside: 83 %
    ok, msg = C.holds_diagnosed(_trace(TEMP=late), start=start)[:2]
    assert not ok and "83 %" in msg


# ---------------------------------------------------------------------------- damping (R8)


def _step_response(zeta, step=2.0, at=360.0, wn=0.02):
    """A second-order response to a set-point step at ``at`` s: damping ``zeta``."""
    tt = np.maximum(T - at, 0.0)
    wd = wn * np.sqrt(1.0 - zeta ** 2)
    y = 1.0 - np.exp(-zeta * wn * tt) * (np.cos(wd * tt) + zeta / np.sqrt(1 - zeta ** 2)
                                         * np.sin(wd * tt))
    return 50.0 + step * y, np.where(T < at, 50.0, 50.0 + step)


def test_a_well_damped_small_step_passes_and_a_swinging_one_fails():
    # overshoot exp(-pi zeta / sqrt(1 - zeta^2)): zeta 0.6 -> 9 %, 0.45 -> 21 %, 0.3 -> 37 %,
    # 0.15 -> 62 %
    for zeta, ok in ((0.6, True), (0.45, True), (0.3, False), (0.15, False)):
        temp, sp = _step_response(zeta)
        res = C.damped_step(_trace(TEMP=temp, SP=sp), at=360.0, max_overshoot=0.3)
        assert res[0] is ok, (zeta, res[1])
        if not ok:
            assert "swings" in res[1] and res[2] > 360.0
    # a step down is judged the same way, by the undershoot
    temp, sp = _step_response(0.15, step=-2.0)
    assert not C.damped_step(_trace(TEMP=temp, SP=sp), at=360.0)[0]
    temp, sp = _step_response(0.6, step=-2.0)
    assert C.damped_step(_trace(TEMP=temp, SP=sp), at=360.0)[0]


def test_damped_step_needs_a_step():
    temp, _ = _step_response(0.6)
    res = C.damped_step(_trace(TEMP=temp, SP=np.full(len(T), 50.0)), at=360.0)
    assert not res[0] and "did not change" in res[1]


def test_the_lab_states_a_performance_spec_and_a_tuning_is_not_a_survivor():
    from plclab.grade.audit import Mutant, classify
    from plclab.grade.lab import load_lab

    assert load_lab("heater-pid").performance_spec
    assert not load_lab("motor-start-stop").performance_spec
    full, part = 49.0, 40.0
    m = Mutant("constant", "20.0 doubled", 26, "")
    classify(m, "survived", full, full, performance_spec=True)
    assert m.status == "tuning"
    for op, score, spec in (("constant", part, True), ("negate", full, True),
                            ("constant", full, False)):
        m = Mutant(op, "x", 1, "")
        classify(m, "survived", score, full, performance_spec=spec)
        assert m.status == "survived", (op, score, spec)
    m = Mutant("comparison", "x", 1, "")
    classify(m, "equivalent:one scan", full, full)
    assert m.status == "equivalent" and m.equivalence == "one scan"


def test_performance_spec_must_be_a_boolean(tmp_path):
    import shutil

    import pytest

    from plclab.errors import PlcError
    from plclab.grade.lab import load_lab

    dst = tmp_path / "heater-pid"
    shutil.copytree(ROOT / "labs" / "heater-pid", dst)
    toml = dst / "lab.toml"
    toml.write_text(toml.read_text(encoding="utf-8").replace(
        "performance_spec = true", 'performance_spec = "yes"'), encoding="utf-8")
    with pytest.raises(PlcError) as e:
        load_lab(str(dst))
    assert e.value.code == "PLC5004"


# ---------------------------------------------------------------------------- R8 vs the plant


def _small_step_overshoot(kp, tn, period, lab):
    """The loop's linear model from the plant the lab builds (mass, element power, losses, the
    thermowell's lag, the sampling as half a period of delay): phase margin (degrees) and the
    overshoot of a small set-point step (share of the step), with python-control."""
    import control as ct

    from plants import Heater

    p = Heater(**lab.plant_params)
    c_heat = 1000.0 * p.area * p.level0 * 4186.0  # J/K: rho V c of the water
    gain = p.p_max / p.ua / 100.0  # degC per % of power, in steady state
    plant = ct.tf([gain], [c_heat / p.ua, 1.0])
    lag = ct.tf([1.0], [4.0, 1.0])  # the transmitter's thermowell (lab.toml wiring: tau 4 s)
    hold = ct.tf(*ct.pade(period / 2.0, 3))
    ctl = ct.tf([kp * tn, kp], [tn, 0.0])
    _gm, pm, _wg, _wp = ct.margin(ctl * plant * lag * hold)
    t = np.linspace(0.0, 1500.0, 7501)
    _, y = ct.step_response(ct.feedback(ctl * plant * hold, lag), t)
    return pm, float(np.max(y) - 1.0)


def test_r8_separates_well_damped_tunings_from_swinging_ones_on_the_plant_model():
    """The 40 % of R8 lies between the tunings the lab accepts (the solution, the variants, a
    doubled gain, a halved integral time, brisk tunings with TN = 30 s: phase margin 40 degrees
    or more) and the badly damped ones (the controller called every scan but told T = 1 s: an
    integral time of about 10 s; KP 10 with TN 30 s)."""
    import pytest

    from plclab.grade.lab import load_lab

    pytest.importorskip("control")
    lab = load_lab("heater-pid")
    for kp, tn, period in ((20, 100, 1.0), (25, 80, 2.0), (15, 120, 0.1), (30, 75, 0.5),
                           (25, 90, 0.2), (40, 100, 1.0), (20, 50, 1.0), (40, 30, 1.0),
                           (30, 30, 1.0)):
        pm, over = _small_step_overshoot(kp, tn, period, lab)
        assert over <= 0.4 and pm >= 40.0, (kp, tn, period, pm, over)
    for kp, tn, period in ((20, 11, 1.0), (10, 30, 1.0), (10, 15, 1.0)):
        pm, over = _small_step_overshoot(kp, tn, period, lab)
        assert over > 0.4 and pm < 35.0, (kp, tn, period, pm, over)
