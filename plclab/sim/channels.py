"""Binding a wiring table to a plant and a PLC, and the per-scan I/O transfer.

:func:`bind` checks every row against the plant's signal table and the PLC's process image and
variables, builds the I/O module of each row and returns a :class:`Transfer`. The transfer
is compiled once into three plain Python functions (the simulation calls them every scan):

``read_in(t, values)``
    plant values -> input modules -> the PLC's input terminals (``plc.inputs``, written
    byte by byte at addresses resolved at start-up) or input variables; returns the PLC-side
    value of every input row (for the trace);
``read_out()``
    the PLC's output terminals (``plc.outputs``) or output variables -> a tuple;
``apply_out(t, q)``
    that tuple -> output modules -> plant actuators (written only when they change).

Modules whose output cannot change while their input stays the same are not called again
(a digital input once its bounce and filter time have passed, a relay once its delay has
passed, a noise-free analog channel while the value is unchanged); the result is the same as
calling them every scan, because :mod:`plclab.io` computes everything from event times.
"""

from __future__ import annotations

import hashlib
import math
import re
import struct
from dataclasses import dataclass, field
from typing import Any

from plclab.errors import Diagnostic, PlcError
from plclab.io.modules import ModuleKind, alternative
from plclab.lang.addresses import SIZE_BYTES

from .errors import did_you_mean, raise_all, sim_error
from .transfers import TRANSFERS
from .wiring import ADDRESS_RE, MODULES, WireRow, Wiring

_SIZE_NAMES = {"X": "a bit", "B": "a byte", "W": "a word", "D": "a double word", "L": "a long word"}


def mix_seed(sim_seed: int, *parts: Any) -> int:
    """A 63-bit seed from the simulation seed and a row's own seed or position."""
    h = hashlib.sha256(repr((int(sim_seed),) + tuple(parts)).encode()).digest()
    return int.from_bytes(h[:8], "big") >> 1


@dataclass
class Channel:
    """One bound wiring row."""

    row: WireRow
    direction: str  # "in" / "out"
    signal: Any  # plants.base.Signal
    module: Any = None  # plclab.io object or None
    # PLC side
    address: str | None = None  # canonical address, or None for a variable
    size: str = "X"
    byte: int = 0
    bit: int = 0
    float_fmt: str | None = None  # ">f"/">d" when the address holds a REAL/LREAL
    var: Any = None  # plclab.runtime.plc.Var for a variable row
    var_kind: str = ""  # bool / int / real
    int_range: tuple[int, int] = (-(2**31), 2**31 - 1)
    plc_kind: str = "bool"  # dtype of the PLC side: bool / int / float
    name: str = ""  # trace column of the PLC side
    settle: float = 0.0  # s after a change during which the module must be called
    memoryless: bool = False
    invert: bool = False
    state: list[Any] = field(default_factory=list)

    @property
    def label(self) -> str:
        return self.row.label()

    @property
    def kind(self) -> ModuleKind:
        """The specification of the row's module (:data:`plclab.io.modules.KINDS`)."""
        return MODULES[self.row.module]


@dataclass
class Transfer:
    """The compiled I/O transfer of a bound wiring table."""

    channels: list[Channel]
    inputs: list[Channel]
    outputs: list[Channel]
    read_in: Any
    read_out: Any
    apply_out: Any
    source: str  # the generated Python (for the curious and for debugging)
    warnings: list[str]
    # the same code as loose statements, for the simulation's fused loop (ADR 0032): the
    # input statements leave x<i> (``in_names``) and read ``t`` and the plant's values ``v``;
    # the outputs are the expressions ``out_items`` (stored in q<i>); ``apply_body`` reads
    # q<i> and ``t``. They run in ``namespace``.
    namespace: dict[str, Any] = field(default_factory=dict)
    in_body: list[str] = field(default_factory=list)
    in_names: list[str] = field(default_factory=list)
    out_items: list[str] = field(default_factory=list)
    apply_body: list[str] = field(default_factory=list)

    def find(self, target: str) -> list[Channel]:
        """Channels whose PLC side or plant signal is ``target`` (case-insensitive)."""
        t = target.strip().upper()
        return [c for c in self.channels if c.row.plc.upper() == t or c.name.upper() == t
                or c.signal.name.upper() == t]

    def mark_dirty(self, ch: Channel) -> None:
        """Make the next transfer call the channel's module (after a fault change)."""
        if ch.direction == "in" and ch.kind.transfer == "sampled" and ch.memoryless:
            ch.state[0], ch.state[1] = math.inf, -math.inf
        else:
            ch.state[0] = _DIRTY


