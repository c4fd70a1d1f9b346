"""Command-line sub-commands ``plclab sim`` and ``plclab plants``.

``plclab sim PLANT PROGRAM... [--wiring FILE] [--scenario FILE] [--duration 10min] [--scan 10ms]
[--seed N] [--watch A,B] [--trace out.npz] [--csv out.csv]`` runs a simulation and prints a
short summary (``--rrd/--vcd/--wavedrom/--png`` hand the trace to :mod:`plclab.viz`);
``plclab plants [NAME]`` lists the plants and their signals.
"""

from __future__ import annotations

import argparse
import sys

from plclab.cli_registry import arg, command
from plclab.errors import PlcError
from plclab.names import split_names


def _param(text: str) -> tuple[str, object]:
    import tomllib

    if "=" not in text:
        raise PlcError("PLC4020", f"--param {text}: write NAME=VALUE, e.g. --param area=2.0")
    name, _, value = text.partition("=")
    try:
        v = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        v = value.strip()
    return name.strip(), v


@command("sim")
@arg("plant", metavar="PLANT", help="plant name (see: plclab plants)")
@arg("programs", nargs="+", metavar="PROGRAM", help="ST source files")
@arg("--wiring", metavar="FILE", default=None,
     help="wiring table (TOML); default: the plant's default wiring")
@arg("--scenario", metavar="FILE", default=None, help="scenario (TOML): actions, faults, until")
@arg("--duration", default=None,
     help="simulated time, e.g. 90s, 10min, 1h, T#1m (default: the scenario's, else 10min)")
@arg("--scan", default=None, help="PLC scan (cycle) time, e.g. 10ms (default)")
@arg("--dt", default=None, help="plant sub-step (default: min(scan, plant max_dt))")
@arg("--seed", type=int, default=None, help="random seed (default: the scenario's, else 0)")
@arg("--image-size", type=int, default=None, metavar="BYTES",
     help="bytes of each process image area, 8 to 65536 (default: sized from the program's "
     "addresses, at least 1024)")
@arg("--watch", default=None, metavar="A,B", help="PLC variables to record")
@arg("--watch-table", default=None, metavar="FILE",
     help="a watch table (TOML) sampled at its trigger point into the trace (plclab.scada)")
@arg("--alarms", default=None, metavar="FILE",
     help="an alarm configuration (TOML): the alarm log goes into the trace (plclab.scada)")
@arg("--until", default=None, metavar="EXPR", help="stop when this holds, e.g. 'LEVEL > 1.9'")
@arg("--param", action="append", default=[], metavar="NAME=VALUE",
     help="plant parameter, e.g. --param area=2.0 (repeatable)")
@arg("--trace", default=None, metavar="OUT.npz", help="save the trace (.npz)")
@arg("--csv", default=None, metavar="OUT.csv", help="export the trace as CSV")
@arg("--decimate", type=int, default=1, help="record every n-th scan (default 1)")
@arg("--snapshot", action="store_true", help="also record the plant's snapshot() extras")
@arg("--events", action="store_true", help="print every event, not only the counts")
@arg("--rrd", default=None, metavar="OUT.rrd", help="rerun timeline (needs plclab[viz])")
@arg("--vcd", default=None, metavar="OUT.vcd", help="VCD waveform (needs plclab[viz])")
@arg("--wavedrom", default=None, metavar="OUT.json", help="WaveDrom timing diagram (viz)")
@arg("--png", default=None, metavar="OUT.png", help="timing diagram picture (viz)")
@arg("--signals", default=None, metavar="A,B", help="columns for the viz exports")
@arg("--window", default=None, metavar="T0..T1", help="time window of the viz exports, "
     "e.g. 0s..20s")
@arg("--spawn", action="store_true", help="stream the run live into the rerun viewer")
@arg("--speed", type=float, default=None, help="with --spawn: pace the run to the wall clock "
     "(1.0 = real time, 10 = ten times faster)")
