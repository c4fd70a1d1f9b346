"""The simulation's fused loop: the common scans of :meth:`Simulation.run` as one function.

:meth:`Simulation._advance_plain` is the reference: per scan it calls the scenario, the
input transfer, the PLC, the output transfer, the recorder, the plant and the events, each
through a function call and a few attribute lookups. For the common scan (no scenario action
due, no ramp running, no hook, no stop condition) this module generates one Python function
that does the same work inline: the I/O transfer's statements (:class:`~.channels.Transfer`
keeps them as ``in_body``/``out_items``/``apply_body``), the plant's sub-steps
(``_advance``/``_outputs`` of a :class:`plants.base.Plant` whose ``step`` is the base class's),
the trace rows, and everything else bound to locals once.

Every statement is the one the plain loop runs, in the same order, on the same objects, so the
trace is identical scan for scan (``tests/sim/test_sim_fastloop.py`` compares both paths;
``ENABLED = False`` turns the fused loop off). The function returns at the first scan that
needs the plain loop (a scenario action is due); the simulation runs that scan the plain way
and comes back. See ADR 0032.
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable
from typing import Any

ENABLED = True
"""False: every scan goes through the plain loop (for comparisons and debugging)."""

# the loop's own local names (the transfer's namespace must not use them)
_RESERVED = frozenset({"k", "k_end", "next_op", "scan", "checked", "t_ns", "t", "v", "w0", "w1",
                       "pending", "fault", "st", "evs"})


def _plant_parts(plant: Any, h: float) -> tuple[bool, bool, bool]:
    """(inline step, live values, direct events): which of the plant's methods are the base
    class's own, so that the fused loop may do their work without calling them."""
    try:
        from plants.base import Plant
    except ImportError:  # pragma: no cover - plants ship with plclab
        return False, False, False
    if not isinstance(plant, Plant):
        return False, False, False
    cls = type(plant)
    step = cls.step is Plant.step and 0.0 < h <= plant.max_dt
    values = cls.values is Plant.values and isinstance(getattr(plant, "_io", None), dict)
    events = cls.drain_events is Plant.drain_events
    return step, values, events


def key(sim: Any) -> tuple[Any, ...]:
    """What the generated function depends on beyond the objects it binds (rebuild on change)."""
    return (_plant_parts(sim.plant, sim.dt), sim.snapshot, sim.decimate, sim.wall_clock,
            bool(sim._g_watch.names), sim.substeps)