_DIRTY = object()


def _declared(plc: Any, address: str) -> Any:
    """The type of a located variable declared at ``address`` (or None)."""
    for v in plc.project.symbols.located_vars():
        if v.address == address:
            return v.decl.ty
    return None


def type_kind(ty: Any) -> tuple[str, tuple[int, int]]:
    """('bool' | 'int' | 'real' | other kind, integer range) of a PLC type."""
    from plclab.lang import types as T

    t = T.resolve(ty)
    base = T.base_of(t)
    kind = getattr(base, "kind", "?")
    if kind == "bool":
        return "bool", (0, 1)
    if kind in ("int", "bits"):
        lo = getattr(t, "lo", None)
        hi = getattr(t, "hi", None)
        if lo is None or hi is None:
            bits = getattr(base, "bits", 32) or 32
            signed = getattr(base, "signed", False)
            lo, hi = (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1) if signed else (0, 2**bits - 1)
        return "int", (int(lo), int(hi))
    if kind == "real":
        return "real", (0, 0)
    return kind, (0, 0)


def bind(wiring: Wiring, plant: Any, plc: Any, seed: int = 0) -> Transfer:
    """Check ``wiring`` against ``plant`` and ``plc``; build modules and the transfer.

    Raises
    ------
    PlcError
        One error carrying a diagnostic for every bad row (codes PLC4002-PLC4008).
    """
    diags: list[Diagnostic] = []
    signals = plant.signals
    if wiring.plant and wiring.plant != plant.name:
        raise sim_error("PLC4008", f"this wiring is for the plant '{wiring.plant}', but the "
                        f"simulation runs '{plant.name}'; use a wiring file made for "
                        f"'{plant.name}' (plclab/sim/wirings/{plant.name}.toml) or none for the default",
                        wiring.source)
    channels: list[Channel] = []
    in_bits: dict[tuple[int, int], WireRow] = {}
    in_vars: dict[str, WireRow] = {}
    driven: dict[str, WireRow] = {}

    for row in wiring.rows:
        n0 = len(diags)

        def bad(code: str, msg: str, key: str | None = None, row: WireRow = row) -> None:
            diags.append(Diagnostic(code, f"{row.label()}: {msg}", row.where(key)))

        sig = signals.get(row.signal)
        if sig is None:
            bad("PLC4002", f"plant '{plant.name}' has no signal '{row.signal}'."
                f"{did_you_mean(row.signal, signals)} Its signals: {', '.join(signals)}",
                "signal")
            continue
        spec = MODULES[row.module]
        direction = spec.direction
        if direction is None:
            if row.is_address:
                area = row.plc[1]
                direction = "in" if area == "I" else "out" if area == "Q" else None
                if direction is None:
                    bad("PLC4004", f"{row.plc} is PLC memory (%M); wire plant signals to inputs "
                        "(%I) or outputs (%Q), or to a variable", "plc")
                    continue
            else:
                direction = "in" if sig.kind in ("sensor", "panel") else "out"
        # -- direction against the signal's kind
        if direction == "in" and sig.kind in ("actuator", "lamp"):
            bad("PLC4003", f"{sig.name} is {_a(sig.kind)} {sig.kind}: the PLC drives it. Wire it "
                f"from an output: module {_kinds('out')} (or direct) with a %Q address or an "
                "output variable", "module" if spec.direction else "plc")
            continue
        if direction == "out" and sig.kind == "sensor":
            bad("PLC4003", f"{sig.name} is a sensor: the plant computes it and the PLC can only "
                f"read it. Wire it to an input: module {_kinds('in')} (or direct) with a %I "
                "address", "module" if spec.direction else "plc")
            continue
        if direction == "out" and sig.kind == "panel":
            bad("PLC4003", f"{sig.name} is a panel input (an operator button, switch or the "
                "environment): the scenario sets it and the PLC reads it. Wire it to an input "
                "(%I); set it from a scenario", "module" if spec.direction else "plc")
            continue
        # -- the module against the signal's type
        is_bool = sig.type == "bool"
        if not spec.takes(is_bool, row.params):
            bad("PLC4006", _wrong_signal(spec, sig, is_bool), "module")
            continue
        if is_bool and spec.real_param in row.params:
            bad("PLC4006", f"{spec.real_param} only applies to REAL signals; {sig.name} is BOOL",
                spec.real_param)
            continue
        if row.params.get("invert") and not is_bool:
            bad("PLC4006", f"invert only applies to BOOL signals; {sig.name} is REAL", "invert")
            continue
        ch = Channel(row, direction, sig, invert=bool(row.params.get("invert", False)))
        # -- the PLC side
        if row.is_address:
            _bind_address(ch, row, plc, direction, is_bool, bad)
        else:
            _bind_variable(ch, row, plc, direction, is_bool, bad)
        if len(diags) > n0:
            continue
        # -- duplicates
        if direction == "in":
            if ch.address is not None:
                n = SIZE_BYTES[ch.size]
                keys = [(ch.byte, ch.bit)] if ch.size == "X" else \
                    [(b, k) for b in range(ch.byte, ch.byte + n) for k in range(8)]
                clash = next((in_bits[k] for k in keys if k in in_bits), None)
                if clash is not None:
                    bad("PLC4007", f"{row.plc} overlaps {clash.plc} of wiring row {clash.index}: "
                        "two signals cannot drive the same input terminal", "plc")
                    continue
                for k in keys:
                    in_bits[k] = row
            else:
                key = ch.var.path.upper()
                if key in in_vars:
                    bad("PLC4007", f"variable {row.plc} is already written by wiring row "
                        f"{in_vars[key].index}", "plc")
                    continue
                in_vars[key] = row
        else:
            if sig.name in driven:
                bad("PLC4007", f"{sig.name} is already driven by wiring row "
                    f"{driven[sig.name].index} ({driven[sig.name].plc}); an actuator can have "
                    "only one output", "signal")
                continue
            driven[sig.name] = row
        # -- the module
        try:
            _make_module(ch, row, sig, seed)
        except PlcError as e:
            bad("PLC4006", f"the {row.module} module rejects its parameters: {e.message}",
                "module")
            continue
        channels.append(ch)
    raise_all(diags)
    return _compile(channels, plant, plc)


