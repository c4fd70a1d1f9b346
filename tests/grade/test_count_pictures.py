"""A criterion that counts draws what it expects beside what the run counted (issue 32):
``at most 30 switchings, switched 41``; a counter also gets the plant's count as a dashed line
on its own row. Read back from the SVG the failure diagram writes."""

from __future__ import annotations

import re

import numpy as np
import pytest

from plclab.grade.feedback import counted_limits, criterion_picture, timing_png
from plclab.grade.lab import load_lab
from plclab.trace import Event, Trace


def _crit(lab: str, name: str):
    return next(c for c in load_lab(lab).criteria if c.name == name)


def _counter_trace(good: int, binned: int) -> Trace:
    """GOOD (%MW0) counts to ``good`` while the plant bins ``binned`` unfilled bottles."""
    t = np.arange(0.0, 40.0, 0.1)
    counts = np.minimum((t // 2).astype(int), good)
    evs = [Event(1.0 + 3.0 * k, "bottle_binned", "plant", f"bottle {k}",
                 {"result": "unfilled_passed"}) for k in range(binned)]
    evs.append(Event(2.5, "bottle_binned", "plant", "a fallen one", {"result": "fallen"}))
    return Trace(t, {"%MW0": counts}, {"%MW0": "int"}, {"period": 0.1}, evs)


def _texts(svg) -> str:
    return " ".join(re.findall(r"<text[^>]*>([^<]*)</text>", svg.read_text(encoding="utf-8")))


def test_a_counter_shows_the_plants_count_and_its_own():
    crit = _crit("bottle-reject", "counts good bottles")
    lims = counted_limits(_counter_trace(good=9, binned=6), crit, [])
    assert lims == []  # nothing to extend: no invention
    from plclab.grade.criteria import criterion_limits

    lims = counted_limits(_counter_trace(good=9, binned=6), crit, criterion_limits(crit))
    words = " ".join(lim.label for lim in lims)
    assert "the plant counted 6" in words and "%MW0 = 9" in words  # the fallen one not counted
    line = [lim for lim in lims if lim.kind == "level"]
    assert [(x.signal, x.value) for x in line] == [("%MW0", 6.0)]


def test_switchings_and_events_show_the_count_of_the_run():
    sw = _crit("relay-thermostat", "few relay operations")
    t = np.arange(0.0, 100.0, 0.1)
    heater = (np.arange(t.size) // 5) % 2 == 1  # 0.5 s on, 0.5 s off: 199 switchings
    tr = Trace(t, {"HEATER": heater}, {"HEATER": "bool"}, {"period": 0.1})
    from plclab.grade.criteria import criterion_limits

    words = " ".join(x.label for x in counted_limits(tr, sw, criterion_limits(sw)))
    n = int(np.count_nonzero(np.diff(heater.astype(int))))
    assert f"at most 30 switchings, switched {n}" in words
    ev = _crit("press-safety", "no stroke below the melt temperature")
    tr2 = Trace(t, {"X": heater}, {"X": "bool"}, {"period": 0.1},
                [Event(3.0, "cold_extrusion", "plant", "a"), Event(5.0, "cold_extrusion", "plant",
                                                                  "b")])
    words = " ".join(x.label for x in counted_limits(tr2, ev, criterion_limits(ev)))
    assert "at most 0 cold extrusion events, counted 2" in words


def test_a_criterion_that_does_not_count_is_left_alone():
    crit = _crit("relay-thermostat", "few relay operations")
    other = next(c for c in load_lab("relay-thermostat").criteria
                 if c.check not in ("event_count", "counter", "max_switchings", "no_chatter"))
    from plclab.grade.criteria import criterion_limits

    lims = criterion_limits(other)
    assert counted_limits(_counter_trace(3, 3), other, lims) == lims
    assert crit.check == "max_switchings"


@pytest.mark.parametrize("good,binned", [(9, 6), (4, 7)])
def test_the_failure_diagram_draws_both_counts(tmp_path, good, binned):
    pytest.importorskip("matplotlib")
    crit = _crit("bottle-reject", "counts good bottles")
    tr = _counter_trace(good, binned)
    svg = tmp_path / "count.svg"
    timing_png(tr, ["%MW0"], svg, 0.0, tr.t_end, [(40.0, "counts good bottles fails")],
               "run: counts good bottles (FAILED)", {"%MW0": "GOOD %MW0"},
               drawing=criterion_picture(tr, crit, ["%MW0"]))
    text = _texts(svg)
    assert f"the plant counted {binned}" in text and f"%MW0 = {good}" in text
    assert "GOOD %MW0" in text
