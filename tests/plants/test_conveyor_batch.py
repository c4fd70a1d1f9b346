"""The conveyor reads every bottle's pose with one call of pymunk's batch API: the same poses,
events and snapshots, scan by scan, as reading each body on its own (with bottles released,
knocked over, rejected and binned, so bodies come and go and the space's order changes)."""

from __future__ import annotations

import pytest

pytest.importorskip("pymunk")

import plants.conveyor_bottle as conveyor_bottle  # noqa: E402
from plants import Conveyor  # noqa: E402


def _record(batched: bool, monkeypatch) -> list:
    if not batched:
        monkeypatch.setattr(conveyor_bottle, "batch_reader", lambda pm: None)
    c = Conveyor(belt_length=6.0, feed_pitch=0.3, knock_rate=0.3, max_bottles=40)
    c.reset(seed=3)
    assert (c._poses.batch is not None) == batched
    rows = []
    for k in range(1500):
        c["CONVEYOR"] = k > 20
        c["REJECT"] = 300 <= k % 400 < 330  # the pusher sweeps bottles off now and then
        c.step(0.01)
        rows.append((c.snapshot(), [(e.kind, e.data) for e in c.drain_events()],
                     c["X1"], c["X2"], c["FILL_EYE"]))
    monkeypatch.undo()
    return rows


def test_batched_and_single_reads_give_the_same_run(monkeypatch) -> None:
    single = _record(False, monkeypatch)
    batched = _record(True, monkeypatch)
    kinds = {kind for _, evs, *_ in single for kind, _ in evs}
    assert {"bottle_released", "bottle_rejected"} <= kinds  # bodies came and went
    for k, (a, b) in enumerate(zip(single, batched, strict=True)):
        assert repr(a) == repr(b), f"scan {k} differs"  # NaN slots compare as text


def test_a_wrong_index_is_caught(monkeypatch) -> None:
    """The comparison above can fail: a reader that swaps two bottles' poses differs."""
    c = Conveyor(belt_length=6.0, feed_pitch=0.3, knock_rate=0.0)
    c.reset(seed=1)
    c["CONVEYOR"] = True
    for _ in range(300):
        c.step(0.01)
    fl, idx = c._poses.read(c._space, c._bottles)
    assert len(idx) == len(c._bottles) >= 2
    xs = [fl[i] for i in idx]
    assert xs == [b.x for b in c._bottles] and xs[0] != xs[1]


def test_the_snapshot_row_is_the_snapshot_in_its_keys_order() -> None:
    c = Conveyor(belt_length=6.0, feed_pitch=0.3, knock_rate=0.3, max_bottles=30)
    c.reset(seed=2)
    keys = c.snapshot_keys()
    for k in range(600):
        c["CONVEYOR"] = k > 10
        c["REJECT"] = 200 <= k < 240
        c.step(0.01)
        if k % 50 == 0:
            want = c.snapshot()
            assert list(want) == keys
            assert repr(c.snapshot_row()) == repr(list(want.values())), f"scan {k}"


def test_a_simulation_records_the_same_snapshot_either_way(monkeypatch) -> None:
    import numpy as np

    import plclab
    from plclab.sim import Scenario, Simulation

    src = ("PROGRAM Line VAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL; "
           "CONVEYOR AT %QX0.0 : BOOL; END_VAR CONVEYOR := (START OR CONVEYOR) AND STOP; "
           "END_PROGRAM")

    def run():
        sim = Simulation(plclab.loads(src), "conveyor", scenario=Scenario().press("START", at="0.5s"),
                         plant_params={"belt_length": 6.0, "feed_pitch": 0.3, "max_bottles": 30})
        return sim.run(8.0)

    fast = run()
    monkeypatch.delattr(Conveyor, "snapshot_row")
    plain = run()
    assert fast.names == plain.names and "bottle3.x" in fast.names
    for name in fast.names:
        assert np.array_equal(fast[name], plain[name], equal_nan=True), name
