"""Command-line commands ``plclab serve`` and ``plclab plant-serve``.

pymodbus is imported only when a command runs, so ``plclab --help`` works without it.
"""

from __future__ import annotations

import argparse
import asyncio
import ipaddress
import signal
import sys

from ..cli_registry import arg, command
from ..errors import PlcError


def _params(items: list[str], what: str) -> dict:
    out = {}
    for item in items:
        name, eq, text = item.partition("=")
        if not eq or not name.strip():
            raise PlcError("PLC3002", f"{what} {item}: write NAME=VALUE, e.g. {what} area=0.5")
        t = text.strip()
        value: object
        if t.lower() in ("true", "false"):
            value = t.lower() == "true"
        else:
            try:
                value = int(t)
            except ValueError:
                try:
                    value = float(t)
                except ValueError:
                    value = t
        out[name.strip()] = value
    return out


def _check_endpoint(host: str, port: int, writable: str = "") -> None:
    if not 1 <= port <= 65535:
        raise PlcError("PLC9203", f"--port {port}: give a TCP port 1..65535 (5020 is usual; "
                       "502 needs root)")
    try:
        loopback = ipaddress.ip_address(host).is_loopback
    except ValueError:
        loopback = host == "localhost"
    if not loopback:
        what = f"read the PLC and write {writable}" if writable else "read it"
        print(f"warning: serving on {host}: every computer that can reach this one can "
              f"{what} over Modbus (there is no authentication); use the default 127.0.0.1 "
              "unless you mean it", file=sys.stderr, flush=True)


def _make_plant(name: str, params: dict, seed: int):
    try:
        from plants import get_plant
    except ModuleNotFoundError:
        raise PlcError("PLC3003", "the plants package is not installed") from None
    try:
        plant = get_plant(name, **params)
        plant.reset(seed=seed)
    except ValueError as exc:  # PlantError
        raise PlcError("PLC3002", str(exc)) from None
    return plant


def _run(server, duration: float | None) -> None:
    """Run a server's ``run()`` with SIGINT and SIGTERM ending it cleanly."""

    async def main():
        loop = asyncio.get_running_loop()
        await server.start()
        for sig in (signal.SIGINT, signal.SIGTERM):
            try:
                loop.add_signal_handler(sig, server.request_stop)
            except (NotImplementedError, RuntimeError):  # pragma: no cover - Windows
                pass
        print(f"listening on {server.host}:{server.port} (device id {server.device_id}, "
              f"speed {server.speed:g}x); Ctrl-C stops", flush=True)
        await server.run(duration)

    asyncio.run(main())


