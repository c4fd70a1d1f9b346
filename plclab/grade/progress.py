"""What ``plclab grade`` shows in the terminal: a progress bar while it grades and the summary
table at the end (used by :mod:`plclab.grade.commands`)."""

from __future__ import annotations

import sys
import time
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .grader import Outcome


class ProgressBar:
    """A one-line progress bar with rate and ETA (only used when stdout is a terminal).
    Unchanged submissions count as done but not in the rate: it is the grading's speed."""

    def __init__(self, stream: Any = None, width: int = 30) -> None:
        self.stream = stream or sys.stdout
        self.width = width
        self.t0 = time.monotonic()
        self.graded = 0

    def line(self, done: int, total: int, student: str, oc: Outcome, now: float) -> str:
        """The bar's text after ``done`` of ``total`` submissions."""
        self.graded += 0 if oc.skipped else 1
        frac = done / total if total else 1.0
        n = int(round(frac * self.width))
        bar = "#" * n + "." * (self.width - n)
        el = max(now - self.t0, 1e-9)
        rate = self.graded / el * 60
        eta = (total - done) / (self.graded / el) if self.graded else None
        what = "skipped" if oc.skipped else f"{oc.result.score:g}/{oc.result.max_score:g}"
        left = "--" if eta is None else _clock(eta)
        return (f"\r[{bar}] {done}/{total} {_clock(el)} {rate:5.0f}/min ETA {left:>5}  "
                f"{student[:20]:<20} {what:<10}")

    def __call__(self, done: int, total: int, student: str, oc: Outcome) -> None:
        self.stream.write(self.line(done, total, student, oc, time.monotonic()))
        if done == total:
            self.stream.write("\n")
        self.stream.flush()


def _clock(seconds: float) -> str:
    """``m:ss`` (or ``h:mm:ss``).

    >>> _clock(75.2), _clock(3725)
    ('1:15', '1:02:05')
    """
    s = int(round(seconds))
    h, rest = divmod(s, 3600)
    m, sec = divmod(rest, 60)
    return f"{h}:{m:02d}:{sec:02d}" if h else f"{m}:{sec:02d}"


def summary_table(outcomes: list[Outcome]) -> str:
    """The end-of-run table: student, score, status, time."""
    rows = [("student", "score", "status", "time")]
    for o in outcomes:
        r = o.result
        rows.append((r.student, f"{r.score:g}/{r.max_score:g}",
                     r.status + (" (unchanged)" if o.skipped else ""),
                     "-" if o.skipped else f"{o.wall_s:.1f} s"))
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    lines = []
    for i, row in enumerate(rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip())
        if i == 0:
            lines.append("  ".join("-" * w for w in widths))
    graded = list(outcomes)
    if graded:
        scores = [o.result.score for o in graded]
        mx = graded[0].result.max_score
        lines.append("")
        lines.append(f"{len(graded)} submissions, mean {sum(scores) / len(scores):.1f}/{mx:g}, "
                     f"{sum(1 for s in scores if s >= mx)} with full marks")
    return "\n".join(lines)
