"""The browse tree: every global and program variable of a PLC as an OPC UA tag.

``Globals/<name>`` and ``Programs/<instance>/<name>``; a function block instance is a folder
of its variables (inputs, outputs, locals; never VAR_TEMP), a STRUCT a folder of its fields,
an array of a scalar type one array tag, an array of structures or blocks a folder of its
elements. References and interfaces are left out (they have no value a client could use).
Each tag's path is the one ``plc.var`` and ``plclab run`` understand (``Main.t1.ET``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from plclab.errors import PlcError
from plclab.lang import types as T
from plclab.suggest import suggest

from .typemap import kind_of

MAX_ELEMENTS = 256  # elements of an array of structures/blocks shown as a folder each
MAX_DEPTH = 8


@dataclass
class Tag:
    """One variable node: its PLC path, place in the tree, types, and how to read it."""

    path: str
    browse: tuple[str, ...]
    ty: Any
    kind: str  # OPC UA type name
    var: Any  # plclab.runtime.plc.Var
    dims: list[int] | None = None  # array dimensions, None for a scalar
    address: str | None = None
    section: str = "VAR"
    constant: bool = False
    writable: bool = False


@dataclass
class Tree:
    tags: list[Tag] = field(default_factory=list)
    folders: list[tuple[str, ...]] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)

    def by_path(self) -> dict[str, Tag]:
        return {t.path.upper(): t for t in self.tags}


def build_tree(plc: Any) -> Tree:
    """Walk the PLC's globals and program instances into a :class:`Tree`."""
    tree = Tree()
    project = plc.project
    symbols = project.symbols
    gl = [(d.spelling or d.name, d) for d in project.globals.values()]
    if gl:
        tree.folders.append(("Globals",))
    for name, d in gl:
        _add(tree, plc, name, ("Globals", name), d, 0)
    progs = list(symbols.programs())
    if progs:
        tree.folders.append(("Programs",))
    from plclab.lang.check.symbols import instance_label

    for inst, pou, _ in progs:
        label = instance_label(inst, pou)
        tree.folders.append(("Programs", label))
        for d in symbols.members(pou).values():
            if d.section == "VAR_TEMP" or d.name.startswith("__"):
                continue
            name = d.spelling or d.name
            _add(tree, plc, f"{label}.{name}", ("Programs", label, name), d, 0)
    return tree


def _add(tree: Tree, plc: Any, path: str, browse: tuple[str, ...], decl: Any, depth: int,
         ty: Any = None) -> None:
    try:
        var = plc.var(path)
    except PlcError:
        tree.skipped.append(path)
        return
    ty = var.type if ty is None else ty
    r = T.resolve(ty)
    section = getattr(decl, "section", "VAR") if decl is not None else "VAR"
    constant = bool(getattr(decl, "constant", False)) if decl is not None else False
    kind = kind_of(r)
    if kind is not None:
        tree.tags.append(Tag(path, browse, ty, kind, var, None, var.address, section, constant))
        return
    if depth >= MAX_DEPTH:
        tree.skipped.append(path)
        return
    if isinstance(r, T.ArrayType):
        ek = kind_of(r.elem)
        if ek is not None:
            dims = [hi - lo + 1 for lo, hi in r.dims]
            tree.tags.append(Tag(path, browse, ty, ek, var, dims, var.address, section,
                                 constant))
            return
        if len(r.dims) != 1 or r.size > MAX_ELEMENTS:
            tree.skipped.append(path)
            return
        tree.folders.append(browse)
        lo, hi = r.dims[0]
        for i in range(lo, hi + 1):
            _add(tree, plc, f"{path}[{i}]", (*browse, f"[{i}]"), decl, depth + 1, r.elem)
        return
    if isinstance(r, T.StructType):
        tree.folders.append(browse)
        for fname, fd in r.fields.items():
            name = getattr(fd, "spelling", None) or fname
            _add(tree, plc, f"{path}.{name}", (*browse, name), fd, depth + 1)
        return
    if isinstance(r, T.FBType) and r.pou is not None:
        tree.folders.append(browse)
        for d in plc.project.symbols.members(r.pou).values():
            if d.section == "VAR_TEMP" or d.name.startswith("__"):
                continue
            name = d.spelling or d.name
            _add(tree, plc, f"{path}.{name}", (*browse, name), d, depth + 1)
        return
    tree.skipped.append(path)


def apply_rules(tree: Tree, access: Any, wired: dict[str, str] | None = None) -> list[Tag]:
    """Mark the tags the access rules name as writable; PLC7053 for a rule that names no tag
    or a tag a client must not write (an output, a constant, a block's output, an input the
    plant drives). ``wired``: upper-case address or path -> the plant signal driving it."""
    wired = wired or {}
    out = []
    for rule in access.writable:
        hits = [t for t in tree.tags if access.matches_one(rule, t.path)]
        if not hits:
            close = suggest(rule, [t.path for t in tree.tags])
            hint = f"; did you mean {close[0]}?" if close else \
                "; plclab opcua --list shows the variables"
            raise PlcError("PLC7053", f"writable rule {rule!r} ({access.source}) names no "
                           f"variable of the program{hint}")
        for t in hits:
            why = refusal(t, wired)
            if why:
                raise PlcError("PLC7053", f"writable rule {rule!r} ({access.source}): {t.path} "
                               f"{why}; name only inputs and set points")
            t.writable = True
            out.append(t)
    return out


def refusal(tag: Tag, wired: dict[str, str]) -> str:
    """Why a client may not write ``tag`` ("" when it may)."""
    addr = (tag.address or "").upper()
    if tag.constant:
        return "is a CONSTANT"
    if addr.startswith("%Q"):
        return f"is an output ({tag.address}): the program writes it every scan"
    if tag.section in ("VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL") and tag.path.count(".") > 1:
        return f"is a {tag.section} of a block: the block writes it"
    for key in (addr, tag.path.upper()):
        if key and key in wired:
            return f"is wired to the plant's signal {wired[key]}, which drives it every scan"
    return ""
