"""Mine sump driven by the textbook's ST program (001 lines 7845-7868), translated to Python."""

from __future__ import annotations

import pytest

from plants import Sump


class Ton:
    """IEC TON on a virtual clock."""

    def __init__(self, pt: float) -> None:
        self.pt = pt
        self.start: float | None = None
        self.q = False

    def __call__(self, inp: bool, now: float) -> bool:
        if not inp:
            self.start = None
            self.q = False
        else:
            if self.start is None:
                self.start = now
            self.q = now - self.start >= self.pt
        return self.q


class TextbookProgram:
    """The textbook's program, statement by statement."""

    def __init__(self, qt: float = 600.0) -> None:
        self.ton1 = Ton(qt)
        self.ton2 = Ton(qt)
        self.tns1 = self.tns2 = False
        self.out = {"ZAL": False, "NS1": False, "NS2": False, "NS3": False}

    def scan(self, p: Sump) -> None:
        o = self.out
        if p["NY"]:
            o["ZAL"] = not p["DAWL"]
            if p["WY"] and not o["NS1"]:
                o["NS1"] = True
            if (p["PWY"] or self.tns1) and not o["NS2"]:
                o["NS2"] = True
            if (p["AWY"] or self.tns2) and not o["NS3"]:
                o["NS3"] = True
        if not p["NY"]:
            o["NS1"] = o["NS2"] = o["NS3"] = o["ZAL"] = False
        self.tns1 = self.ton1(o["NS1"], p.time)
        self.tns2 = self.ton2(o["NS2"], p.time)
        for k, v in o.items():
            p[k] = v


def _run(p: Sump, prog: TextbookProgram | None, seconds: float, dt: float = 0.5) -> list[float]:
    levels = []
    for _ in range(int(seconds / dt)):
        if prog is not None:
            prog.scan(p)
        p.step(dt)
        levels.append(p["LEVEL"])
    return levels


def test_signal_names_match_the_textbook_program() -> None:
    names = set(Sump().signals)
    assert {"NY", "WY", "PWY", "AWY", "DAWL", "ZAL", "NS1", "NS2", "NS3"} <= names


def test_textbook_program_keeps_the_sump_below_emergency() -> None:
    p = Sump()
    prog = TextbookProgram()
    levels = _run(p, prog, 4 * 3600)
    assert max(levels) < p.heights[3]
    kinds = [e.kind for e in p.drain_events()]
    assert "primed" in kinds
    assert "emergency_level" not in kinds and "flooded" not in kinds
    assert "lost_prime" not in kinds
    s = p.snapshot()
    assert s["pump1_seconds"] > 0.0
    # several pumping cycles: level went up to WY and back to NY more than once
    starts = sum(1 for a, b in zip(levels, levels[1:], strict=False) if a < p.heights[0] <= b)
    assert starts >= 2


def test_surge_needs_the_second_and_third_pump_and_they_cope() -> None:
    p = Sump(inflow_noise=0.0)
    prog = TextbookProgram(qt=300.0)
    _run(p, prog, 1800)
    p.inject("inflow_surge", factor=3.5)
    levels = _run(p, prog, 3 * 3600)
    s = p.snapshot()
    assert s["pump2_seconds"] > 0 and s["pump3_seconds"] > 0
    assert max(levels) < p.depth
    assert "flooded" not in [e.kind for e in p.drain_events()]


def test_pump_failures_lead_to_emergency_level() -> None:
    p = Sump(inflow_noise=0.0, inflow=0.05)
    for i in (1, 2, 3):
        p.inject(f"pump{i}_fail")
    prog = TextbookProgram()
    _run(p, prog, 3 * 3600)
    kinds = [e.kind for e in p.drain_events()]
    assert "emergency_level" in kinds and "flooded" in kinds
    s = p.snapshot()
    assert s["volume_overflow"] > 0
    books = s["volume_in"] - s["volume_out"] - s["volume_overflow"]
    assert books == pytest.approx(s["volume"] - s["volume0"], rel=1e-6)


def test_priming_and_dry_run() -> None:
    p = Sump(level0=1.0, inflow=0.0, inflow_noise=0.0, priming_time=20.0)
    p["NS1"] = True
    p.step(1.0)
    assert p["DAWL"] is False
    assert "pump_dry_run" in [e.kind for e in p.drain_events()]
    assert p.snapshot()["q_pump1"] == 0.0
    p["ZAL"] = True
    _run(p, None, 19.0)
    assert p["DAWL"] is False
    _run(p, None, 2.0)
    assert p["DAWL"] is True
    p["ZAL"] = False
    _run(p, None, 20.0)
    assert p.snapshot()["q_pump1"] > 0.0
    # pumping below the intake loses the prime
    _run(p, None, 2000.0)
    kinds = [e.kind for e in p.drain_events()]
    assert "lost_prime" in kinds
    assert p["DAWL"] is False
    assert p["LEVEL"] == pytest.approx(p.intake_height, abs=0.05)


def test_pump_curve_flow_rises_with_level() -> None:
    p = Sump(inflow_noise=0.0)
    assert p._pump_flow(0.0) == pytest.approx(p.pump_q_nom)
    assert p._pump_flow(4.0) > p._pump_flow(1.0)


def test_pressure_switch_stuck_and_priming_fail() -> None:
    p = Sump(level0=1.0, inflow=0.0, inflow_noise=0.0)
    p.inject("pressure_switch_stuck", value=True)
    assert p["DAWL"] is True
    p.clear("pressure_switch_stuck")
    p.inject("priming_fail")
    p["ZAL"] = True
    _run(p, None, 60.0)
    assert p["DAWL"] is False
    p.clear("priming_fail")
    _run(p, None, 30.0)
    assert p["DAWL"] is True
    p.inject("pressure_switch_stuck")
    assert p["DAWL"] is False
