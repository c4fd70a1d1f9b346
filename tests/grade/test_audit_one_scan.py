"""The audit's one-scan rule (ADR 0049): a mutant whose signals differ from the solution's only
by edges moved by at most one scan is equivalent at the PLC's resolution; a real timing mistake
(a preset off by 10 %), a lamp that goes dark for a scan, an extra edge or an analog signal
that moves differently is a change of behaviour."""

import numpy as np
import pytest

from plclab.grade.audit import CAUGHT, Run, within_one_scan

SCAN = 0.05


def run(t_end=10.0, outputs=None, **cols):
    n = int(round(t_end / SCAN))
    sig = {k: np.asarray(v(np.arange(n) * SCAN) if callable(v) else v) for k, v in cols.items()}
    return Run(sig, np.arange(n) * SCAN, t_end, SCAN, outputs or sorted(sig))


def between(a, b):
    return lambda t: (t >= a - 1e-9) & (t < b - 1e-9)


def test_an_edge_moved_by_one_scan_is_equivalent():
    sol = run(G=between(1.0, 4.0), Y=between(4.0, 7.0))
    assert within_one_scan(run(G=between(1.0, 4.0), Y=between(4.0, 7.0)), sol)
    # the yellow phase one scan longer: it ends a scan later
    assert within_one_scan(run(G=between(1.0, 4.0), Y=between(4.0, 7.05)), sol)
    # the whole cycle starts a scan later (both edges of both lamps move together)
    assert within_one_scan(run(G=between(1.05, 4.05), Y=between(4.05, 7.05)), sol)


def test_a_phase_a_scan_longer_in_every_cycle_is_equivalent():
    """The drift adds up over cycles, each phase stays right within a scan."""
    def cycle(extra):
        def f(t):
            out = np.zeros(len(t), bool)
            for k in range(4):
                start = k * (2.0 + extra)
                out |= between(start, start + 1.0 + extra)(t)
            return out
        return f
    assert within_one_scan(run(L=cycle(SCAN)), run(L=cycle(0.0)))
    assert not within_one_scan(run(L=cycle(3 * SCAN)), run(L=cycle(0.0)))


@pytest.mark.parametrize("mutant", [
    dict(G=between(1.0, 4.0), Y=between(4.0, 7.3)),  # yellow preset 10 % too long
    dict(G=between(1.0, 4.0), Y=between(4.0, 6.7)),  # 10 % too short
    dict(G=between(1.0, 4.0), Y=between(4.0, 7.1)),  # two scans
    dict(G=between(1.0, 4.0), Y=between(4.05, 7.0)),  # dark for a scan between the lamps
    dict(G=between(1.0, 4.05), Y=between(4.0, 7.0)),  # both lit for a scan
    dict(G=between(1.0, 4.0), Y=lambda t: between(4.0, 7.0)(t) | between(8.0, 8.05)(t)),
    dict(G=between(1.0, 4.0), Y=np.zeros(200, bool)),  # yellow never lights
])
def test_real_timing_and_combination_changes_are_not_equivalent(mutant):
    sol = run(G=between(1.0, 4.0), Y=between(4.0, 7.0))
    assert not within_one_scan(run(**mutant), sol)


def test_an_input_edge_a_scan_apart_from_an_output_edge_is_below_the_resolution():
    """A plant input that fell on the same scan as an output edge may come a scan apart;
    two outputs may not."""
    sol = run(outputs=["G"], G=between(1.0, 4.0), S=between(2.0, 4.0))
    assert within_one_scan(run(outputs=["G"], G=between(1.0, 4.05), S=between(2.0, 4.0)), sol)
    both = run(G=between(1.0, 4.0), S=between(2.0, 4.0))  # S an output too
    assert not within_one_scan(run(G=between(1.0, 4.05), S=between(2.0, 4.0)), both)


def test_an_edge_pushed_past_the_end_and_analog_signals():
    sol = run(L=between(9.95, 10.0))
    assert within_one_scan(run(L=np.zeros(200, bool)), sol)
    ramp = run(T=lambda t: 20.0 + t)
    assert within_one_scan(run(T=lambda t: 20.0 + t), ramp)
    assert not within_one_scan(run(T=lambda t: 20.0 + np.maximum(t - SCAN, 0.0)), ramp)


@pytest.fixture(scope="module")
def crossing():
    from plclab.grade.engine import grade_sources
    from plclab.grade.lab import load_lab

    lab = load_lab("pedestrian-crossing")
    text = (lab.path / "solution" / "crossing.st").read_text(encoding="utf-8")
    base = grade_sources(lab, [(text, "s.st")], media_dir=None, rrd=False, keep_traces=True)

    def grade(old, new):
        assert old in text
        res = grade_sources(lab, [(text.replace(old, new), "m.st")], media_dir=None,
                            rrd=False, keep_traces=True)
        same = all(within_one_scan(Run.of(tr), Run.of(base.traces[n]))
                   for n, tr in res.traces.items())
        return same, res.score / res.max_score
    return grade


def test_crossing_a_step_time_one_scan_later_is_equivalent(crossing):
    assert crossing("CarsYellow.T >= T#3s", "CarsYellow.T > T#3s")[0]
    assert crossing("RedYellow.T >= T#1500ms", "RedYellow.T > T#1500ms")[0]


@pytest.mark.parametrize("old, new", [
    ("CarsYellow.T >= T#3s", "CarsYellow.T >= T#3300ms"),  # yellow 10 % too long
    ("CarsYellow.T >= T#3s", "CarsYellow.T >= T#2700ms"),  # 10 % too short
    ("CarsGreen.T >= T#20s", "CarsGreen.T >= T#18s"),  # minimum green 10 % short
    ("AllRed.T >= T#2s", "AllRed.T >= T#1800ms"),
])
def test_crossing_a_preset_off_by_ten_percent_changes_behaviour_and_is_caught(crossing, old,
                                                                              new):
    same, share = crossing(old, new)
    assert not same and share <= CAUGHT