def _a(word: str) -> str:
    return "an" if word[0] in "aeiou" else "a"


def _kinds(direction: str) -> str:
    """``di/ai``: the module kinds of one direction, for messages."""
    return "/".join(k.name for k in MODULES.values() if k.direction == direction)


def _wrong_signal(kind: ModuleKind, sig: Any, is_bool: bool) -> str:
    """Why a module kind cannot carry a plant signal, and what to use instead."""
    alt = alternative(kind, "bool" if is_bool else "real")
    other = alt.name if alt else "another module"
    if is_bool:
        return f"{sig.name} is a BOOL signal; module {kind.name} is for REAL signals: use {other}"
    head = f"{sig.name} is a REAL {sig.kind} ({sig.unit}); module {kind.name} carries a bit"
    if kind.real_param:
        return f"{head}: give {kind.real_param} = <value> " \
               f"({kind.params[kind.real_param].help}) to turn it into one, or use module {other}"
    return f"{head}: use module {other} or direct"


def _bind_address(ch: Channel, row: WireRow, plc: Any, direction: str, is_bool: bool,
                  bad: Any) -> None:
    m = ADDRESS_RE.fullmatch(row.plc)
    assert m is not None
    area, size, byte = m.group(1).upper(), (m.group(2) or "X").upper(), int(m.group(3))
    bit = m.group(4)
    want = "I" if direction == "in" else "Q"
    if area != want:
        if area == "M":
            bad("PLC4004", f"{row.plc} is PLC memory (%M); plant signals go to inputs (%I) and "
                "come from outputs (%Q)", "plc")
        elif direction == "in":
            bad("PLC4004", f"{row.plc} is an output address, but {ch.signal.name} goes into the "
                f"PLC (module {row.module}); use an input address such as "
                f"%I{row.plc[2:]}", "plc")
        else:
            bad("PLC4004", f"{row.plc} is an input address, but {ch.signal.name} is driven by "
                f"the PLC (module {row.module}); use an output address such as "
                f"%Q{row.plc[2:]}", "plc")
        return
    if size == "X":
        if bit is None or not 0 <= int(bit) <= 7:
            bad("PLC4004", f"{row.plc}: a bit address is byte.bit with bit 0..7, e.g. "
                f"%{area}X{byte}.0", "plc")
            return
    elif bit is not None:
        bad("PLC4004", f"{row.plc}: only bit addresses (X) have a .bit part", "plc")
        return
    n = SIZE_BYTES[size]
    if byte + n > plc.image_size:
        bad("PLC4004", f"{row.plc} is beyond the process image ({plc.image_size} bytes; "
            "give a larger one: --image-size, Plc(..., image_size=...))", "plc")
        return
    mod, spec = row.module, MODULES[row.module]
    if spec.carries == "bit" or (spec.carries == "value" and is_bool):
        if size != "X":
            bad("PLC4004", f"{ch.signal.name} is a BOOL signal: wire it to a bit address such as "
                f"%{area}X{byte}.0, not {row.plc}", "plc")
            return
    elif size == "X":
        what = "counts" if spec.carries == "counts" else "a number"
        bad("PLC4004", f"{ch.signal.name} is a REAL signal ({what}): wire it to a word such as "
            f"%{area}W{byte} (or %{area}D for 32 bits), not the bit {row.plc}", "plc")
        return
    elif spec.sizes and size not in spec.sizes:
        fits = " or ".join(f"{_SIZE_NAMES[z]} (%{area}{z}{byte})" for z in spec.sizes)
        bad("PLC4004", f"module {mod} carries {spec.carries}: they need {fits}, not {row.plc}",
            "plc")
        return
    ch.address = row.plc
    ch.size, ch.byte, ch.bit = size, byte, int(bit or 0)
    ch.name = row.plc
    if size == "X":
        ch.plc_kind = "bool"
        return
    declared = _declared(plc, row.plc)
    kind = type_kind(declared)[0] if declared is not None else ""
    if kind == "real" and spec.carries == "value" and size in ("D", "L"):
        ch.float_fmt = ">f" if size == "D" else ">d"
        ch.plc_kind = "float"
        return
    if kind == "real":
        bad("PLC4004", f"{row.plc} holds a REAL variable in the program; module {mod} delivers "
            "integer counts. Declare it as INT (and scale in the program) or use module direct "
            "with a %ID address", "plc")
        return
    bits = 8 * n
    signed = size != "B"
    ch.int_range = (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1) if signed else (0, 2**bits - 1)
    ch.plc_kind = "int"


