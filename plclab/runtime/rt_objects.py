"""Objects in generated code: ``ARRAY[*]`` arguments, interface variables, references
(REF_TO, POINTER TO), the copy of an instance and FB_exit (ADRs 0021, 0034, 0051, 0060)."""

from __future__ import annotations

from operator import attrgetter as _attrgetter

from .rt_faults import Fault, out_of_bounds


class _VLA:
    """The argument of an ``ARRAY[*]`` VAR_IN_OUT (ADR 0060): the caller's array (its flat
    list, shared, so writes reach the caller) and its bounds, ``((lo, hi), ...)``."""

    __slots__ = ("data", "dims")

    def __init__(self, data: list, dims: tuple[tuple[int, int], ...]) -> None:
        self.data = data
        self.dims = tuple(dims)


def _vla_ix(v: _VLA, ixs: tuple[int, ...], where: int) -> int:
    """The flat position of ``v[ixs]``; an index outside its dimension's bounds is PLC2002."""
    flat = 0
    for i, (lo, hi) in zip(ixs, v.dims, strict=True):
        if not lo <= i <= hi:
            out_of_bounds(i, lo, hi, where)
        flat = flat * (hi - lo + 1) + i - lo
    return flat


def _iref(obj, method: str, where: int):
    """The instance an interface variable refers to, for a call of ``method`` (ADR 0021)."""
    if obj is None:
        raise Fault("PLC9110", f"call of {method} through an interface variable that refers to "
                    "no instance; assign an instance first (itf := inst;) or test it with "
                    "__ISVALIDREF(itf) before the call", where)
    return obj


def _qi(obj, interface: str):
    """``obj`` if its block implements ``interface`` (``__QUERYINTERFACE``), else None."""
    return obj if obj is not None and interface in getattr(obj, "_itf", ()) else None


def fb_exit_all(roots) -> None:
    """FB_exit(bInCopyCode := FALSE) of every instance under ``roots`` (the program and global
    instances), each before the instances it contains (ADR 0021)."""
    seen: set[int] = set()
    stack = list(reversed(list(roots)))
    while stack:
        obj = stack.pop()
        if id(obj) in seen or obj is None or isinstance(obj, bool | int | float | str | bytes):
            continue
        seen.add(id(obj))
        if isinstance(obj, list):
            stack.extend(reversed(obj))
            continue
        exit_ = getattr(obj, "m_FB_EXIT", None)
        if exit_ is not None:
            exit_(False)
        slots = getattr(type(obj), "__slots__", ())
        stack.extend(reversed([getattr(obj, n, None) for n in slots]))


class _RefAttr:
    """A reference (REF_TO, POINTER TO) to the attribute ``key`` of ``obj`` (ADR 0021)."""

    __slots__ = ("obj", "key")

    def __init__(self, obj, key) -> None:
        self.obj, self.key = obj, key

    def get(self):
        return getattr(self.obj, self.key)

    def set(self, v) -> None:
        setattr(self.obj, self.key, v)

    def __eq__(self, other) -> bool:
        return type(other) is type(self) and other.obj is self.obj and other.key == self.key

    def __hash__(self) -> int:
        return hash((id(self.obj), self.key))


class _RefItem(_RefAttr):
    """A reference to the element ``key`` of the list ``obj`` (an ARRAY element)."""

    __slots__ = ()

    def get(self):
        return self.obj[self.key]

    def set(self, v) -> None:
        self.obj[self.key] = v


class _RefCell:
    """A reference to a local of the running FUNCTION, METHOD or TEST (a Python local): read
    and written through two closures; the checker lets it live only during the call (PLC0240,
    ADR 0051)."""

    __slots__ = ("get", "set")

    def __init__(self, get, set) -> None:  # noqa: A002
        self.get, self.set = get, set


_PUN = {"REAL": "<f", "LREAL": "<d", "SINT": "<b", "USINT": "<B", "BYTE": "<B", "INT": "<h",
        "UINT": "<H", "WORD": "<H", "DINT": "<i", "UDINT": "<I", "DWORD": "<I", "LINT": "<q",
        "ULINT": "<Q", "LWORD": "<Q"}


class _RefPun:
    """``pt : REF_TO DWORD; pt := REF(x)`` with ``x : REAL``: reads and writes ``x``'s bits as
    the other elementary type of the same size (IEEE 754, little-endian as on x86 and ARM PLCs;
    the codesys dialect, PLC0291, ADR 0051)."""

    __slots__ = ("ref", "src", "dst")

    def __init__(self, ref, src: str, dst: str) -> None:
        self.ref, self.src, self.dst = ref, _PUN[src], _PUN[dst]

    def get(self):
        import struct

        return struct.unpack(self.dst, struct.pack(self.src, self.ref.get()))[0]

    def set(self, v) -> None:
        import struct

        self.ref.set(struct.unpack(self.src, struct.pack(self.dst, v))[0])


def _deref(ref, where: int):
    """``ref`` for r^, or the fault PLC9111 when it is NULL."""
    if ref is None:
        raise Fault("PLC9111", "dereference of a NULL reference (r^ where r refers to no "
                    "variable); assign r := REF(x) first, or test __ISVALIDREF(r) or "
                    "r <> NULL before", where)
    return ref


def _setattrs(obj, **kw):
    for k, v in kw.items():
        setattr(obj, k, v)
    return obj


def _copier(plain: tuple[str, ...], objs: tuple[str, ...], lists: tuple[str, ...],
            obj_lists: tuple[str, ...]):
    """The ``_copy`` method of a generated class (ADR 0034): a new instance of the same class
    whose members ``plain`` (elementary values) are shared, ``objs`` (structures and block
    instances) copied by their own ``_copy``, ``lists`` (arrays of elementary values) copied
    and ``obj_lists`` (arrays of structures or blocks) copied element by element. One helper
    instead of a generated method per class keeps the generated source short."""
    get_plain = _attrgetter(*plain) if len(plain) > 1 else None

    def _copy(self):
        cls = self.__class__
        n = cls.__new__(cls)
        if get_plain is not None:
            for k, v in zip(plain, get_plain(self), strict=True):
                setattr(n, k, v)
        elif plain:
            setattr(n, plain[0], getattr(self, plain[0]))
        for k in objs:
            setattr(n, k, getattr(self, k)._copy())
        for k in lists:
            setattr(n, k, list(getattr(self, k)))
        for k in obj_lists:
            setattr(n, k, [e._copy() for e in getattr(self, k)])
        return n

    return _copy


RefAttr = _RefAttr  # the name the other helper modules import (a reference's IEC text)
