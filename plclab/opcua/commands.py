"""Command-line sub-command ``plclab opcua``: a running PLC behind an OPC UA server.

``plclab opcua PROGRAM... [--lab LAB | --plant NAME] [--scenario NAME|FILE]`` runs the
programs in real time (the operator panel's runner: plant, I/O modules, alarms) and serves
every variable on opc.tcp://127.0.0.1:4840/ (docs/opcua.md). asyncua is imported only when
the command runs.
"""

from __future__ import annotations

import argparse
import asyncio
import ipaddress
import math
import signal
import sys

from plclab.cli_registry import arg, command
from plclab.errors import PlcError


def check_endpoint(host: str, port: int, allow_remote: bool) -> None:
    """PLC7055 for a port outside 1..65535, PLC7052 for a non-loopback host without
    ``--allow-remote`` (0.0.0.0 serves every network the computer is on)."""
    if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
        raise PlcError("PLC7055", f"--port {port}: give a TCP port 1..65535 (4840 is the "
                       "OPC UA port)")
    try:
        loopback = ipaddress.ip_address(host).is_loopback
    except ValueError:
        loopback = host == "localhost"
    if not loopback and not allow_remote:
        raise PlcError("PLC7052", f"--host {host} serves the PLC to other computers (0.0.0.0: "
                       "to every network this one is on), without encryption; keep the "
                       "default 127.0.0.1, or add --allow-remote if you mean it")


def _positive(value: float | None, what: str) -> None:
    if value is not None and not (math.isfinite(value) and value > 0):
        raise PlcError("PLC7055", f"{what} must be a positive number of seconds, not {value}")


def _simulation(ns: argparse.Namespace, plc_files: list[str]):
    """The PLC, its plant simulation (or a bare PLC) and the alarm server."""
    from plclab.process.alarms import AlarmServer
    from plclab.sim.runner import load_plc

    from .runner import BarePlc

    alarms = AlarmServer.load(ns.alarms) if ns.alarms else None
    scenario = None
    if ns.lab:
        from plclab.grade.lab import load_lab

        lab = load_lab(ns.lab)
        plant, wiring, params, scan = lab.plant, lab.wiring, dict(lab.plant_params), lab.scan
        if alarms is None and lab.alarms:
            alarms = AlarmServer.from_dict(lab.alarms, f"{lab.id}/alarms")
        if ns.scenario and not ns.scenario.lower().endswith(".toml"):
            specs = {s.name: s for s in lab.scenarios}
            spec = specs.get(ns.scenario)
            if spec is None:
                raise PlcError("PLC7055", f"lab {lab.id} has no scenario {ns.scenario!r}; its "
                               f"scenarios: {', '.join(specs) or '(none)'} (or give a .toml "
                               "file)")
            params.update(spec.plant_params)
            scenario = spec.scenario()
    elif ns.plant:
        plant, wiring, params, scan = ns.plant, ns.wiring, None, ns.scan or "10ms"
    else:
        if ns.scenario or ns.wiring:
            raise PlcError("PLC7055", "--scenario and --wiring need a plant: give --lab LAB or "
                           "--plant NAME")
        plc = load_plc(plc_files, cycle_time=ns.scan or "10ms")
        return BarePlc(plc), alarms
    if ns.scenario and scenario is None:
        from plclab.sim.scenario import as_scenario

        scenario = as_scenario(ns.scenario)
    from plclab.sim import Simulation

    plc = load_plc(plc_files, cycle_time=ns.scan or scan)
    sim = Simulation(plc, plant, ns.wiring or wiring, seed=ns.seed, plant_params=params,
                     scenario=scenario, wall_clock=False)
    return sim, alarms


def _wired(sim) -> dict[str, str]:
    """Upper-case address/path -> plant signal, for every input the plant drives."""
    from .quality import channel_keys

    out = {}
    transfer = getattr(sim, "transfer", None)
    for ch in transfer.inputs if transfer is not None else []:
        for k in channel_keys(ch):
            out[k] = ch.signal.name
    return out