def cmd_sim(ns: argparse.Namespace) -> int:
    from .durations import format_duration, parse_ns
    from .runner import load_plc
    from .scenario import as_scenario
    from .simulation import Simulation

    sc = as_scenario(ns.scenario)
    scan = ns.scan if ns.scan is not None else sc.scan  # None: the PLC's own cycle
    if scan is not None:
        parse_ns(scan, "--scan", allow_zero=False)
    if ns.duration is not None:
        parse_ns(ns.duration, "--duration", allow_zero=False)
    plc = load_plc(ns.programs, cycle_time=scan if scan is not None else "10ms",
                   image_size=ns.image_size)
    for d in getattr(plc.compiled, "diagnostics", []):
        if d.severity != "error":
            print(str(d), file=sys.stderr)
    params = dict(_param(p) for p in ns.param) if ns.param else None
    watch = split_names(ns.watch) if ns.watch else []
    sim = Simulation(plc, ns.plant, ns.wiring, scan, ns.dt, ns.seed, scenario=sc, watch=watch,
                     snapshot=ns.snapshot or None, decimate=ns.decimate,
                     plant_params=params)
    for w in sim.warnings:
        print(f"note: {w}", file=sys.stderr)
    # -- SCADA hooks (plclab.scada, ADR 0025)
    table = alarms = None
    if ns.watch_table:
        from plclab.process import WatchTable

        table = sim.add_hook(WatchTable.load(ns.watch_table))
    if ns.alarms:
        from plclab.process import AlarmServer

        alarms = sim.add_hook(AlarmServer.load(ns.alarms))
    duration = ns.duration
    if duration is None and sc.duration_ns is None:
        duration = "10min"
    if ns.spawn:
        from plclab.viz.live import run_live

        tr = run_live(sim, duration, ns.until, spawn=True, speed=ns.speed,
                      names=split_names(ns.signals) if ns.signals else None)
    else:
        tr = sim.run(duration, ns.until)
    wall = tr.wall.get("run_s", 0.0) or 1e-9
    print(f"{sim.plant.name}: {format_duration(tr.t_end)} simulated in {wall:.2f} s "
          f"({tr.t_end / wall:,.0f}x real time), {sim.k} scans of "
          f"{format_duration(sim.scan)}, seed {sim.seed}")
    print(f"wiring: {sim.wiring.source or 'default for ' + sim.plant.name} "
          f"({len(sim.wiring)} rows)" + (f"; scenario: {sc.source}" if sc.source else ""))
    if sim.plc.fault is not None:
        print(f"PLC FAULT: {sim.plc.fault}")
    print(tr.summary().split("\n", 1)[1])
    if ns.events and tr.events:
        print("all events:")
        for e in tr.events:
            print(f"  {e}")
    if alarms is not None:
        print(f"alarm log ({len(alarms.log)} entries):")
        for entry in alarms.log:
            print(f"  {entry}")
    if table is not None and table.samples:
        print(f"watch table {table.name} ({table.trigger}, {len(table.samples)} samples), last:")
        print("  " + table.show().replace("\n", "\n  "))
    watched = [c for c in tr.names if c in sim.watch or c.startswith("plc:")]
    if watched:
        print("watched (final):")
        for c in watched:
            print(f"  {c:<16} {tr[c][-1].item()}")
    if ns.trace:
        tr.save(ns.trace)
        print(f"trace saved to {ns.trace}")
    if ns.csv:
        tr.to_csv(ns.csv)
        print(f"CSV written to {ns.csv}")
    if ns.rrd or ns.vcd or ns.wavedrom or ns.png:
        try:
            from plclab.viz import export
        except ImportError:
            raise PlcError("PLC4020", "--rrd/--vcd/--wavedrom/--png need plclab.viz: "
                           "pip install 'plclab[viz]'") from None
        signals = split_names(ns.signals) if ns.signals else None
        for line in export(tr, rrd=ns.rrd, vcd=ns.vcd, wavedrom=ns.wavedrom, png=ns.png,
                           signals=signals, window=ns.window):
            print(line)
    return 0


@command("plants")
@arg("name", nargs="?", default=None, metavar="NAME", help="one plant: signals, faults, events, "
     "default wiring")
def cmd_plants(ns: argparse.Namespace) -> int:
    from plants import PLANTS, get_plant

    from .errors import did_you_mean, sim_error
    from .wirings import DEFAULTS, default_wiring

    names = list(PLANTS)
    if ns.name is not None:
        if ns.name not in PLANTS:
            raise sim_error("PLC4020", f"unknown plant {ns.name!r}.{did_you_mean(ns.name, PLANTS)}"
                            f" Plants: {', '.join(PLANTS)}")
        names = [ns.name]
    for i, name in enumerate(names):
        p = get_plant(name)
        if i:
            print()
        print(f"{name} — {p.title}")
        print(f"  {'signal':<14} {'kind':<9} {'type':<5} {'unit':<6} {'range':<14} description")
        for s in p.signals.values():
            rng = "" if s.type == "bool" else f"{s.range[0]:g}..{s.range[1]:g}"
            print(f"  {s.name:<14} {s.kind:<9} {s.type:<5} {s.unit:<6} {rng:<14} "
                  f"{s.description}")
        if ns.name is not None:
            print("faults:")
            for f, d in p.faults.items():
                print(f"  {f:<24} {d}")
            print("events:")
            for e, d in p.events.items():
                print(f"  {e:<24} {d}")
            if name in DEFAULTS:
                print(f"default wiring (plclab/sim/wirings/{name}.toml):")
                for line in default_wiring(name).table().splitlines():
                    print(f"  {line}")
            print(f"max_dt: {p.max_dt:g} s")
    return 0
