"""The student's picture (issue 15): marker labels that never overlap, analog integers as
lines, digital series reduced to their changes, the limits of a criterion as thresholds."""

from __future__ import annotations

from plclab.grade.feedback import thresholds_of
from plclab.grade.lab import load_lab
from plclab.viz.series import Series
from plclab.viz.timing import _as_analog, marker_labels


def _overlap(labels, lo, hi, chars_per_span=110.0):
    span = hi - lo
    rows: dict[int, list[tuple[float, float]]] = {}
    for t, text, row in labels:
        a, b = t, t + (len(text) + 1) / chars_per_span * span
        if any(a < e and s < b for s, e in rows.get(row, [])):
            return True
        rows.setdefault(row, []).append((a, b))
    return False


def test_marker_labels_merge_equal_ones_and_never_overlap():
    markers = [(10.0, "chatter"), (10.5, "chatter"), (11.0, "chatter"), (10.2, "PLC fault"),
               (10.3, "no overflow fails"), (50.0, "chatter"), (200.0, "outside")]
    labels = marker_labels(markers, 0.0, 100.0)
    texts = [t for _, t, _ in labels]
    assert "chatter x3" in texts and texts.count("chatter") == 1  # the one at 50 s
    assert "outside" not in texts
    assert not _overlap(labels, 0.0, 100.0)
    assert len({row for _, _, row in labels}) >= 2  # close labels went up a row


def test_analog_integers_are_lines_and_bools_keep_only_their_changes():
    counts = Series("%IW64", [i * 0.1 for i in range(100)], [8000 + i * 3 for i in range(100)],
                    "int")
    assert _as_analog(counts).kind == "real"
    mode = Series("STEP", [0.0, 1.0, 2.0, 3.0], [1, 1, 2, 2], "int")
    assert _as_analog(mode).kind == "int"
    b = Series("PUMP", [i * 0.1 for i in range(1000)], [i >= 500 for i in range(1000)], "bool")
    c = _as_analog(b)
    assert list(c.times) == [0.0, 50.0] and list(c.values) == [False, True]


def test_thresholds_come_from_the_criteria():
    tank = load_lab("tank-two-position")
    crit = {c.name: c for c in tank.criteria}
    assert thresholds_of(crit["no overflow"]) == {"LEVEL": [(1.75, "never >= 1.75")]}
    both = thresholds_of(crit["level between the switches"])
    assert sorted(v for v, _ in both["LEVEL"]) == [0.4, 1.6]
