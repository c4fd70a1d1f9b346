"""Command-line sub-command ``plclab panel``: the operator panel in the browser.

``plclab panel PROGRAM... --lab water-boiler`` (the lab's plant, wiring, alarms and recipe) or
``plclab panel PROGRAM... --plant tank [--alarms FILE] [--recipe FILE]`` runs the programs
against the plant in real time (``--speed``) and serves the panel on http://127.0.0.1:PORT/.
"""

from __future__ import annotations

import argparse

from plclab.cli_registry import arg, command
from plclab.errors import PlcError


@command("panel")
@arg("programs", nargs="+", metavar="PROGRAM", help="ST (or IL, LD, XML) source files")
@arg("--lab", default=None, help="take plant, wiring, scan, alarms and recipe from a lab")
@arg("--plant", default=None, help="plant name (see: plclab plants), without --lab")
@arg("--wiring", default=None, metavar="FILE", help="wiring table (default: the plant's)")
@arg("--alarms", default=None, metavar="FILE", help="alarm configuration (TOML)")
@arg("--recipe", default=None, metavar="FILE", help="recipe with records (TOML)")
@arg("--scan", default=None, help="PLC cycle time, e.g. 10ms")
@arg("--seed", type=int, default=0, help="random seed (default 0)")
@arg("--speed", type=float, default=1.0, help="virtual seconds per second (default 1)")
@arg("--port", type=int, default=8765, help="port on 127.0.0.1 (default 8765)")
def cmd_panel(ns: argparse.Namespace) -> int:
    from plclab.process.alarms import AlarmServer
    from plclab.process.recipes import Recipe
    from plclab.sim import Simulation
    from plclab.sim.runner import load_plc

    from .panel import Panel, serve

    alarms = AlarmServer.load(ns.alarms) if ns.alarms else None
    recipe = Recipe.load(ns.recipe) if ns.recipe else None
    if ns.lab:
        from plclab.grade.lab import load_lab

        lab = load_lab(ns.lab)
        plant, wiring, params, scan = lab.plant, lab.wiring, dict(lab.plant_params), lab.scan
        if alarms is None and lab.alarms:
            alarms = AlarmServer.from_dict(lab.alarms, f"{lab.id}/alarms")
        if recipe is None and lab.recipes:
            recipe = Recipe.from_dict(lab.recipes, f"{lab.id}/recipes")
    elif ns.plant:
        plant, wiring, params, scan = ns.plant, ns.wiring, None, ns.scan or "10ms"
    else:
        raise PlcError("PLC6050", "which plant? give --lab LAB or --plant NAME")
    plc = load_plc(ns.programs, cycle_time=ns.scan or scan)
    sim = Simulation(plc, plant, ns.wiring or wiring, seed=ns.seed, plant_params=params,
                     wall_clock=False)
    serve(Panel(sim, alarms, recipe, speed=ns.speed), ns.port)
    return 0
