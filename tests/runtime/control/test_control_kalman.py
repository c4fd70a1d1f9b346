"""A Kalman filter on a noisy, quantised tank level (the example in tank_kalman.py).

The true level comes from a Torricelli tank model; it reaches the PLC through a 4-20 mA
transmitter with Gaussian noise and a 10-bit S7 analog input (plclab.io.AnalogInput), is
scaled by AI_SCALE and filtered by MOVING_AVG and PT1 in the PLC and by a filterpy
KalmanFilter beside it.
"""

import importlib.util
from pathlib import Path

import numpy as np

_spec = importlib.util.spec_from_file_location(
    "tank_kalman", Path(__file__).with_name("tank_kalman.py"))
tank_kalman = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(tank_kalman)


def test_kalman_filter_reduces_the_rms_error_of_the_raw_adc_value():
    res = tank_kalman.run(seconds=600.0, noise=0.05, bits=10, seed=1)
    err = res["rms"]
    print("RMS error against the true level (mm): " +
          ", ".join(f"{k} {1000 * v:.1f}" for k, v in err.items()))
    # the raw value carries the noise (50 mm) and the quantisation (11.6 mm per step / sqrt 12)
    assert 0.04 < err["raw"] < 0.06
    assert err["kalman"] < 0.3 * err["raw"]
    assert err["kalman"] < err["avg"] and err["kalman"] < err["pt1"]
    assert err["avg"] < err["raw"] and err["pt1"] < err["raw"]


def test_the_example_is_reproducible_and_quantised():
    a = tank_kalman.run(seconds=60.0, seed=4)
    b = tank_kalman.run(seconds=60.0, seed=4)
    assert np.array_equal(a["signals"]["raw"], b["signals"]["raw"])
    # without noise the raw value is the truth quantised to one ADC step (S7, 10 bit)
    q = tank_kalman.run(seconds=60.0, noise=0.0)
    step = q["resolution"]
    assert abs(step - 10.0 * 32 / 27648) < 1e-12
    assert np.max(np.abs(q["signals"]["raw"] - q["true"])) <= step / 2 + 1e-4
