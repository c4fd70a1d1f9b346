"""The recording of a :class:`~plclab.sim.simulation.Simulation`: the recorder's groups, snapshots,
the Trace built from them, SFC lanes and edges (a mixin, moved out of simulation.py)."""


from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from plclab.errors import PlcError

from .errors import sim_error


class Recording:
    """The recorder and the Trace (a mixin of Simulation)."""

    # ------------------------------------------------------------------ set-up
    def _build_recorder(self, watch: list[str]) -> None:
        from plclab.trace.recorder import Recorder

        from .channels import type_kind

        rec = Recorder()
        sigs = self.plant.signals
        used = {n.upper() for n in sigs}
        names = list(self.plant.values())
        self._g_plant = rec.add("plant", names,
                                ["bool" if sigs[n].type == "bool" else "float" for n in names])

        def unique(name: str) -> str:
            cand = name if name.upper() not in used else f"plc:{name}"
            i = 2
            base = cand
            while cand.upper() in used:
                cand = f"{base}#{i}"
                i += 1
            used.add(cand.upper())
            return cand

        tr = self.transfer
        for ch in tr.channels:
            ch.name = unique(ch.name)
        self._g_in = rec.add("in", [c.name for c in tr.inputs], [c.plc_kind for c in tr.inputs])
        self._g_out = rec.add("out", [c.name for c in tr.outputs],
                              [c.plc_kind for c in tr.outputs])
        # watched variables
        wired = {_canonical(self.plc, c.row.plc): c.name for c in tr.channels}
        wired.update({c.name.upper(): c.name for c in tr.channels})
        getters, wnames, wkinds = [], [], []
        self.watch: list[str] = []
        for raw in watch:
            name = raw.strip()
            if not name or name.upper() in wired or _canonical(self.plc, name) in wired:
                continue
            try:
                var = self.plc.var(name)
            except PlcError as e:
                raise sim_error("PLC4020", f"watch {name}: {e.message}") from None
            kind, _ = type_kind(var.type)
            if kind == "time":
                kind = "int"
            elif kind == "enum":
                kind = "int"
            if kind not in ("bool", "int", "real"):
                raise sim_error("PLC4020", f"watch {name}: a {var.type} cannot be recorded; "
                                "watch BOOL, integer, REAL or TIME variables (for arrays and "
                                "structures name an element, e.g. arr[1] or s.x)")
            col = unique(name)
            wired[name.upper()] = col
            wired[_canonical(self.plc, name)] = col
            getters.append(var.get)
            wnames.append(col)
            wkinds.append("float" if kind == "real" else kind)
            self.watch.append(name)
        self._watch_get = _tuple_getter(getters)
        self._g_watch = rec.add("watch", wnames, wkinds)
        self._g_snap = None
        self._snap_keys: list[str] | None = None
        self._snap_row: Any = None  # the plant's snapshot_row() when it gives the keys' order
        self.recorder = rec

    def _record_snapshot(self) -> None:
        row_of = self._snap_row
        if row_of is not None:
            self._g_snap.rows.append(row_of())  # the plant's values in the keys' order
            return
        snap = self.plant.snapshot()
        if self._g_snap is None:
            keys = list(snap)
            self._snap_keys = keys
            taken = {n.upper() for g in self.recorder.groups.values() for n in g.names}
            names = [k if k.upper() not in taken else f"snapshot:{k}" for k in keys]
            self._g_snap = self.recorder.add("snapshot", names, ["float"] * len(keys))
            self._g_snap.rows.extend([(math.nan,) * len(keys)] * (len(self.recorder.index) - 1))
            # a plant that gives its snapshot as a row in fixed key order (the conveyor's
            # hundreds of slot columns): a list a scan, no dict
            row_of = getattr(self.plant, "snapshot_row", None)
            if row_of is not None and list(self.plant.snapshot_keys()) == keys:
                self._snap_row = row_of
        keys = self._snap_keys
        assert keys is not None
        if len(snap) == len(keys) and list(snap) == keys:
            self._g_snap.rows.append(tuple(snap.values()))
        else:
            self._g_snap.rows.append(tuple(snap.get(k, math.nan) for k in keys))

    # ------------------------------------------------------------------ the record
    @property
    def trace(self) -> Any:
        """The :class:`~plclab.trace.Trace` of everything run so far."""
        import numpy as np

        from plclab import __version__
        from plclab.trace import Trace

        rec = self.recorder
        cols, kinds = rec.columns()
        tnum = np.asarray(rec.index, dtype=np.int64) * self.scan_ns
        time = tnum / 1e9
        sigs = self.plant.signals
        io = []
        for c in self.transfer.channels:
            io.append({"plc": c.row.plc, "signal": c.signal.name, "module": c.row.module,
                       "direction": c.direction, "column": c.name, "plant_column": c.signal.name,
                       "params": c.row.params, "description": c.row.description})
        edges, initial, bounce = self._edges()
        extra: list[Any] = []
        hook_meta: dict[str, Any] = {}
        for hk in self.hooks:
            evs, hm = hk.finish(self)
            extra += evs
            hook_meta.update(hm)
        sfc = self._sfc_lane(cols, time)
        events = sorted(self.events + bounce + extra + sfc.pop("events"),
                        key=lambda e: e.time)
        meta = {
            "plant": self.plant.name, "title": getattr(self.plant, "title", ""),
            "plant_params": {k: v for k, v in self.plant_params.items()
                             if isinstance(v, bool | int | float | str)},
            "signals": list(sigs),
            "units": {n: s.unit for n, s in sigs.items()},
            "signal_info": {n: {"kind": s.kind, "type": s.type, "unit": s.unit,
                                "range": list(s.range), "description": s.description}
                            for n, s in sigs.items()},
            "io": io, "located": self._located(), "watch": list(self.watch),
            "scan": self.scan, "dt": self.dt,
            "substeps": self.substeps, "seed": self.seed, "decimate": self.decimate,
            "period": self.scan * self.decimate, "t_end": self.time, "scans": self.k,
            "plc_time0": self.t0_ns / 1e9, "stop_reason": self.stop_reason,
            "wiring": self.wiring.source or f"default for {self.plant.name}",
            "scenario": self.scenario.source or "", "description": self.scenario.description,
            "edge_initial": initial, "warnings": list(self.warnings),
            "plclab_version": __version__,
            **hook_meta,
            **sfc,
        }
        wall = {"scan_s": np.asarray(rec.wall, dtype=np.float64) / 1e9, "run_s": self.wall_s}
        return Trace(time, cols, kinds, meta, events, wall, edges)

    def _located(self) -> dict[str, str]:
        """``{address: the program's variable declared at it}`` (``%QX0.0`` -> ``PUMP``): the
        pictures name a lane by the student's variable and its address (ADR 0069)."""
        out: dict[str, str] = {}
        symbols = getattr(getattr(self.plc, "project", None), "symbols", None)
        for lv in symbols.located_vars() if symbols is not None else ():
            if "*" not in lv.address:
                out.setdefault(lv.address.upper(), lv.decl.spelling or lv.decl.name)
        return out

    def _sfc_lane(self, cols: dict[str, Any], time: Any) -> dict[str, Any]:
        """The charts (``sfc``), why they stand where they are (``sfc_end``) and the
        transition firings (``events``) of the programs with an SFC body; nothing otherwise."""
        if not self._sfc_steps:
            return {"events": []}
        from .sfc_lane import sfc_meta, step_events, why_stuck

        columns = {name.upper(): col for name, col in zip(
            self.watch, self._g_watch.names, strict=True)}
        meta = sfc_meta(self.plc, columns)
        return {"sfc": meta, "sfc_end": why_stuck(self.plc),
                "events": step_events(meta, time, cols)}

    def _edges(self) -> tuple[dict[str, Any], dict[str, bool], list[Any]]:
        import numpy as np

        from plclab.io import DigitalInput, DigitalOutput
        from plclab.trace.events import Event

        edges: dict[str, Any] = {}
        initial: dict[str, bool] = {}
        bounce: list[Any] = []
        for c in self.transfer.channels:
            m = c.module
            if isinstance(m, DigitalInput):  # its raw and filtered histories
                raw = m.raw_transitions
                filt = m.filtered_transitions
                init = bool(m.initial) if m.initial is not None else False
                edges[f"{c.name}.raw"] = (np.array([x[0] for x in raw], dtype=float),
                                          np.array([x[1] for x in raw], dtype=bool))
                edges[f"{c.name}.filtered"] = (np.array([x[0] for x in filt], dtype=float),
                                               np.array([x[1] for x in filt], dtype=bool))
                initial[f"{c.name}.raw"] = initial[f"{c.name}.filtered"] = init
                if m.bounce_ms > 0 and raw:
                    gap = m.bounce_ms / 1000.0 + 1e-9
                    burst = [raw[0]]
                    for e in list(raw[1:]) + [None]:
                        if e is not None and e[0] - burst[-1][0] <= gap:
                            burst.append(e)
                            continue
                        if len(burst) > 1:
                            span = (burst[-1][0] - burst[0][0]) * 1000.0
                            bounce.append(Event(burst[0][0], "bounce", c.name,
                                                f"{c.signal.name} bounced: {len(burst)} edges in "
                                                f"{span:.2f} ms", {"edges": len(burst)}))
                        if e is not None:
                            burst = [e]
            elif isinstance(m, DigitalOutput):  # its contact's history
                sw = m.switch_times
                edges[f"{c.name}.contact"] = (np.array([x[0] for x in sw], dtype=float),
                                              np.array([x[1] for x in sw], dtype=bool))
                initial[f"{c.name}.contact"] = False
        return edges, initial, bounce


def _canonical(plc: Any, path: str) -> str:
    """``PROG.VAR`` for a variable given without its program (for comparing paths)."""
    p = path.strip().upper()
    if p.startswith("%"):
        return p
    head = p.split(".")[0].split("[")[0]
    project = plc.project
    if head in {n.upper() for n, _, _ in project.programs} or head in project.globals:
        return p
    owners = [n.upper() for n, _ in project.symbols.programs_declaring(head)]
    return f"{owners[0]}.{p}" if len(owners) == 1 else p


def _tuple_getter(getters: list[Callable[[], Any]]) -> Callable[[], tuple[Any, ...]]:
    if not getters:
        return tuple
    ns = {f"g{i}": g for i, g in enumerate(getters)}
    src = "lambda: (" + "".join(f"g{i}(), " for i in range(len(getters))) + ")"
    return eval(src, ns)  # noqa: S307 - fixed text, no user input