def _bind_variable(ch: Channel, row: WireRow, plc: Any, direction: str, is_bool: bool,
                   bad: Any) -> None:
    try:
        var = plc.var(row.plc)
    except PlcError as e:
        bad("PLC4004", f"{e.message}; name a variable of the program (e.g. Main.SP) or an "
            "address such as %IX0.0", "plc")
        return
    kind, rng = type_kind(var.type)
    mod, carries = row.module, MODULES[row.module].carries
    need_bool = carries == "bit" or (carries == "value" and is_bool)
    if need_bool and kind != "bool":
        bad("PLC4004", f"{row.plc} is {var.type}; {ch.signal.name} is a bit: wire it to a BOOL "
            "variable", "plc")
        return
    if carries == "counts" and kind != "int":
        bad("PLC4004", f"{row.plc} is {var.type}; module {mod} carries integer counts: use an "
            "INT variable (or module direct to copy engineering units into a REAL)", "plc")
        return
    if carries == "value" and not is_bool and kind not in ("int", "real"):
        bad("PLC4004", f"{row.plc} is {var.type}; {ch.signal.name} is a number: use a REAL or "
            "integer variable", "plc")
        return
    addr = (var.address or "").upper()
    if addr and not addr.endswith("*"):
        area = addr[1]
        if direction == "in" and area != "I" or direction == "out" and area not in ("Q", "M"):
            bad("PLC4004", f"{row.plc} is located at {addr}, which does not fit a signal going "
                f"{'into' if direction == 'in' else 'out of'} the PLC", "plc")
            return
        if area in ("I", "Q"):
            # a located variable: go through its terminal, like the hardware does
            alias = WireRow(addr, row.signal, row.module, row.params, row.description,
                            row.location, row.index, row.key_locations)
            _bind_address(ch, alias, plc, direction, is_bool, bad)
            ch.name = row.plc
            return
    ch.var = var
    ch.var_kind = kind
    ch.int_range = rng
    ch.name = row.plc
    ch.plc_kind = {"bool": "bool", "int": "int", "real": "float"}[kind]


