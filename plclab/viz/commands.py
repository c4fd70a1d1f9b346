"""``plclab view TRACE.npz``: look at a saved run (rerun viewer if installed, or files)."""

from __future__ import annotations

import argparse

from ..cli_registry import arg, command
from ..errors import PlcError


@command("view")
@arg("trace", metavar="TRACE.npz", help="a trace saved by plclab sim --trace")
@arg("--rrd", help="write a rerun recording (.rrd) instead of opening the viewer")
@arg("--vcd", help="write a VCD file (GTKWave)")
@arg("--wavedrom", help="write WaveDrom WaveJSON")
@arg("--png", help="write a timing diagram (.png or .svg)")
@arg("--signals", help="signals, comma separated")
@arg("--window", help="time window, e.g. 0s..20s")
@arg("--report", action="store_true", help="print the relay chatter / switching report")
def cmd_view(ns: argparse.Namespace) -> int:
    from ..trace import load
    from .display import require_display
    from .from_trace import run_exports

    if not any(getattr(ns, k) for k in ("rrd", "vcd", "wavedrom", "png", "report")):
        require_display(f"'{ns.trace}'")  # before anything slow: no hanging, exit 1
    trace = load(ns.trace)
    print(trace.summary(finals=False) if hasattr(trace, "summary") else repr(trace))
    if ns.report:
        print(switching_report(trace))
    wants_files = any(getattr(ns, k) for k in ("rrd", "vcd", "wavedrom", "png"))
    if not wants_files:
        try:
            import rerun  # noqa: F401
        except ImportError:
            raise PlcError("PLC3005", "the rerun viewer is not installed: pip install "
                           "'plclab[viz]', or export files with --rrd/--png/--vcd") from None
        ns.spawn = True
    for line in run_exports(trace, ns):
        print(line)
    return 0


def switching_report(trace) -> str:
    """Relay chatter report of every digital output, and bounce of every bouncing input."""
    from .chatter import bounce_stats, report
    from .series import Series

    info = trace.meta.get("signal_info", {})
    outs = [Series(n, trace.time, trace.columns[n], "bool") for n in trace.columns
            if trace.kind(n) == "bool" and (n.startswith("%Q") or
                                             info.get(n, {}).get("kind") == "actuator")]
    inputs = []
    for key, (t, v) in trace.edges.items():
        if key.endswith(".raw"):
            base = key[:-4]
            filt = trace.edges.get(base + ".filtered")
            init = trace.meta.get("edge_initial", {})
            raw = Series(base + " raw", [0.0] + list(t), [init.get(key, False)] + list(v), "bool")
            if filt is not None:
                seen = Series(base, [0.0] + list(filt[0]),
                              [init.get(base + ".filtered", False)] + list(filt[1]), "bool")
            else:
                seen = Series(base, trace.time, trace.columns.get(base, []), "bool")
            inputs.append(bounce_stats(base, raw, seen))
    return report(outs, trace.t_end, [b for b in inputs if b.raw_edges])


@command("figures")
@arg("folder", help="where to write the pictures")
@arg("--format", default="svg", choices=["svg", "png"], help="picture format (default svg)")
@arg("--scan-cycle", action="store_true", help="also draw the scan-cycle diagram")
def cmd_figures(ns: argparse.Namespace) -> int:
    from pathlib import Path

    from .figures import write_all

    for p in write_all(ns.folder, ns.format):
        print(p)
    if ns.scan_cycle:
        from .timing import scan_cycle_diagram

        p = Path(ns.folder) / f"scan_cycle.{ns.format}"
        _, reaction = scan_cycle_diagram(p)
        print(f"{p} (reaction {reaction:.1f} ms)")
    return 0
