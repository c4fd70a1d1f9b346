"""The FBD examples (examples/fbd/*.xml) are FBD networks and behave exactly as the ST
programs they were drawn from: the same outputs after every scan, timers included."""

import random
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import plclab
from plclab.lang.frontends.plcopen import NS

ROOT = Path(__file__).resolve().parents[3]
PAIRS = {
    "motor": "labs/motor-start-stop/solution/motor.st",
    "bottle": "labs/bottle-reject/solution/bottle.st",
    "ventilation": "labs/ventilation-fans/solution/ventilation.st",
    "tank": "labs/tank-two-position/solution/tank.st",
}


def run(plc, names: list[str], inputs: list[str], scans: int, seed: int) -> list[tuple]:
    rng = random.Random(seed)
    rows = []
    for _ in range(scans):
        for n in inputs:
            if rng.random() < 0.15:
                plc[n] = not plc[n]
        plc.scan()
        rows.append(tuple(plc[n] for n in names))
    return rows


@pytest.mark.parametrize("name", sorted(PAIRS))
def test_fbd_example_has_the_trace_of_its_st_form(name):
    fbd = plclab.load(ROOT / "examples/fbd" / f"{name}.xml")
    st = plclab.load(ROOT / PAIRS[name])
    names = [n for n in st.variables() if isinstance(st[n], bool | int | float)]
    inputs = [n for n in names if (st.var(n).address or "").startswith("%I")]
    assert inputs
    for seed in (1, 2, 3):
        assert run(fbd, names, inputs, 400, seed) == run(st, names, inputs, 400, seed)
        fbd.cold_restart()
        st.cold_restart()


@pytest.mark.parametrize("name", sorted(PAIRS))
def test_fbd_example_is_a_network_of_blocks(name):
    root = ET.parse(ROOT / "examples/fbd" / f"{name}.xml").getroot()
    bodies = root.findall(f".//{{{NS}}}body/{{{NS}}}FBD")
    assert bodies and bodies[0].findall(f"{{{NS}}}block")
