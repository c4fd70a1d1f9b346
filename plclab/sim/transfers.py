"""The per-scan code of each kind of I/O module (``ModuleKind.transfer``, :data:`TRANSFERS`).

:func:`plclab.sim.channels.bind` compiles a wiring table into three Python functions; the
statements of each row come from the template its module kind names. An input template emits
the statements that leave the PLC-side value of input channel ``i`` in ``x`` (from the plant
values ``v`` at time ``t``; ``s`` names the channel's state list [last input, settle deadline or
-1, last result]); an output template emits the statements that take the command ``cmd`` (an
expression of ``q``) to the plant signal ``sig`` through ``_W`` (``s``: [last command, settle
deadline or -1, last value written]). Modules are called only when their result can change:
the same result as calling them every scan (``tests/sim/test_sim_transfer.py``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from plclab.io.modules import SignalTransmitter

Emit = Callable[[str], None]


class _Buckets:
    """The values that give the same counts as the last conversion of a noise-free AI.

    The chain value -> linear transmitter -> ADC is monotonic and quantised, so the values that
    convert to a regular code ``c`` form an interval; inside it (less a margin of a millionth
    of its width) no conversion is needed. The interval is computed from the module's
    public parameters and checked against every real conversion: if the module ever
    disagrees (another transmitter model, a fault), the shortcut is switched off for good.
    """

    def __init__(self, ai: Any) -> None:
        fmt, rng = ai.format, ai.range
        tx = ai.transmitter
        self.ai = ai
        self.ok = True
        self.min_code, self.max_code, self.step = fmt.min_code, fmt.max_code, fmt.step
        span = rng.hi - rng.lo
        if isinstance(tx, SignalTransmitter):
            ax, bx = 1.0, 0.0
            xlo, xhi = -math.inf, math.inf
        elif type(tx).__name__ == "LinearTransmitter":
            ax = span / (tx.hi - tx.lo)
            bx = rng.lo - tx.lo * ax
            xlo, xhi = (rng.sat_lo, rng.sat_hi) if tx.saturate else (-math.inf, math.inf)
        else:
            self.ok = False
            return
        ac = fmt.nominal_counts / span
        self.a = ac * ax  # counts = a * value + b
        self.b = ac * (bx - rng.lo) + fmt.zero
        v1, v2 = (xlo - bx) / ax, (xhi - bx) / ax  # values the transmitter passes unclipped
        self.vlo, self.vhi = min(v1, v2), max(v1, v2)

    def __call__(self, c: int, p: float) -> tuple[float, float]:
        if not self.ok or self.ai.fault is not None or not self.min_code < c < self.max_code \
                or not self.vlo < p < self.vhi:
            return math.inf, -math.inf  # clipped, saturated, special code or fault: convert
        v1 = (c - self.step / 2 - self.b) / self.a
        v2 = (c + self.step / 2 - self.b) / self.a
        va, vb = max(min(v1, v2), self.vlo), min(max(v1, v2), self.vhi)
        m = 1e-6 * abs(v2 - v1)
        if not va - m <= p <= vb + m:
            self.ok = False  # the module does something else: always convert from now on
            return math.inf, -math.inf
        return va + m, vb - m


def _in_held(ch: Any, i: int, x: str, s: str, sig: str, ns: dict[str, Any],
             emit: Emit) -> None:
    """Call the module while its input changed or its events (bounce, filter) are not all
    past; else keep its last result."""
    ns[f"_m{i}"] = ch.module.sample
    emit(f"    p = v[{sig}]; s = {s}")
    emit("    if p != s[0] or s[1] >= 0.0:")
    emit("        if p != s[0]:")
    emit(f"            s[0] = p; s[1] = t + {ch.settle!r}")
    emit(f"        s[2] = _m{i}(t, p)")
    emit("        if t >= s[1]: s[1] = -1.0")
    emit(f"    {x} = {'not ' if ch.invert else ''}s[2]")


def _in_sampled(ch: Any, i: int, x: str, s: str, sig: str, ns: dict[str, Any],
                emit: Emit) -> None:
    """Convert every scan; a memoryless channel (no noise, no filter) only when the value
    leaves the quantisation step of the last conversion (see _Buckets)."""
    ns[f"_m{i}"] = ch.module.sample
    if not ch.memoryless:
        emit(f"    {x} = _m{i}(t, v[{sig}])")
        return
    ns[s] = ch.state = [math.inf, -math.inf, None]
    ns[f"_b{i}"] = _Buckets(ch.module)
    emit(f"    p = v[{sig}]; s = {s}")
    emit("    if not s[0] <= p <= s[1]:")
    emit(f"        c = s[2] = _m{i}(t, p)")
    emit(f"        s[0], s[1] = _b{i}(c, p)")
    emit(f"    {x} = s[2]")


def _in_copy(ch: Any, i: int, x: str, s: str, sig: str, ns: dict[str, Any],
             emit: Emit) -> None:
    """No module: the value itself (a BOOL, a float, or an integer within the PLC type)."""
    if ch.signal.type == "bool":
        emit(f"    {x} = {'not ' if ch.invert else ''}v[{sig}]")
    elif ch.plc_kind == "float":
        emit(f"    {x} = float(v[{sig}])")
    else:
        lo, hi = ch.int_range
        emit(f"    {x} = round(v[{sig}])")
        emit(f"    {x} = {lo} if {x} < {lo} else {hi} if {x} > {hi} else {x}")


def _out_held(ch: Any, i: int, s: str, sig: str, cmd: str, ns: dict[str, Any],
              emit: Emit) -> None:
    """Call the module while the command changed or its delays are not past; write the
    actuator when the module's output changes (a relay's contact also makes an event)."""
    ns[f"_n{i}"] = ch.module.apply
    emit(f"    c = {cmd}; s = {s}")
    emit("    if c != s[0] or s[1] >= 0.0:")
    emit("        if c != s[0]:")
    emit(f"            s[0] = c; s[1] = t + {ch.settle!r}")
    emit(f"        a = _n{i}(t, c)")
    emit("        if t >= s[1]: s[1] = -1.0")
    emit("        if a != s[2]:")
    emit(f"            s[2] = a; _W({sig}, a)")
    if getattr(ch.module, "kind", None) == "relay":
        ns[f"_e{i}"] = ch
        emit(f"            _E(_e{i}, a)")


def _out_on_change(ch: Any, i: int, s: str, sig: str, cmd: str, ns: dict[str, Any],
                   emit: Emit) -> None:
    """Call the module when the command changes (its output depends on the command only)."""
    ns[f"_n{i}"] = ch.module.apply
    emit(f"    c = {cmd}; s = {s}")
    emit("    if c != s[0]:")
    emit(f"        s[0] = c; a = _n{i}(t, c)")
    emit("        if a != s[2]:")
    emit(f"            s[2] = a; _W({sig}, a)")


def _out_copy(ch: Any, i: int, s: str, sig: str, cmd: str, ns: dict[str, Any],
              emit: Emit) -> None:
    """No module: the command itself, written when it changes."""
    conv = "" if ch.signal.type == "bool" else "float"
    emit(f"    a = {conv}({cmd}); s = {s}")
    emit("    if a != s[2]:")
    emit(f"        s[2] = a; _W({sig}, a)")


TRANSFERS: dict[str, tuple[Callable[..., None] | None, Callable[..., None] | None]] = {
    "held": (_in_held, _out_held),
    "sampled": (_in_sampled, None),
    "on_change": (None, _out_on_change),
    "copy": (_in_copy, _out_copy),
}
"""The per-scan code of a module kind (``ModuleKind.transfer``): (input template, output
template); None where the template does not exist for that direction."""
