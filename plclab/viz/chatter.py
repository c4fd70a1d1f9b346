"""Relay chatter and contact bounce analysis on step series.

Per digital output: switchings per minute, minimum on/off dwell, chatter episodes (at least
``min_toggles`` changes within ``window`` seconds), relay operations (closures, i.e. wear).
Per digital input: bounce bursts in the raw contact signal versus the edges the PLC saw after its
input filter.

>>> from plclab.viz.series import Series
>>> s = Series("K1", [0, 1, 1.1, 1.2, 1.3, 5], [0, 1, 0, 1, 0, 1], "bool")
>>> st = output_stats(s, duration=6.0)
>>> st.switchings, st.operations, round(st.min_on, 3), len(st.episodes)
(5, 3, 0.1, 1)
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .series import Series


@dataclass
class OutputStats:
    name: str
    switchings: int
    operations: int  # FALSE -> TRUE transitions (contact closures: relay wear)
    per_minute: float
    min_on: float | None
    min_off: float | None
    episodes: list[tuple[float, float, int]] = field(default_factory=list)  # (t0, t1, toggles)

    @property
    def chatters(self) -> bool:
        return bool(self.episodes)

    def line(self) -> str:
        on = "-" if self.min_on is None else f"{self.min_on * 1000:.0f} ms"
        off = "-" if self.min_off is None else f"{self.min_off * 1000:.0f} ms"
        chat = f", {len(self.episodes)} chatter episode(s)" if self.episodes else ""
        return (f"{self.name}: {self.switchings} switchings ({self.per_minute:.1f}/min), "
                f"{self.operations} operations, min on {on}, min off {off}{chat}")


def edges(series: Series) -> list[tuple[float, bool]]:
    """Times at which a BOOL series changes, with the new value (the first sample excluded)."""
    ch = series.changes()
    return [(t, bool(v)) for t, v in ch[1:]]


def chatter_episodes(times: list[float], min_toggles: int = 4,
                     window: float = 10.0) -> list[tuple[float, float, int]]:
    """Maximal runs in which every ``min_toggles`` consecutive changes fit in ``window`` s."""
    out: list[tuple[float, float, int]] = []
    n = len(times)
    i = 0
    while i + min_toggles <= n:
        if times[i + min_toggles - 1] - times[i] <= window:
            j = i + min_toggles - 1
            while j + 1 < n and times[j + 1] - times[j + 2 - min_toggles] <= window:
                j += 1
            out.append((times[i], times[j], j - i + 1))
            i = j + 1
        else:
            i += 1
    return out


def output_stats(series: Series, duration: float | None = None, min_toggles: int = 4,
                 window: float = 10.0) -> OutputStats:
    """Switching statistics of one digital output."""
    e = edges(series)
    times = [t for t, _ in e]
    if duration is None:
        duration = (series.times[-1] - series.times[0]) if len(series.times) > 1 else 0.0
    ops = sum(1 for _, v in e if v)
    per_min = len(e) / duration * 60 if duration else 0.0
    return OutputStats(series.name, len(e), ops, per_min, min_dwell(e, True),
                       min_dwell(e, False), chatter_episodes(times, min_toggles, window))


def min_dwell(e: list[tuple[float, bool]], on: bool) -> float | None:
    """Shortest complete ON (or OFF) interval between two edges; the interval before the first
    edge and after the last are censored (their start or end is unknown) and left out."""
    full = [e[k][0] - e[k - 1][0] for k in range(1, len(e)) if e[k - 1][1] == on]
    return min(full) if full else None


@dataclass
class BounceStats:
    name: str
    physical_edges: int
    raw_edges: int
    plc_edges: int
    bursts: list[tuple[float, float, int]]

    def line(self) -> str:
        return (f"{self.name}: contact switched {self.physical_edges}x, raw signal toggled "
                f"{self.raw_edges}x in {len(self.bursts)} bounce burst(s), the PLC saw "
                f"{self.plc_edges} edge(s) after its input filter")


def bounce_stats(name: str, raw: Series, plc: Series, physical: Series | None = None,
                 burst_gap: float = 0.010) -> BounceStats:
    """Compare the raw (bouncing) contact signal at 1 ms resolution with what the PLC saw."""
    raw_e = [t for t, _ in edges(raw)]
    bursts: list[tuple[float, float, int]] = []
    for t in raw_e:
        if bursts and t - bursts[-1][1] <= burst_gap:
            b = bursts[-1]
            bursts[-1] = (b[0], t, b[2] + 1)
        else:
            bursts.append((t, t, 1))
    bursts = [b for b in bursts if b[2] > 1]
    phys_n = len(edges(physical)) if physical is not None else 0
    return BounceStats(name, phys_n, len(raw_e), len(edges(plc)), bursts)


def report(outputs: list[Series], duration: float | None = None,
           inputs: list[BounceStats] | None = None) -> str:
    """A short text report: one line per output, then one per bouncing input."""
    lines = ["Relay / output switching:"]
    for s in outputs:
        lines.append("  " + output_stats(s, duration).line())
    if inputs:
        lines.append("Input bounce:")
        lines += ["  " + b.line() for b in inputs]
    return "\n".join(lines)
