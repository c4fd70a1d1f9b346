"""Example: a Kalman filter on a noisy, quantised tank level (helper of test_control_kalman.py).

The chain is the one a lab wires up::

    tank (true level, m) -> 4-20 mA transmitter + noise -> S7 analog input (10 bit)
        -> %IW counts -> AI_SCALE in the PLC (raw level, m) -> filters

Three filters look at the same raw level: MOVING_AVG and PT1 run in the PLC program, a
constant-velocity Kalman filter (filterpy) runs beside it on the value the PLC publishes.
:func:`run` returns the true level, every signal and their RMS errors.

The tank: ``A dh/dt = q_in(t) - c sqrt(h)`` (Torricelli outflow), ``A = 1 m^2``,
``c = 0.012 m^2.5/s``, an inflow that steps between 30, 10 and 25 l/s.
"""

from __future__ import annotations

import math

import numpy as np
from filterpy.common import Q_discrete_white_noise
from filterpy.kalman import KalmanFilter

import plclab
from plclab.io import AnalogInput

AREA = 1.0  # m^2
C_OUT = 0.012  # m^2.5 / s
LO, HI = 0.0, 10.0  # m, transmitter range
DT = 0.1  # s, PLC cycle and ADC conversion period

PROGRAM = """
PROGRAM Tank
VAR
    level_word AT %IW64 : INT;   (* S7 analog input, 4-20 mA, 0..10 m *)
    ai : AI_SCALE;
    avg : MOVING_AVG;
    lag : PT1;
    level_raw : REAL;
    level_avg : REAL;
    level_pt1 : REAL;
END_VAR
ai(IN := level_word, LO := 0.0, HI := 10.0, RANGE := '4-20mA', CONVENTION := 's7');
level_raw := ai.VALUE;
avg(IN := level_raw, N := 16);
level_avg := avg.AVG;
lag(IN := level_raw, T := T#1s);
level_pt1 := lag.OUT;
END_PROGRAM
"""


def inflow(t: float) -> float:
    """m^3/s"""
    return 0.030 if t < 200.0 else 0.010 if t < 400.0 else 0.025


def simulate_level(seconds: float, h0: float = 2.0, dt: float = DT, substeps: int = 10):
    """True level at t = k dt (RK-free: small explicit Euler substeps are plenty here)."""
    n = round(seconds / dt)
    h = h0
    out = np.empty(n)
    for k in range(n):
        out[k] = h
        for j in range(substeps):
            t = (k + j / substeps) * dt
            h += dt / substeps * (inflow(t) - C_OUT * math.sqrt(max(h, 0.0))) / AREA
    return out


def kalman(z: np.ndarray, r_var: float, accel_std: float = 2e-3, dt: float = DT) -> np.ndarray:
    """Constant-velocity Kalman filter: state (level, rate), measurement the level."""
    kf = KalmanFilter(dim_x=2, dim_z=1)
    kf.F = np.array([[1.0, dt], [0.0, 1.0]])
    kf.H = np.array([[1.0, 0.0]])
    kf.R = np.array([[r_var]])
    kf.Q = Q_discrete_white_noise(dim=2, dt=dt, var=accel_std**2)
    kf.x = np.array([[z[0]], [0.0]])
    kf.P = np.diag([r_var, 1e-2])
    out = np.empty(len(z))
    for k, zk in enumerate(z):
        kf.predict()
        kf.update(np.array([[zk]]))
        out[k] = kf.x[0, 0]
    return out


def rms(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.sqrt(np.mean((a - b) ** 2)))


def run(seconds: float = 600.0, noise: float = 0.05, bits: int = 10, seed: int = 1) -> dict:
    """Run the example; return the signals and the RMS error of each against the truth."""
    true = simulate_level(seconds)
    ch = AnalogInput(lo=LO, hi=HI, signal="4-20mA", convention="s7", bits=bits,
                     noise=noise, seed=seed)
    plc = plclab.loads(PROGRAM, cycle_time=f"{round(DT * 1000)}ms")
    sig = {name: np.empty(len(true)) for name in ("raw", "avg", "pt1")}
    for k, h in enumerate(true):
        plc["level_word"] = ch.sample(k * DT, float(h))
        plc.scan()
        sig["raw"][k] = plc["Tank.level_raw"]
        sig["avg"][k] = plc["Tank.level_avg"]
        sig["pt1"][k] = plc["Tank.level_pt1"]
    quant = ch.resolution
    sig["kalman"] = kalman(sig["raw"], r_var=noise**2 + quant**2 / 12.0)
    skip = round(5.0 / DT)  # let every filter settle
    errors = {name: rms(s[skip:], true[skip:]) for name, s in sig.items()}
    return {"true": true, "signals": sig, "rms": errors, "resolution": quant}


if __name__ == "__main__":  # pragma: no cover - run by hand to see the numbers
    res = run()
    for name, err in res["rms"].items():
        print(f"{name:7s} RMS error {1000 * err:6.1f} mm")
