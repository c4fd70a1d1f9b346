"""The scan's fixed cost: one generated function per PLC that runs one scan of its tasks.

:meth:`Plc._scan_once <plclab.runtime.plc_scan.ScanCycle._scan_once>` is the reference: it
tests for STOP, forcing, pending modifications, trigger points, system bytes, located
variables and the task layout on every scan. This module writes, once per restart
(``Plc._bind``), a Python function for the common case (RUN, nothing forced, no watch-table
hook or pending modification) that does only what this PLC needs, with everything bound to
locals: the input copy, the system and clock memory bytes only when they are configured, the
located variables' image transfer (ADR 0056) only when the program has located variables, a
direct call of each program body (no loop over a list), the image copies through a prebound
slice (Python 3.11 builds ``[:]``'s slice on every call), the tasks' interval tests only for
tasks slower than the base tick, the output copy, the clock step. See ADR 0058.

Forcing, modifications and trigger points are "swapped in only when active": the PLC keeps one
flag, ``live[0]``, up to date where those change (``force``/``unforce``, the forced table
itself, ``modify``, the trigger lists, the ``state`` setter); the generated ``scan`` tests that
flag and its argument and otherwise hands the call to the general :meth:`Plc.scan`. The text is
fixed: program bodies are bound objects named ``B0``, ``B1``, ...; no user text reaches it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def build(plc: Any, general: Callable[..., None]) -> tuple[Any, Any, list[bool]]:
    """``(scan, unchecked, live)`` for ``plc`` as bound now (``plc._task_bodies``, images).

    ``scan(n=1)``: one scan when ``live[0]`` holds and ``n`` is 1, else ``general(plc, n)``;
    ``unchecked()``: the scan alone, for a caller that knows ``live[0]`` holds; ``live``: the
    flag (a one-element list the PLC updates)."""
    tick = plc._tick_ns
    ns: dict[str, Any] = {
        "plc": plc, "general": general, "budget": plc.budget, "ctx": plc.ctx,
        "img_in": plc.image_in, "inputs": plc.inputs, "img_out": plc.image_out,
        "outputs": plc.outputs, "to_stop": plc._to_stop,
        "sysmem": plc._update_system_memory, "sync_in": plc._sync_in,
        "sync_out": plc._sync_out, "ALL": slice(None),
    }
    live = [False]
    ns["live"] = live
    body: list[str] = ["budget.left = budget.limit", "img_in[ALL] = inputs"]
    if plc._system_bytes:
        body.append("sysmem()")
    body.append("try:")
    inner: list[str] = []
    if plc._sync_in is not None:
        inner.append("sync_in()")
    if any(interval != tick for interval, _ in plc._task_bodies):
        inner.append("now = ctx.now_ns")
    k = 0
    for interval, bodies in plc._task_bodies:
        calls = []
        for b in bodies:
            ns[f"B{k}"] = b
            calls.append(f"B{k}()")
            k += 1
        if not calls:
            continue
        if interval == tick:
            inner += calls
        else:
            inner.append(f"if now % {int(interval)} == 0:")
            inner += ["    " + c for c in calls]
    if plc._sync_out is not None:
        inner.append("sync_out()")
    if not inner:
        inner.append("pass")
    body += ["    " + s for s in inner]
    body += ["except BaseException as exc:", "    to_stop(exc)",
             "outputs[ALL] = img_out",
             f"t = ctx.now_ns + {int(tick)}", "ctx.now_ns = t", "ctx.now = t // 1000000",
             "ctx.first_scan = False", "ctx.scan_count += 1"]
    lines = ["def scan(n=1):",
             "    if n != 1 or n.__class__ is not int or not live[0]:",
             "        return general(plc, n)"]
    lines += ["    " + s for s in body]
    lines += ["", "", "def unchecked():"]
    lines += ["    " + s for s in body]
    source = "\n".join(lines) + "\n"
    exec(compile(source, "<plclab-scan>", "exec"), ns)  # noqa: S102 - fixed text
    scan, unchecked = ns["scan"], ns["unchecked"]
    scan.__doc__ = general.__doc__
    scan.source = source  # type: ignore[attr-defined]
    scan.ready = lambda: live[0]  # type: ignore[attr-defined]
    scan.unchecked = unchecked  # type: ignore[attr-defined]
    return scan, unchecked, live


__all__ = ["build"]
