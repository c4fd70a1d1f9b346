"""The labs ventilation-fans, pump-station, heater-pid and press-safety: every reference
solution scores 100 % (hidden scenarios included), the starter scores low, the README keeps its I/O table in
step with lab.toml and cites the textbook, and the labs' own Python checks do what they say on
small hand-made traces."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from plclab.grade.engine import grade_sources, read_submission
from plclab.grade.lab import load_lab
from plclab.grade.scaffold import readme_table
from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]
NEW_LABS = ["ventilation-fans", "pump-station", "heater-pid", "press-safety"]
EXPECT = re.compile(r"\(\*\s*expect:\s*(.+?)\s*\*\)")

# The typical mistakes, their score bounds and the criteria they break are in each lab.toml
# ([[mistake]]); tests/grade/test_grade_labs.py grades them for every lab.


def _grade(lab_id, path):
    lab = load_lab(lab_id)
    sources, _ = read_submission(path)
    return lab, grade_sources(lab, sources, include_hidden=True)



def _trace(t, **cols):
    t = np.asarray(t, dtype=float)
    return Trace(t, {k: np.asarray(v) for k, v in cols.items()},
                 meta={"t_end": float(t[-1]) + (t[1] - t[0] if len(t) > 1 else 1.0)})


# ---------------------------------------------------------------------------- the labs


@pytest.mark.parametrize("lab_id", NEW_LABS)
def test_lab_is_complete(lab_id):
    lab = load_lab(lab_id, deep=True)
    assert len(lab.files("mistakes")) >= 2
    assert lab.files("solution") and lab.starter
    assert any(not s.visible for s in lab.scenarios) and any(s.visible for s in lab.scenarios)
    readme = (lab.path / "README.md").read_text(encoding="utf-8")
    assert readme_table(readme) == lab.io_table_markdown(), (
        f"run: plclab lab show {lab_id} --update-readme")
    assert "001_c648febd3bbd6efb.txt" in readme and re.search(r"lines \d+-\d+", readme)
    for m in lab.files("mistakes"):
        assert EXPECT.search(m.read_text(encoding="utf-8")), f"{m.name}: (* expect: ... *)"


def _solutions():
    return [(lab_id, p.name) for lab_id in NEW_LABS for p in load_lab(lab_id).files("solution")]


@pytest.mark.parametrize("lab_id,name", _solutions())
def test_solution_scores_full_marks_hidden_included(lab_id, name):
    lab, res = _grade(lab_id, ROOT / "labs" / lab_id / "solution" / name)
    failed = [f"{t.name}: {t.message}" for t in res.tests if not t.passed]
    assert res.status == "ok" and not failed, failed
    assert res.score == res.max_score == lab.max_score
    assert {t.scenario for t in res.tests} == {s.name for s in lab.scenarios}


@pytest.mark.parametrize("lab_id", NEW_LABS)
def test_starter_scores_low(lab_id):
    lab = load_lab(lab_id)
    sources, _ = read_submission(lab.starter[0])
    res = grade_sources(lab, sources, include_hidden=True)
    assert res.status == "ok", res.diagnostics
    assert res.score <= 0.25 * res.max_score


def test_grading_is_deterministic():
    a = _grade("pump-station", ROOT / "labs/pump-station/mistakes/no_latch.st")[1]
    b = _grade("pump-station", ROOT / "labs/pump-station/mistakes/no_latch.st")[1]
    assert [(t.name, t.score, t.message) for t in a.tests] == \
        [(t.name, t.score, t.message) for t in b.tests]


# ---------------------------------------------------------------------------- the checks


def test_two_fans_run():
    two_fans_run = lab_checks("ventilation-fans").two_fans_run
    t = np.arange(0.0, 10.0, 0.5)
    n = len(t)
    on, off = np.ones(n, bool), np.zeros(n, bool)
    f2 = t >= 5.0
    good = _trace(t, FAULT1=off, FAULT2=f2, FAULT3=off, MAIN_POWER=on,
                  FAN1=t >= 6.0, FAN2=on, FAN3=on)  # a faulted fan's contactor may stay on
    assert two_fans_run(good, settle=2.0)[0]
    late = _trace(t, FAULT1=off, FAULT2=f2, FAULT3=off, MAIN_POWER=on,
                  FAN1=t >= 8.0, FAN2=on, FAN3=on)
    ok, msg, tf = two_fans_run(late, settle=2.0)
    assert not ok and tf == 7.0 and "1 fan(s)" in msg
    three = _trace(t, FAULT1=off, FAULT2=off, FAULT3=off, MAIN_POWER=on, FAN1=on, FAN2=on,
                   FAN3=on)
    assert not two_fans_run(three)[0]


def test_lamps_show_state():
    lamps = lab_checks("ventilation-fans").lamps_show_state
    t = np.arange(0.0, 3.0, 1.0)
    on, off = np.ones(3, bool), np.zeros(3, bool)
    cols = {"%QX0.0": on, "%QX0.1": off, "%QX0.2": on, "%QX0.3": on, "%IX0.3": off,
            "%IX0.4": np.array([False, True, True]), "%IX0.5": off, "%QX0.4": on,
            "%QX0.6": off, "%QX0.7": np.array([True, False, False]), "%QX1.0": on}
    assert lamps(_trace(t, **cols))[0]
    cols["%QX0.7"] = on  # lit although fan 2 is faulted
    ok, msg, tf, sig = lamps(_trace(t, **cols))
    assert not ok and tf == 1.0 and sig == ["FAN2_LAMP"]


def test_stage_and_start_gap():
    c = lab_checks("pump-station")
    t = np.arange(0.0, 300.0, 0.5)
    ns1 = (t >= 10.0) & (t < 250.0)
    sw = np.zeros(len(t), bool)
    ok_ns2 = (t >= 130.5) & (t < 250.0)
    assert c.stage(_trace(t, NS1=ns1, NS2=ok_ns2, PWY=sw), delay=120.0)[0]
    early = (t >= 50.0) & (t < 250.0)
    ok, msg, tf, _ = c.stage(_trace(t, NS1=ns1, NS2=early, PWY=sw), delay=120.0)
    assert not ok and tf == 50.0 and "only 40.0 s after NS1" in msg
    assert c.stage(_trace(t, NS1=ns1, NS2=early, PWY=t >= 45.0), delay=120.0)[0]
    never = np.zeros(len(t), bool)
    ok, msg, tf, _ = c.stage(_trace(t, NS1=ns1, NS2=never, PWY=sw), delay=120.0)
    assert not ok and "still off" in msg
    ns3 = np.zeros(len(t), bool)
    assert c.start_gap(_trace(t, NS1=ns1, NS2=ok_ns2, NS3=ns3))[0]
    ok, msg, tf, _ = c.start_gap(_trace(t, NS1=ns1, NS2=(t >= 12.0), NS3=ns3), gap=5.0)
    assert not ok and tf == 12.0


def test_no_saturation_chatter():
    chk = lab_checks("heater-pid").no_saturation_chatter
    t = np.arange(0.0, 60.0, 1.0)
    smooth = np.clip(100.0 - 2.0 * t, 0.0, 100.0)
    assert chk(_trace(t, POWER=smooth))[0]
    bang = np.where(np.arange(len(t)) % 2 == 0, 100.0, 0.0)
    ok, msg, tf, sig = chk(_trace(t, POWER=bang))
    assert not ok and sig == ["POWER"]


def test_two_hand_and_dose():
    c = lab_checks("press-safety")
    t = np.round(np.arange(0.0, 10.0, 0.01), 2)
    left = (t >= 1.0) & (t < 5.0)
    right = (t >= 1.3) & (t < 5.0)
    down = (t >= 1.31) & (t < 3.7)
    assert c.two_hand(_trace(t, **{"%IX0.0": left, "%IX0.1": right, "%QX0.0": down}))[0]
    taped = t >= 0.2
    ok, msg, tf, _ = c.two_hand(_trace(t, **{"%IX0.0": taped, "%IX0.1": right,
                                            "%QX0.0": down}))
    assert not ok and "1.10 s after" in msg
    twice = down | ((t >= 6.0) & (t < 7.0))
    both = (t >= 1.0) & (t < 8.0)
    ok, msg, _, _ = c.two_hand(_trace(t, **{"%IX0.0": both, "%IX0.1": both, "%QX0.0": twice}))
    assert not ok and "without releasing" in msg
    pos = np.clip((t - 1.31) * 25.0, 0.0, 60.0) + 2.0
    assert c.dose(_trace(t, DOWN=down, POSITION=pos), pulses=60, count=1)[0]
    ok, msg, _, _ = c.dose(_trace(t, DOWN=down, POSITION=pos * 0.5), pulses=60)
    assert not ok and "60 mm" in msg


def test_pumps_latched_until_low_level():
    chk = lab_checks("pump-station").latched
    t = np.arange(0.0, 100.0, 0.5)
    ny = t < 80.0
    latched = (t >= 10.0) & (t < 80.5)
    assert chk(_trace(t, NY=ny, NS1=latched, NS2=latched & (t >= 30.0), NS3=t < 0))[0]
    follows = latched & ~((t >= 40.0) & (t < 50.0))
    ok, msg, tf, sig = chk(_trace(t, NY=ny, NS1=latched, NS2=follows & (t >= 30.0), NS3=t < 0))
    assert not ok and tf == 40.0 and "NS2" in msg and sig[0] == "NS2"


def test_steady_output():
    chk = lab_checks("heater-pid").steady_output
    t = np.arange(0.0, 100.0, 1.0)
    calm = 85.0 + 0.5 * np.sin(t)
    assert chk(_trace(t, POWER=calm, TEMP=t * 0), max_std=3.0, start=10.0)[0]
    noisy = 85.0 + 10.0 * np.sin(t)
    ok, msg = chk(_trace(t, POWER=noisy, TEMP=t * 0), max_std=3.0, start=10.0)[:2]
    assert not ok and "at most 3" in msg