def _make_module(ch: Channel, row: WireRow, sig: Any, sim_seed: int) -> None:
    kind = MODULES[row.module]
    if kind.build is None:
        return
    p = dict(row.params)
    p.pop("invert", None)  # the channel inverts, not the module
    if "seed" in kind.params:
        row_seed = p.pop("seed", None)
        p["seed"] = mix_seed(sim_seed, kind.name, row_seed if row_seed is not None else row.index,
                             row.signal)
    ch.module = kind.build(p, sig)
    ch.settle = kind.settle(ch.module)
    ch.memoryless = kind.memoryless(ch.module)


# --------------------------------------------------------------------------- code generation
def _compile(channels: list[Channel], plant: Any, plc: Any) -> Transfer:
    ins = [c for c in channels if c.direction == "in"]
    outs = [c for c in channels if c.direction == "out"]
    ns: dict[str, Any] = {"I": plc.inputs, "Q": plc.outputs, "_W": plant.write,
                          "_pack": struct.pack_into, "_unpack": struct.unpack_from,
                          "_DIRTY": _DIRTY, "__builtins__": __builtins__,
                          "_E": lambda ch, closed: None, "math": math}
    lines: list[str] = []
    emit = lines.append
    values = plant.values()

    # ---- read_in
    emit("def read_in(t, v):")
    names = []
    for i, ch in enumerate(ins):
        s = f"_s{i}"
        ns[s] = ch.state = [_DIRTY, -1.0, None]
        sig = repr(ch.signal.name)
        x = f"x{i}"
        names.append(x)
        TRANSFERS[ch.kind.transfer][0](ch, i, x, s, sig, ns, emit)
        emit(_write_in(ch, i, x, ns))
    in_body = lines[1:]
    emit(f"    return ({''.join(n + ', ' for n in names)})")

    # ---- read_out
    emit("def read_out():")
    items = []
    for i, ch in enumerate(outs):
        if ch.var is not None:
            ns[f"_g{i}"] = ch.var.get
            items.append(f"_g{i}()")
        elif ch.size == "X":
            items.append(f"Q[{ch.byte}] & {1 << ch.bit} != 0")
        elif ch.float_fmt:
            items.append(f"_unpack({ch.float_fmt!r}, Q, {ch.byte})[0]")
        else:
            n = SIZE_BYTES[ch.size]
            signed = ch.size != "B"
            items.append(f"int.from_bytes(Q[{ch.byte}:{ch.byte + n}], 'big', signed={signed})")
    emit(f"    return ({''.join(it + ', ' for it in items)})")

    # ---- apply_out
    emit("def apply_out(t, q):")
    for i, ch in enumerate(outs):
        s = f"_o{i}"
        ns[s] = ch.state = [_DIRTY, -1.0, values[ch.signal.name]]
        sig = repr(ch.signal.name)
        if ch.signal.type == "bool":
            cmd = f"{'not ' if ch.invert else ''}@q{i}@"
            if ch.var is not None and ch.var_kind != "bool":
                cmd = f"{'not ' if ch.invert else ''}bool(@q{i}@)"
        else:
            cmd = f"@q{i}@"
        TRANSFERS[ch.kind.transfer][1](ch, i, s, sig, cmd, ns, emit)
    emit("    return None")
    k = lines.index("def apply_out(t, q):")
    apply_body = lines[k + 1:-1]
    lines = [_QREF.sub(r"q[\1]", ln) for ln in lines]
    source = "\n".join(lines) + "\n"
    code = compile(source, "<plclab-sim-io>", "exec")
    exec(code, ns)  # noqa: S102 - generated from checked rows; names only as repr() literals
    return Transfer(channels, ins, outs, ns["read_in"], ns["read_out"], ns["apply_out"], source,
                    _warnings(channels, plc), ns, in_body, names, items,
                    [_QREF.sub(r"q\1", ln) for ln in apply_body])


