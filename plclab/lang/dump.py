"""A readable, indented dump of the AST (``plclab compile FILE --emit ast``).

One node a line: its class, its plain fields (names, operators, literal values), and its child
nodes indented below, each under the name of the field that holds it. Checker annotations
(``ty``, ``sym``) are left out; locations are shown as ``@line:col`` unless ``locations=False``,
which makes two dumps comparable whatever the layout of the source.

>>> from plclab.lang.frontends.st import parse_st
>>> print(dump(parse_st("PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM").pous[0].body))
Assign op=':=' @1:32
  target: Name name='X' @1:32
  value: Binary op='+' @1:39
    left: Name name='X' @1:37
    right: Literal value=1 kind='INT' @1:41
"""

from __future__ import annotations

import dataclasses

from .limits import compiler_guard

_SKIP = {"loc", "ty", "sym", "target", "text", "spelling", "used", "end_loc", "spellings"}


def dump(node: object, locations: bool = True) -> str:
    """The dump of a node, a list of nodes or a :class:`~plclab.lang.ast.SourceFile`."""
    lines: list[str] = []
    with compiler_guard():
        _dump(node, "", 0, lines, locations)
    return "\n".join(lines)


def _is_node(x: object) -> bool:
    return dataclasses.is_dataclass(x) and not isinstance(x, type) and \
        type(x).__name__ != "Location"


def _has_node(x: object) -> bool:
    if _is_node(x):
        return True
    if isinstance(x, list | tuple):
        return any(_has_node(i) for i in x)
    return False


def _dump(node: object, label: str, depth: int, lines: list[str], locations: bool) -> None:
    pad = "  " * depth
    if isinstance(node, tuple):  # (name, value, location), (lo, hi), (condition, body)...
        items = [i for i in node if type(i).__name__ != "Location"]
        plain = [repr(i) for i in items if not _has_node(i)]
        lines.append(f"{pad}{label + ': ' if label else ''}-" + "".join(" " + p for p in plain))
        for i in items:
            if _has_node(i):
                _dump(i, "", depth + 1, lines, locations)
        return
    if isinstance(node, list):
        if label:
            lines.append(f"{pad}{label}:" if node else f"{pad}{label}: []")
            depth += 1
        for item in node:
            _dump(item, "", depth, lines, locations)
        return
    if not _is_node(node):
        lines.append(f"{pad}{label + ': ' if label else ''}{node!r}")
        return
    plain, children = [], []
    for f in dataclasses.fields(node):
        if not f.repr:  # checker annotations and tool data (drawn rungs), not the program
            continue
        if f.name in _SKIP and not (f.name == "target" and type(node).__name__ == "Assign"):
            continue
        if f.name == "file" and not locations:
            continue
        value = getattr(node, f.name)
        if _has_node(value):
            children.append((f.name, value))
        elif value is not None and value != [] and (value is not False or f.name == "value"):
            plain.append(f"{f.name}={value!r}")
    loc = getattr(node, "loc", None)
    where = f" @{loc.line}:{loc.col}" if locations and loc is not None and loc.line else ""
    head = type(node).__name__ + "".join(" " + p for p in plain) + where
    lines.append(f"{pad}{label + ': ' if label else ''}{head}")
    for name, value in children:
        _dump(value, name, depth + 1, lines, locations)
