"""The failure diagram: the failed criterion's own signals are never dropped by the cap on the
number of rows; the one-Axes drawing gives a PNG with one band per signal."""

from __future__ import annotations

from plclab.grade.feedback import MAX_SIGNALS, diagram_names, timing_png
from plclab.grade.lab import load_lab


class _AnyTrace:
    """A trace that has every signal under its own name."""

    io: list = []

    def __contains__(self, name: str) -> bool:
        return True

    def resolve(self, name: str) -> str:
        return name


def test_the_failed_criterions_signal_survives_the_row_cap():
    lab = load_lab("ventilation-fans")
    crit = next(c for c in lab.criteria if c.name == "fault lamp flashes at 5 Hz")
    assert len(lab.diagram_signals) >= MAX_SIGNALS  # the cap would cut the lamp off
    names = diagram_names(_AnyTrace(), lab, crit)
    assert "FAULT_LAMP" in names and len(names) == MAX_SIGNALS
    assert names == [n for n in lab.diagram_signals if n in names]  # in the lab's order


def test_a_failure_diagram_is_a_png_of_the_signals(tmp_path):
    import numpy as np

    from plclab.trace import Trace

    t = np.arange(0, 60, 0.01)
    trace = Trace(t, {"LEVEL": np.sin(t / 5) + 1.0, "PUMP": np.sin(t) > 0},
                  {"LEVEL": "float", "PUMP": "bool"})
    path = tmp_path / "f.png"
    fig_path = tmp_path / "g.png"
    timing_png(trace, ["LEVEL", "PUMP"], path, 10.0, 30.0, [(20.0, "no overflow fails")],
               "normal: no overflow", None, {"LEVEL": [(1.75, "limit")]})
    timing_png(trace, ["LEVEL"], fig_path, 10.0, 30.0, [], "one row", None, None)
    assert path.read_bytes().startswith(b"\x89PNG")
    from PIL import Image

    tall, short = Image.open(path).size, Image.open(fig_path).size
    assert tall[0] == short[0] and tall[1] > short[1]  # one band per signal
