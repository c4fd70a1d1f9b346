"""Variables of :class:`~plclab.runtime.plc.Plc` by path (``Main.t1.ET``, ``arr[3]``, ``%QX0.0``),
their values in and out (``convert_in``, ``format_typed``) (a mixin, moved out of plc.py)."""


from __future__ import annotations

import datetime as _dt
import re
from dataclasses import dataclass
from dataclasses import replace as _replace
from typing import Any

from ..compile.codegen import kind_name
from ..errors import PlcError
from ..lang import types as T
from ..names import split_outside_brackets
from .plc_limits import (
    ADDR_RE,
    SIZE_BYTES,
    check_address,
)
from .rt import format_value

_PATH_RE = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[[^\]]*\])*)")


MAX_SHOWN = 1000  # elements of an array that format_typed writes out


_SHOWN_SECTIONS = ("VAR_INPUT", "VAR_OUTPUT", "VAR")  # a block instance's state, shown
MAX_DEPTH = 4  # block instances inside block instances that format_typed writes out


def format_typed(v: Any, ty: Any, members: Any = None, depth: int = 0) -> str:
    """``v`` as an IEC literal of its declared type: arrays as ``[1, 2]`` (flat, as an array
    initializer; the first :data:`MAX_SHOWN` elements), structures as ``(X := 1, S := 'a')``,
    block instances as a structure of their inputs, outputs and variables (``(IN := TRUE,
    PT := T#1s, Q := FALSE, ET := T#0ms)``; VAR_IN_OUT and VAR_TEMP are not state), every
    element formatted by its own type (``T#1s``, ``'a$N'``), never a Python repr.
    ``members(pou)``: a block's variables with the inherited ones (the symbol table's)."""
    r = T.resolve(ty) if ty is not None else None
    if isinstance(r, T.ArrayType) and isinstance(v, list):
        shown = [format_typed(e, r.elem, members, depth) for e in v[:MAX_SHOWN]]
        if len(v) > MAX_SHOWN:
            shown.append(f"... {len(v) - MAX_SHOWN} more")
        return "[" + ", ".join(shown) + "]"
    if isinstance(r, T.StructType) and hasattr(type(v), "__slots__"):
        return "(" + ", ".join(
            f"{getattr(d, 'spelling', None) or n} := "
            f"{format_typed(getattr(v, n.upper(), None), d.ty, members, depth)}"
            for n, d in r.fields.items()) + ")"
    if isinstance(r, T.FBType) and r.pou is not None and hasattr(type(v), "__slots__") and \
            depth < MAX_DEPTH:
        decls = members(r.pou).values() if members is not None else r.pou.decls
        return "(" + ", ".join(
            f"{d.spelling or d.name} := "
            f"{format_typed(getattr(v, d.name.upper()), d.ty, members, depth + 1)}"
            for d in decls if d.section in _SHOWN_SECTIONS and not d.constant and
            d.ty is not None and hasattr(v, d.name.upper())) + ")"
    return format_value(v, kind_name(ty))


@dataclass
class Var:
    """A resolved variable path: how to read and write it and what type it has."""

    path: str
    type: T.Type
    get: Any
    set: Any
    address: str | None = None