@command("opcua")
@arg("programs", nargs="+", metavar="PROGRAM", help="ST (or IL, LD, XML) source files")
@arg("--lab", default=None, help="take plant, wiring, scan and alarms from a lab")
@arg("--plant", default=None, help="plant name (see: plclab plants), without --lab")
@arg("--wiring", default=None, metavar="FILE", help="wiring table (default: the plant's)")
@arg("--alarms", default=None, metavar="FILE", help="alarm configuration (TOML, plclab.scada)")
@arg("--scenario", default=None, metavar="NAME|FILE", help="faults and actions at virtual "
     "times: a scenario of the lab, or a TOML file (e.g. a wire break)")
@arg("--scan", default=None, help="PLC cycle time, e.g. 10ms")
@arg("--seed", type=int, default=0, help="random seed (default 0)")
@arg("--speed", type=float, default=1.0, help="virtual seconds per wall second (default 1)")
@arg("--host", default=None, help="address to listen on (default 127.0.0.1, this computer "
     "only)")
@arg("--port", type=int, default=None, help="TCP port (default 4840)")
@arg("--allow-remote", action="store_true", help="allow a --host other than the loopback "
     "interface (0.0.0.0: every network)")
@arg("--config", default=None, metavar="FILE", help="access rules (TOML): anonymous role, "
     "users, writable variables (docs/opcua.md)")
@arg("--writable", action="append", default=[], metavar="VARIABLE",
     help="a variable (or pattern, e.g. 'Main.SP_*') clients may write; repeat for more")
@arg("--anonymous", default=None, choices=["read", "write", "none"],
     help="what a client without a user name may do (default read)")
@arg("--user", default=None, metavar="NAME", help="a user with the write role; the password "
     "comes from the environment variable PLCLAB_OPCUA_PASSWORD")
@arg("--period", type=float, default=0.05, metavar="S", help="wall seconds between two "
     "copies of the PLC into the address space (default 0.05)")
@arg("--duration", type=float, default=None, metavar="S",
     help="stop after S wall-clock seconds (default: run until Ctrl-C)")
@arg("--list", action="store_true", help="print the tags (path, OPC UA type, writable) and "
     "exit")
def cmd_opcua(ns: argparse.Namespace) -> int:
    from .access import load_access
    from .tags import apply_rules, build_tree

    access = load_access(ns.config, writable=ns.writable, anonymous=ns.anonymous,
                         user=ns.user)
    host = ns.host or access.host or "127.0.0.1"
    port = ns.port if ns.port is not None else access.port if access.port is not None else 4840
    check_endpoint(host, port, ns.allow_remote)
    _positive(ns.period, "--period")
    _positive(ns.duration, "--duration")
    _positive(ns.speed, "--speed")
    sim, alarms = _simulation(ns, ns.programs)
    tree = build_tree(sim.plc)
    apply_rules(tree, access, _wired(sim))
    if ns.list:
        for t in tree.tags:
            shape = f"[{'x'.join(map(str, t.dims))}]" if t.dims else ""
            kind = t.kind + shape
            print(f"ns=2;s={t.path:<32} {kind:<14} "
                  f"{'writable' if t.writable else 'read-only'}"
                  + (f"  {t.address}" if t.address else ""))
        return 0
    from .runner import make_runner
    from .server import OpcUaServer, need_asyncua

    need_asyncua()
    runner = make_runner(sim, alarms, ns.speed)
    server = OpcUaServer(runner, tree, access, host=host, port=port, period=ns.period,
                         on_message=lambda text: print(text, file=sys.stderr, flush=True))

    async def main() -> None:
        await server.start()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            try:
                loop.add_signal_handler(sig, server.request_stop)
            except (NotImplementedError, RuntimeError):  # pragma: no cover - Windows
                pass
        writable = sum(t.writable for t in tree.tags)
        users = ", ".join(access.users) or "none"
        print(f"OPC UA server on {server.url}/ : {len(tree.tags)} tags ({writable} writable), "
              f"{len(alarms.alarms) if alarms else 0} alarms; anonymous {access.anonymous}, "
              f"users: {users}; speed {ns.speed:g}x; Ctrl-C stops", flush=True)
        await server.run(ns.duration)

    asyncio.run(main())
    print(f"stopped: {sim.plc.scan_count} scans, virtual time {sim.plc.time:.3f} s, "
          f"{server.writes} writes ({server.refused} refused)", flush=True)
    return 0