def build(sim: Any) -> Callable[..., int]:
    """The fused loop of ``sim``: ``fast(k, k_end, next_op, scan, checked) -> k``.

    Runs scans ``k, k+1, ...`` while ``k < k_end`` and the scan's time is before ``next_op``
    (the time of the next scenario action, ns); returns the number of the first scan it did
    not run (also stored in ``sim.k``, on a fault too). ``checked`` is the PLC's prebound scan
    (``Plc.scanner()``), ``scan`` the same or its ``unchecked`` part when ``ready()`` held
    at the call: nothing in the loop but a fault changes what ``ready()`` checks, so after
    the PLC's state changed the loop goes on with ``checked``.
    """
    from plclab.errors import PlcRuntimeFault

    tr = sim.transfer
    plant = sim.plant
    rec = sim.recorder
    inline_step, live, direct_events = _plant_parts(plant, sim.dt)
    ns: dict[str, Any] = {k: v for k, v in tr.namespace.items() if k != "__builtins__"}
    clash = _RESERVED & set(ns)
    assert not clash, clash
    ns.update({
        "L_sim": sim, "L_plc": sim.plc, "L_pl": plant, "L_fault": PlcRuntimeFault,
        "L_tick": sim.scan_ns, "L_h": sim.dt, "L_perf": time.perf_counter_ns,
        "L_idx": rec.index.append, "L_wall": rec.wall.append, "L_flush": rec.flush,
        "L_prows": sim._g_plant.rows, "L_prow": sim._g_plant.rows.append,
        "L_irow": sim._g_in.rows.append, "L_orow": sim._g_out.rows.append,
        "L_wrow": sim._g_watch.rows.append, "L_wget": sim._watch_get,
        "L_snap": sim._record_snapshot, "L_values": plant.values, "L_pstep": plant.step,
        "L_drain": plant.drain_events, "L_pevents": sim._plant_events,
        "L_pfault": sim._plc_fault, "L_pchanged": sim._plc_changed,
        "L_adv": getattr(plant, "_advance", None), "L_outp": getattr(plant, "_outputs", None),
        "L_io": getattr(plant, "_io", None), "L_len": len, "L_collect": gc.collect,
    })
    lines: list[str] = []

    def emit(text: str, indent: int = 0) -> None:
        lines.append(" " * indent + text)

    def body(stmts: list[str], indent: int) -> None:
        for ln in stmts:  # the transfer's statements are indented by 4 (a function body)
            emit(ln[4:], indent)

    params = "".join(f", {n}={n}" for n in ns)
    emit(f"def fast(k, k_end, next_op, scan, checked, *{params}):")
    emit("pending = L_len(L_prows)", 4)
    emit("st = L_sim._plc_state", 4)
    emit("try:", 4)
    emit("while k < k_end:", 8)
    i = 12
    emit("t_ns = k * L_tick", i)
    emit("if t_ns >= next_op:", i)
    emit("break", i + 4)
    emit("t = t_ns / 1e9", i)
    # 2. inputs (the plant's own dict: nothing writes the plant until the plant step)
    emit("v = L_io" if live else "v = L_values()", i)
    body(tr.in_body, i)
    # 3. scan
    measure = sim.wall_clock
    emit("w0 = L_perf()" if measure else "w0 = 0", i)
    emit("try:", i)
    emit("scan()", i + 4)
    emit("except L_fault as fault:", i)
    emit("L_pfault(t_ns, fault)", i + 4)
    emit("w1 = L_perf()" if measure else "w1 = 0", i)
    emit("if L_plc.state != st:", i)
    emit("L_pchanged(t_ns)", i + 4)
    emit("st = L_sim._plc_state", i + 4)
    emit("scan = checked", i + 4)
    for j, item in enumerate(tr.out_items):
        emit(f"q{j} = {item}", i)
    # 4. record
    r = i
    if sim.decimate > 1:
        emit(f"if k % {sim.decimate} == 0:", i)
        r = i + 4
    emit("L_idx(k)", r)
    emit("L_prow(tuple(v.values()))", r)
    emit(f"L_irow(({''.join(n + ', ' for n in tr.in_names)}))", r)
    emit(f"L_orow(({''.join(f'q{j}, ' for j in range(len(tr.out_items)))}))", r)
    if sim._g_watch.names:
        emit("L_wrow(L_wget())", r)
    if sim.snapshot:
        emit("L_snap()", r)
    emit("L_wall(w1 - w0)", r)
    emit("pending += 1", r)
    emit(f"if pending >= {_CHUNK}:", r)
    emit("L_flush()", r + 4)
    emit("pending = 0", r + 4)
    emit("L_collect(0)", r + 4)  # the cyclic GC is paused during the loop: young objects
    # 5. plant
    if inline_step:  # Plant.step(h) for 0 < h <= max_dt
        step = ["L_adv(L_h)", "L_pl.time += L_h", "L_outp()"]
    else:
        step = ["L_pstep(L_h)"]
    if sim.substeps == 1:
        for s in step:
            emit(s, i)
    else:
        emit(f"for _ in range({sim.substeps}):", i)
        for s in step:
            emit(s, i + 4)
    emit("k += 1", i)
    emit("t = k * L_tick / 1e9", i)
    emit("L_pl.time = t", i)
    if direct_events:
        emit("if L_pl._events:", i)
        emit("L_pevents(L_drain())", i + 4)
    else:
        emit("evs = L_drain()", i)
        emit("if evs:", i)
        emit("L_pevents(evs)", i + 4)
    # 6. outputs
    body(tr.apply_body, i)
    emit("finally:", 4)
    emit("L_sim.k = k", 8)
    emit("return k", 4)
    source = "\n".join(lines) + "\n"
    exec(compile(source, "<plclab-sim-loop>", "exec"), ns)  # noqa: S102 - fixed text
    fast = ns["fast"]
    fast.source = source
    return fast


_CHUNK = 8192  # rows between recorder flushes (as the plain loop)

__all__ = ["ENABLED", "build", "key"]