def _say(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


@command("serve")
@arg("files", nargs="+", metavar="PROGRAM", help="source files (.st)")
@arg("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1, this "
     "computer only)")
@arg("--port", type=int, default=5020, help="TCP port (default 5020)")
@arg("--speed", type=float, default=1.0, help="virtual seconds per wall second (default 1)")
@arg("--cycle-time", default="10ms", help="task period, e.g. 10ms (default)")
@arg("--allow-coil-writes", action="store_true", help="let clients force %%QX outputs by "
     "writing coils (holding register 4096 = 1 releases the forces)")
@arg("--read-only-inputs", action="store_true", help="no Modbus writes to the input "
     "terminals (removes coils 8192.. and holding registers 2048..)")
@arg("--map", dest="map_file", metavar="FILE.csv|FILE.json", default=None,
     help="write the address map of every located variable to this file")
@arg("--duration", type=float, default=None, metavar="S",
     help="stop after S wall-clock seconds (default: run until Ctrl-C)")
@arg("--plant", default=None, help="a plant joined directly to the PLC (signal order)")
@arg("--wiring", default=None, metavar="FILE", help="wiring table for --plant (needs the "
     "simulation layer plclab.sim)")
@arg("--param", action="append", default=[], metavar="NAME=VALUE",
     help="plant parameter for --plant, e.g. --param area=0.25")
@arg("--seed", type=int, default=0, help="plant seed (default 0)")
@arg("--io", default=None, metavar="modbus://HOST:PORT", help="remote I/O: poll a plant "
     "served by plclab plant-serve (or any Modbus TCP server)")
@arg("--io-period", type=float, default=0.02, metavar="S", help="remote I/O poll period, "
     "wall seconds (default 0.02)")
@arg("--io-timeout", type=float, default=0.5, metavar="S", help="remote I/O request "
     "timeout, wall seconds (default 0.5)")
@arg("--io-status", default=None, metavar="%IXn.m", help="input bit that carries the "
     "remote-I/O status too (a BOOL named IO_OK always does)")
@arg("--max-clients", type=int, default=16, metavar="N", help="Modbus clients served at "
     "once (default 16); more are disconnected at once")
@arg("--idle-timeout", type=float, default=60.0, metavar="S", help="disconnect a client "
     "that sends nothing for S wall seconds (default 60)")
@arg("--watch", default=None, metavar="FILE", help="a watch table (TOML, plclab.scada): "
     "sampled at its trigger point while the clients work; its last samples at the end")
def cmd_serve(ns: argparse.Namespace) -> int:
    from ..project import load
    from ._deps import need_pymodbus
    from .addressing import format_map, map_rows, overlaps, write_map
    from .limits import check_limits
    from .server import PlcServer

    need_pymodbus()
    writable = ["%MW (memory words)"]
    if not ns.read_only_inputs:
        writable.insert(0, "its inputs %I and %IW")
    if ns.allow_coil_writes:
        writable.append("its outputs %Q (forcing)")
    _check_endpoint(ns.host, ns.port, ", ".join(writable))
    check_limits(ns.max_clients, ns.idle_timeout)
    if ns.duration is not None and not ns.duration > 0:
        raise PlcError("PLC3002", "--duration must be positive (seconds)")
    if ns.wiring and not ns.plant:
        raise PlcError("PLC3002", "--wiring goes with --plant PLANT")
    if ns.param and not ns.plant:
        raise PlcError("PLC3002", "--param sets parameters of --plant PLANT")
    if ns.wiring:
        raise PlcError("PLC3002", "--wiring needs the simulation layer (plclab.sim), which "
                       "this installation does not have yet; leave --wiring out to wire the "
                       "plant in signal order (docs/modbus.md)")
    plc = load(*ns.files, cycle_time=ns.cycle_time)
    table = None
    if ns.watch:  # a watch table on the live PLC (plclab.scada, ADR 0025)
        from plclab.process.watch import WatchTable

        table = WatchTable.load(ns.watch)
        table.attach(plc)
    plant = _make_plant(ns.plant, _params(ns.param, "--param"), ns.seed) if ns.plant else None
    server = PlcServer(plc, host=ns.host, port=ns.port, speed=ns.speed,
                       allow_coil_writes=ns.allow_coil_writes,
                       read_only_inputs=ns.read_only_inputs, plant=plant, io=ns.io,
                       io_period=ns.io_period, io_timeout=ns.io_timeout,
                       io_status=ns.io_status, on_message=_say,
                       max_clients=ns.max_clients, idle_timeout=ns.idle_timeout)
    rows, unmapped = map_rows(plc, allow_coil_writes=ns.allow_coil_writes,
                              read_only_inputs=ns.read_only_inputs)
    if ns.map_file:
        try:
            write_map(ns.map_file, rows)
        except ValueError as exc:
            raise PlcError("PLC3002", str(exc)) from None
        except OSError as exc:
            raise PlcError("PLC3003", f"--map {ns.map_file}: {exc.strerror}") from None
    print(format_map(rows, allow_coil_writes=ns.allow_coil_writes,
                     read_only_inputs=ns.read_only_inputs, unmapped=unmapped,
                     shared=overlaps(plc)), flush=True)
    if plant is not None:
        from .plantmap import format_plant_map

        print(f"plant {plant.name!r} wired in signal order:\n"
              + format_plant_map(plant).split("\n", 1)[1], flush=True)
    if ns.io:
        print(f"remote I/O: {ns.io} every {ns.io_period:g} s (timeout {ns.io_timeout:g} s)",
              flush=True)
    _run(server, ns.duration)
    print(f"stopped: {plc.scan_count} scans, virtual time {plc.time:.3f} s, "
          f"{server.bridge.requests} Modbus requests ({server.bridge.refused} refused)",
          flush=True)
    if table is not None and table.samples:
        print(table.report(), flush=True)
    return 0


@command("plant-serve")
@arg("plant", metavar="PLANT", help="plant name, e.g. tank (see plants/README.md)")
@arg("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1)")
@arg("--port", type=int, default=5021, help="TCP port (default 5021)")
@arg("--speed", type=float, default=1.0, help="virtual seconds per wall second (default 1)")
@arg("--param", action="append", default=[], metavar="NAME=VALUE",
     help="plant parameter, e.g. --param area=0.25")
@arg("--seed", type=int, default=0, help="plant seed (default 0)")
@arg("--duration", type=float, default=None, metavar="S",
     help="stop after S wall-clock seconds (default: run until Ctrl-C)")
@arg("--max-clients", type=int, default=16, metavar="N", help="Modbus clients served at "
     "once (default 16); more are disconnected at once")
@arg("--idle-timeout", type=float, default=60.0, metavar="S", help="disconnect a client "
     "that sends nothing for S wall seconds (default 60)")
def cmd_plant_serve(ns: argparse.Namespace) -> int:
    from ._deps import need_pymodbus
    from .limits import check_limits
    from .plant_server import PlantServer
    from .plantmap import format_plant_map

    need_pymodbus()
    _check_endpoint(ns.host, ns.port, "the plant's actuators")
    check_limits(ns.max_clients, ns.idle_timeout)
    if ns.duration is not None and not ns.duration > 0:
        raise PlcError("PLC3002", "--duration must be positive (seconds)")
    plant = _make_plant(ns.plant, _params(ns.param, "--param"), ns.seed)
    server = PlantServer(plant, host=ns.host, port=ns.port, speed=ns.speed, on_message=_say,
                         max_clients=ns.max_clients, idle_timeout=ns.idle_timeout)
    print(format_plant_map(plant, server.layout), flush=True)
    _run(server, ns.duration)
    print(f"stopped: plant time {plant.time:.3f} s", flush=True)
    return 0