_QREF = re.compile(r"@q(\d+)@")


def _write_in(ch: Channel, i: int, x: str, ns: dict[str, Any]) -> str:
    if ch.var is not None:
        ns[f"_w{i}"] = ch.var.set
        if ch.var_kind == "bool":
            return f"    _w{i}(bool({x}))"
        if ch.var_kind == "int":
            lo, hi = ch.int_range
            return f"    _w{i}({lo} if {x} < {lo} else {hi} if {x} > {hi} else int({x}))"
        from plclab.runtime.plc import convert_in

        ns[f"_c{i}"] = convert_in
        ns[f"_t{i}"] = ch.var.type
        return f"    _w{i}(_c{i}(float({x}), _t{i}))"
    b = ch.byte
    if ch.size == "X":
        m = 1 << ch.bit
        return f"    I[{b}] = (I[{b}] | {m}) if {x} else (I[{b}] & {0xFF ^ m})"
    if ch.float_fmt:
        return f"    _pack({ch.float_fmt!r}, I, {b}, {x})"
    n = SIZE_BYTES[ch.size]
    if n == 1:
        return f"    I[{b}] = {x} & 255"
    if n == 2:
        return f"    I[{b}] = ({x} >> 8) & 255; I[{b + 1}] = {x} & 255"
    return f"    I[{b}:{b + n}] = ({x} & {(1 << (8 * n)) - 1}).to_bytes({n}, 'big')"


def _warnings(channels: list[Channel], plc: Any) -> list[str]:
    """Located PLC inputs nobody wires, located outputs that drive nothing."""
    wired = {c.address for c in channels if c.address}
    out = []
    for v in plc.project.symbols.located_vars():
        name, a = v.path, v.address
        if v.wildcard or a[1] not in "IQ":
            continue
        if a not in wired and not _covered(a, wired):
            if a[1] == "I":
                out.append(f"{name} AT {a} is not wired: it stays at 0/FALSE unless a scenario "
                           "sets it")
            else:
                out.append(f"{name} AT {a} is not wired: it drives nothing in the plant")
    return out


def _covered(addr: str, wired: set[str]) -> bool:
    """True when a bit address lies inside a wired byte/word (or the other way round)."""
    m = ADDRESS_RE.fullmatch(addr.upper())
    if not m:
        return False
    area, size, byte = m.group(1), (m.group(2) or "X"), int(m.group(3))
    lo, hi = byte, byte + SIZE_BYTES[size]
    for w in wired:
        mw = ADDRESS_RE.fullmatch(w.upper())
        if not mw or mw.group(1) != area:
            continue
        s2, b2 = (mw.group(2) or "X"), int(mw.group(3))
        if size == "X" and s2 == "X":
            continue
        if b2 < hi and lo < b2 + SIZE_BYTES[s2]:
            return True
    return False
