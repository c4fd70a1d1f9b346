"""The compiled I/O transfer skips module calls only when they cannot change anything: its
results equal calling the plclab.io modules at every scan (random inputs, long runs)."""

from __future__ import annotations

import random

import pytest

import plclab
from plants import get_plant
from plclab.io import AnalogInput, DigitalInput, DigitalOutput
from plclab.sim.channels import bind
from plclab.sim.wiring import Wiring

PROG = """PROGRAM P
VAR a AT %IX0.0 : BOOL; b AT %IX0.1 : BOOL; w AT %IW64 : INT; q AT %QX0.0 : BOOL; END_VAR
q := a;
END_PROGRAM"""


@pytest.mark.parametrize("params", [
    {"filter_ms": 3.0},
    {"filter_ms": 0.0},
    {"filter_ms": 25.0, "bounce_ms": 4.0},
    {"filter_ms": 2.0, "bounce_ms": 30.0, "bounces": [2, 6]},
])
def test_digital_input_with_skips_equals_the_module_every_scan(params):
    plant = get_plant("motor")
    plc = plclab.loads(PROG)
    w = Wiring.from_rows([{"plc": "%IX0.0", "signal": "START", "module": "di", **params}])
    tr = bind(w, plant, plc, seed=5)
    ch = tr.channels[0]
    ref = DigitalInput(seed=ch.module.seed, **{k: tuple(v) if isinstance(v, list) else v
                                                for k, v in params.items()})
    rng = random.Random(1)
    value = False
    for k in range(20000):
        t = k * 0.01
        if rng.random() < 0.05:
            value = not value
        got = tr.read_in(t, {"START": value})[0]
        assert got == ref.sample(t, value), (k, t)
    assert ch.module.raw_transitions == ref.raw_transitions
    assert ch.module.filtered_transitions == ref.filtered_transitions


@pytest.mark.parametrize("params", [
    {"kind": "relay"},
    {"kind": "transistor"},
    {"kind": "relay", "close_ms": 35.0, "open_ms": 12.0},
])
def test_digital_output_with_skips_equals_the_module_every_scan(params):
    plant = get_plant("motor")
    plc = plclab.loads(PROG)
    w = Wiring.from_rows([{"plc": "%QX0.0", "signal": "K1", "module": "do", **params}])
    tr = bind(w, plant, plc)
    ref = DigitalOutput(**params)
    rng = random.Random(2)
    cmd = False
    for k in range(20000):
        t = k * 0.01
        if rng.random() < 0.1:
            cmd = not cmd
        tr.apply_out(t, (cmd,))
        assert plant["K1"] == ref.apply(t, cmd), (k, t)
    assert tr.channels[0].module.switch_times == ref.switch_times


@pytest.mark.parametrize("params", [
    {"lo": 0.0, "hi": 2.0},
    {"lo": 2.0, "hi": 0.0, "convention": "book", "bits": 12, "signal_range": "0-10V"},
    {"lo": -1.0, "hi": 3.0, "convention": "logo", "signal_range": "0-20mA"},
    {"lo": 0.0, "hi": 2.0, "noise": 0.01},
    {"lo": 0.0, "hi": 2.0, "tau": 0.05},
])
def test_analog_input_with_skips_equals_the_module_every_scan(params):
    plant = get_plant("tank")
    plc = plclab.loads(PROG)
    w = Wiring.from_rows([{"plc": "%IW64", "signal": "LEVEL", "module": "ai", **params}])
    tr = bind(w, plant, plc, seed=3)
    ch = tr.channels[0]
    p = dict(params)
    ref = AnalogInput(seed=ch.module.seed, signal=p.pop("signal_range", "4-20mA"), **p)
    rng = random.Random(3)
    x = 1.0
    for k in range(30000):
        t = k * 0.01
        r = rng.random()
        if r < 0.01:
            x = rng.uniform(-1.5, 3.5)  # jumps, also out of range
        elif r < 0.5:
            x += rng.gauss(0.0, 2e-5)  # creeping by less than a count
        got = tr.read_in(t, {"LEVEL": x})[0]
        assert got == ref.sample(t, x), (k, t, x)
        assert plc.inputs[64] == (got >> 8) & 255 and plc.inputs[65] == got & 255