class VariableAccess:
    """Variables by path (a mixin of Plc)."""

    # -- variables ----------------------------------------------------------------------------
    def var(self, path: str) -> Var:
        """Resolve ``"Main.t1.ET"``, ``"LS1"``, ``"arr[3]"`` or ``"%QX0.0"``."""
        key = path.strip().upper()
        v = self._var_cache.get(key)
        if v is None:
            v = self._resolve(path.strip())
            self._var_cache[key] = v
        return v

    def __getitem__(self, path: str) -> Any:
        return self.var(path).get()

    def __setitem__(self, path: str, value: Any) -> None:
        v = self.var(path)
        v.set(convert_in(value, v.type, path))

    def get(self, path: str, iec: bool = False) -> Any:
        v = self.var(path)
        val = v.get()
        return format_typed(val, v.type, self.project.symbols.members) if iec else val

    def format(self, path: str) -> str:
        """The value as an IEC literal (``T#1s``, ``TRUE``, ``7.8``)."""
        return self.get(path, iec=True)

    def _access_var(self, path: str, access: Any) -> Var:
        """An access path (VAR_ACCESS) is the variable it names; READ_ONLY refuses writes."""
        v = self._resolve(access.target)
        if not access.read_only:
            return Var(path, v.type, v.get, v.set, v.address)

        def refuse(_value: Any) -> None:
            raise PlcError("PLC3013", f"{access.spelling} is a READ_ONLY access path; write {access.target} itself, or declare the access "
                           "path READ_WRITE")

        return Var(path, v.type, v.get, refuse, v.address)

    def _resolve(self, path: str) -> Var:
        if path.startswith("%"):
            return self._address_var(path)
        parts = _split_path(path)
        if not parts:
            raise PlcError("PLC3001", f"'{path}' is not a variable path")
        head, idx = parts[0]
        head_u = head.upper()
        progs = {n.upper(): pou for n, pou, _ in self.project.programs}

        def program(name: str):
            attr = name.replace(".", "__")  # RESA.MAIN: a resource's instance (ADR 0037)
            return lambda: getattr(self.ns["_P"], attr)

        res_globals = self.project.symbols.resource_globals
        if len(parts) > 1 and not idx and (head_u in res_globals or any(
                n.startswith(head_u + ".") for n in progs)):
            # RESA.MAIN.x (a program of resource RESA) or RESA.g (a global of RESA)
            second = parts[1][0].upper()
            key = f"{head_u}.{second}"
            if key in progs and (len(parts) > 2 or parts[1][1]):
                if parts[1][1]:
                    raise PlcError("PLC3001", f"{parts[1][0]} is a program, not an array")
                pou = progs[key]
                return self._walk(path, program(key), T.FBType(pou.name, pou), parts[2:],
                                  head_u)
            if second in res_globals.get(head_u, {}):
                return self._walk(path, lambda: self.ns[f"_RG_{head_u}"],
                                  _GlobalsType(self.project, head_u), parts[1:], head_u)

        access = self.project.symbols.access_paths.get(head_u)
        if access is not None and len(parts) == 1 and not idx:  # VAR_ACCESS of the configuration
            return self._access_var(path, access)
        # 1. a program instance name 2. a global 3. a variable of exactly one program
        if head_u in progs and (len(parts) > 1 or idx):
            if idx:
                raise PlcError("PLC3001", f"{head} is a program, not an array")
            pou = progs[head_u]
            own = self.project.symbols.program_access.get(pou.name, {})
            if len(parts) == 2 and not parts[1][1] and parts[1][0].upper() in own:
                # Inst.ax: the program's own VAR_ACCESS (ed.2/ed.3 program_access_decls)
                ap = own[parts[1][0].upper()]
                return self._access_var(path, _replace(
                    ap, target=f"{head}.{ap.target}"))
            return self._walk(path, program(head_u), T.FBType(pou.name, pou), parts[1:])
        if head_u in self.project.globals:
            return self._walk(path, lambda: self.ns["_G"], _GlobalsType(self.project), parts)
        owners = self.project.symbols.programs_declaring(head_u)
        if len(owners) == 1:
            n, pou = owners[0]
            return self._walk(path, program(n.upper()), T.FBType(pou.name, pou), parts)
        if len(owners) > 1:
            raise PlcError("PLC3001", f"{head} exists in several programs ("
                           + ", ".join(n for n, _ in owners) + f"); write e.g. "
                           f"{owners[0][0]}.{head}")
        from ..suggest import suggest

        symbols = self.project.symbols
        cands = [name for _, pou, _ in symbols.programs() for name in symbols.members(pou)]
        cands += list(self.project.globals) + [n for n, _, _ in self.project.programs]
        close = suggest(head_u, cands)
        hint = f"; did you mean {close[0]}?" if close else ""
        raise PlcError("PLC3001", f"no variable named {path}{hint}")

    def _walk(self, path: str, get_obj, ty: T.Type, parts, resource: str | None = None) -> Var:
        """Build getter/setter closures walking members and indices from a root object;
        ``resource``: the resource of the program instance walked (ADR 0037)."""
        steps: list[tuple[str, Any]] = []
        cur = ty
        address = None
        for name, idx in parts:
            cur = T.resolve(cur)
            nu = name.upper()
            if isinstance(cur, _GlobalsType):
                d = cur.globals().get(nu)
                address = d.address if d is not None else None
            elif isinstance(cur, T.FBType) and cur.pou is not None:
                d = self.project.symbols.members(cur.pou).get(nu)
                if d is not None and d.section == "VAR_TEMP":
                    d = None
                if d is not None and d.section == "VAR_EXTERNAL":
                    rest = [(name, idx)] + parts[parts.index((name, idx)) + 1:]
                    if resource and nu not in self.project.globals and nu in \
                            self.project.symbols.resource_globals.get(resource, {}):
                        return self._walk(path, lambda: self.ns[f"_RG_{resource}"],
                                          _GlobalsType(self.project, resource), rest)
                    return self._walk(path, lambda: self.ns["_G"], _GlobalsType(self.project),
                                      rest)
                address = d.address if d is not None else None
            elif isinstance(cur, T.StructType):
                d = cur.fields.get(nu)
            else:
                d = None
            if d is None:
                raise PlcError("PLC3001", f"{path}: {cur} has no member {name}")
            steps.append(("attr", nu))
            cur = d.ty
            for ixs in idx:
                at = T.resolve(cur)
                if not isinstance(at, T.ArrayType) or len(ixs) != len(at.dims):
                    raise PlcError("PLC3001", f"{path}: wrong index for {at}")
                flat, stride = 0, 1
                for i, (lo, hi) in reversed(list(zip(ixs, at.dims, strict=True))):
                    if not lo <= i <= hi:
                        raise PlcError("PLC3001", f"{path}: index {i} is outside {lo}..{hi}")
                    flat += (i - lo) * stride
                    stride *= hi - lo + 1
                steps.append(("item", flat))
                cur = at.elem
        final_t = cur

        def walk_to_parent():
            o = get_obj()
            for kind, key in steps[:-1]:
                o = getattr(o, key) if kind == "attr" else o[key]
            return o

        last_kind, last_key = steps[-1]
        if last_kind == "attr":
            def getter():
                return getattr(walk_to_parent(), last_key)

            def setter(v):
                setattr(walk_to_parent(), last_key, v)
                if address:  # a located variable is its bytes of the image (ADR 0056)
                    self._write_address(address, v, final_t, physical=True)
        else:
            def getter():
                return walk_to_parent()[last_key]

            def setter(v):
                walk_to_parent()[last_key] = v
        return Var(path, final_t, getter, setter, address)

    def _address_var(self, addr: str) -> Var:
        a = addr.upper()
        area, size, byte, bit = check_address(a, self.image_size)
        n = SIZE_BYTES[size]
        ty = {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[size]
        # reading %I gives the input terminals, %Q the output terminals, %M the memory
        buf = {"I": lambda: self.inputs, "Q": lambda: self.outputs, "M": lambda: self.memory}[area]

        def getter():
            b = buf()
            if size == "X":
                return bool(b[byte] >> int(bit) & 1)
            return int.from_bytes(b[byte:byte + n], "big")

        def setter(v):
            if area == "Q":
                self._write_bytes(self.image_out, size, byte, bit, v)
            self._write_bytes(buf(), size, byte, bit, v)

        return Var(addr, ty, getter, setter, a)

    @staticmethod
    def _write_bytes(b: bytearray, size: str, byte: int, bit, v) -> None:
        if size == "X":
            if v:
                b[byte] |= 1 << int(bit)
            else:
                b[byte] &= 0xFF ^ (1 << int(bit))
        else:
            n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
            b[byte:byte + n] = (int(v) & ((1 << (8 * n)) - 1)).to_bytes(n, "big")

    def _write_address(self, address: str, value: Any, ty: T.Type, physical: bool) -> None:
        import struct as _struct

        m = ADDR_RE.fullmatch(address)
        if not m:
            return
        size = m.group(2) or "X"
        byte, bit = int(m.group(3)), m.group(4)
        # %I: the terminals (physical) or the frozen input image; %Q: the output image, which
        # the terminals follow at scan end; %M: the memory (ADR 0056)
        tgt = {"I": self.inputs if physical else self.image_in, "Q": self.image_out,
               "M": self.memory}[m.group(1)]
        t = T.base_of(ty)
        if t.kind == "real":
            fmt = ">f" if size == "D" else ">d"
            _struct.pack_into(fmt, tgt, byte, float(value))
        else:
            self._write_bytes(tgt, size, byte, bit, value)


class _GlobalsType(T.Type):
    kind = "globals"
    name = "globals"

    def __init__(self, project, resource: str | None = None) -> None:
        self.project = project
        self.resource = resource  # the globals of this resource (ADR 0037)

    def globals(self) -> dict:
        if self.resource is not None:
            return self.project.symbols.resource_globals.get(self.resource, {})
        return self.project.globals


def _split_path(path: str) -> list[tuple[str, list[list[int]]]]:
    out = []
    for seg in _split_dots(path):
        m = _PATH_RE.fullmatch(seg.strip())
        if not m:
            raise PlcError("PLC3001", f"'{path}' is not a variable path (e.g. Main.t1.Q, "
                           "arr[2], %QX0.0)")
        idx = []
        for grp in re.findall(r"\[([^\]]*)\]", m.group(2)):
            try:
                idx.append([int(x) for x in grp.split(",")])
            except ValueError:
                raise PlcError("PLC3001", f"'{path}': indices must be integers") from None
        out.append((m.group(1), idx))
    return out


def _split_dots(path: str) -> list[str]:
    return split_outside_brackets(path, ".")


def convert_in(value: Any, ty: T.Type, path: str = "") -> Any:
    """Convert a Python value or an IEC literal string to the run-time form of ``ty``."""
    t = T.resolve(ty)
    if isinstance(value, str) and not isinstance(t, T.StringType):
        from .literals import parse_literal

        return parse_literal(value, t, path)
    if t is T.BOOL:
        if isinstance(value, bool | int):
            return bool(value)
    elif isinstance(t, T.EnumType):
        if isinstance(value, int):
            return value
    elif t.kind in ("int", "bits"):
        if isinstance(value, bool):
            return int(value)
        if isinstance(value, int):
            lo, hi = (t.lo, t.hi) if isinstance(t, T.Elementary | T.Subrange) else (None, None)
            if lo is not None and not lo <= value <= hi:
                raise PlcError("PLC3002", f"{path}: {value} does not fit {t} ({lo}..{hi})")
            return value
    elif t.kind == "real":
        if isinstance(value, int | float) and not isinstance(value, bool):
            from ..compile.real32 import f32

            return f32(float(value)) if t is T.REAL else float(value)
    elif t.kind == "time":
        if isinstance(value, _dt.timedelta):
            ns = round(value.total_seconds() * 1e9)
            return ns if t is T.LTIME else ns // 1_000_000
        if isinstance(value, int) and not isinstance(value, bool):
            return value
    elif isinstance(t, T.StringType):
        if isinstance(value, str):
            return value[: t.length]
    elif t.kind in ("date", "tod", "dt") and isinstance(value, int):
        return value
    elif t is T.ANY:
        return value
    raise PlcError("PLC3002", f"{path}: cannot store {value!r} in a {t} variable")
