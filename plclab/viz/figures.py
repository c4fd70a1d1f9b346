"""Timing diagrams of the standard timers and counters, generated from real PLC runs.

The textbook draws them by hand (``001_c648febd3bbd6efb.txt``, Figs 42-48, lines 3196-3434);
here each figure is the trace of the real function block driven by an input pattern, so the
picture can never disagree with the implementation.

>>> from plclab.viz.figures import block_run
>>> t, cols = block_run("TON")
>>> max(cols["ET"]) == 0.3      # ET stops at PT = 300 ms
True
"""

from __future__ import annotations

from pathlib import Path

from .series import Series

# input patterns: (start s, end s) intervals where the input is TRUE, sampled every 10 ms
_PATTERNS = {
    "TP": {"IN": [(0.1, 0.2), (0.25, 0.3), (0.6, 1.0)]},
    "TON": {"IN": [(0.1, 0.3), (0.4, 0.9)]},
    "TOF": {"IN": [(0.1, 0.2), (0.3, 0.4), (0.5, 0.6)]},
    "TONR": {"IN": [(0.1, 0.25), (0.4, 0.55), (0.7, 0.8)], "R": [(0.9, 0.95)]},
    "CTU": {"CU": [(0.1, 0.15), (0.2, 0.25), (0.3, 0.35), (0.4, 0.45), (0.6, 0.65)],
            "R": [(0.8, 0.85)]},
    "CTD": {"LD": [(0.05, 0.1)], "CD": [(0.2, 0.25), (0.3, 0.35), (0.4, 0.45), (0.5, 0.55)]},
    "CTUD": {"CU": [(0.1, 0.15), (0.2, 0.25), (0.3, 0.35), (0.4, 0.45)],
             "CD": [(0.55, 0.6), (0.65, 0.7)], "R": [(0.85, 0.9)]},
}
_OUTPUTS = {"TP": ["Q", "ET"], "TON": ["Q", "ET"], "TOF": ["Q", "ET"], "TONR": ["Q", "ET"],
            "CTU": ["Q", "CV"], "CTD": ["Q", "CV"], "CTUD": ["QU", "QD", "CV"]}
_PARAM = {"TP": "PT := T#300ms", "TON": "PT := T#300ms", "TOF": "PT := T#300ms",
          "TONR": "PT := T#300ms", "CTU": "PV := 3", "CTD": "PV := 3", "CTUD": "PV := 3"}
BLOCKS = tuple(_PATTERNS)


def block_run(block: str, duration: float = 1.1, cycle_ms: int = 10):
    """Run one standard block in a real PLC with the figure's input pattern.

    Returns (times, columns) with the inputs, outputs and ET in seconds.
    """
    import plclab

    if block not in _PATTERNS:
        raise ValueError(f"no figure for {block}; choose one of {', '.join(BLOCKS)}")
    ins = list(_PATTERNS[block])
    outs = _OUTPUTS[block]
    decl = " ".join(f"{n} : BOOL;" for n in ins)
    call = ", ".join([f"{n} := {n}" for n in ins] + [_PARAM[block]])
    plc = plclab.loads(f"PROGRAM Fig VAR b : {block}; {decl} END_VAR\n"
                       f"b({call});\nEND_PROGRAM", f"{block.lower()}.st",
                       cycle_time=f"{cycle_ms}ms")
    times: list[float] = []
    cols: dict[str, list] = {n: [] for n in ins + outs}
    for k in range(int(round(duration * 1000 / cycle_ms))):
        t = k * cycle_ms / 1000
        for n in ins:
            plc[f"Fig.{n}"] = any(a <= t + 1e-9 < b for a, b in _PATTERNS[block][n])
        plc.scan()
        times.append(round(t, 6))
        for n in ins:
            cols[n].append(plc[f"Fig.{n}"])
        for n in outs:
            v = plc[f"Fig.b.{n}"]
            cols[n].append(v / 1000 if n == "ET" else v)
    return times, cols


def block_figure(block: str, path: str | Path | None = None):
    """The timing diagram of ``block`` (TP, TON, TOF, TONR, CTU, CTD, CTUD) from a real run."""
    from .timing import timing_diagram

    times, cols = block_run(block)
    series = []
    for name, vals in cols.items():
        if name == "ET":
            series.append(Series("ET", times, vals, "real", "s"))
        elif name == "CV":
            series.append(Series("CV", times, vals, "int"))
        else:
            series.append(Series(name, times, vals, "bool"))
    return timing_diagram(series, path, title=f"{block} ({_PARAM[block]}), 10 ms scans",
                          width=7.0)


def write_all(folder: str | Path, fmt: str = "svg") -> list[Path]:
    """Write every block's figure into ``folder`` (for the course and the docs)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = []
    for b in BLOCKS:
        p = folder / f"{b.lower()}.{fmt}"
        block_figure(b, p)
        out.append(p)
    return out
