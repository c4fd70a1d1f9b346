"""Simple conditions on signals: ``LEVEL > 1.9``, ``RUN and SPEED >= 1400``, ``not LS1 or t > 60``.

Used by scenarios (``until``, evaluated once per scan on live values) and by
:meth:`plclab.trace.Trace.first_time` (evaluated on whole columns with NumPy).

The grammar is a small subset of Python expressions, with the ST spellings also accepted:

* numbers, ``True``/``False`` (``TRUE``/``FALSE``);
* names: plant signals, PLC variables (``Main.M``, ``arr[2]``) and addresses (``%QX0.0``),
  ``t`` = time in seconds;
* ``+ - * / // % **``, comparisons ``< <= > >= == !=`` (``=`` and ``<>`` too), chained
  comparisons ``0.5 <= LEVEL <= 1.5``;
* ``and or not`` (``AND OR NOT XOR``), ``abs()``, ``min()``, ``max()``.

Nothing else is accepted (no attribute access outside variable paths, no other calls), so a
condition from a file can never run arbitrary code.

>>> c = parse_condition("LEVEL > 1.9 AND NOT LS2")
>>> sorted(c.names)
['LEVEL', 'LS2']
>>> f = c.scalar({"LEVEL": "LEVEL", "LS2": "LS2"})
>>> f({"LEVEL": 2.0, "LS2": False}, 0.0)
True
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from collections.abc import Callable, Mapping
from typing import Any

from plclab.errors import PlcError
from plclab.lang.addresses import LOCATED

TIME_NAMES = ("t", "time")
_WORDS = {"AND": "and", "OR": "or", "NOT": "not", "TRUE": "True", "FALSE": "False",
          "XOR": "!="}
_FUNCS = ("abs", "min", "max")
_CMP = (ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.Eq, ast.NotEq)
_BIN = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.FloorDiv, ast.Mod, ast.Pow)


def _err(text: str, why: str) -> PlcError:
    return PlcError("PLC4013", f"condition {text!r}: {why}. Write e.g. 'LEVEL > 1.9', "
                    "'RUN and SPEED >= 1400', 'not LS1 or t > 60'")


_ADDR = re.compile(LOCATED, re.IGNORECASE)  # the direct addresses of plclab.lang.addresses


def _normalise(text: str) -> str:
    """ST spellings -> Python: AND/OR/NOT/XOR/TRUE/FALSE, '=' and '<>'; %IX0.0 -> a name."""
    text = _ADDR.sub(lambda m: "_pct_" + m.group(0)[1:].upper().replace(".", "_dot_"), text)
    out: list[tuple[int, str]] = []
    try:
        toks = list(tokenize.generate_tokens(io.StringIO(text.replace("<>", "!=")).readline))
    except (tokenize.TokenError, IndentationError, SyntaxError) as e:
        raise _err(text, f"cannot be read ({e})") from None
    for tok in toks:
        s = tok.string
        if tok.type == tokenize.NAME and s.upper() in _WORDS and s not in ("and", "or", "not"):
            s = _WORDS[s.upper()]
        elif tok.type == tokenize.OP and s == "=":
            s = "=="
        out.append((tok.type, s))
    return tokenize.untokenize(out)


def _path(node: ast.AST) -> str | None:
    """Dotted/indexed variable path of a Name/Attribute/Subscript chain, or None."""
    if isinstance(node, ast.Name):
        if node.id.startswith("_pct_"):
            return "%" + node.id[5:].replace("_dot_", ".")
        if node.id.startswith("__"):
            return None
        return node.id
    if isinstance(node, ast.Attribute):
        if node.attr.startswith("__"):
            return None
        base = _path(node.value)
        return None if base is None else f"{base}.{node.attr}"
    if isinstance(node, ast.Subscript):
        base = _path(node.value)
        sl = node.slice
        items = sl.elts if isinstance(sl, ast.Tuple) else [sl]
        idx = []
        for it in items:
            if isinstance(it, ast.UnaryOp) and isinstance(it.op, ast.USub) and \
                    isinstance(it.operand, ast.Constant):
                idx.append(-it.operand.value)
            elif isinstance(it, ast.Constant) and type(it.value) is int:
                idx.append(it.value)
            else:
                return None
        return None if base is None else f"{base}[{','.join(str(i) for i in idx)}]"
    return None


class Condition:
    """A parsed, checked condition; :meth:`scalar` and :meth:`vector` turn it into functions.

    Attributes
    ----------
    text : str
        The condition as written.
    names : set of str
        Every signal or variable path it reads (``t`` excluded).
    """

    def __init__(self, text: str, tree: ast.Expression, names: set[str]) -> None:
        self.text = text
        self.tree = tree
        self.names = names

    def __repr__(self) -> str:
        return f"Condition({self.text!r})"

    # ------------------------------------------------------------------ scalar
    def scalar(self, plant_names: Mapping[str, str],
               plc_getters: Mapping[str, Callable[[], Any]] | None = None
               ) -> Callable[[Mapping[str, Any], float], bool]:
        """A function ``f(values, t) -> bool``.

        ``plant_names`` maps a name of the condition to a key of ``values`` (the plant's
        signal values); ``plc_getters`` maps the other names to zero-argument getters.
        """
        getters = dict(plc_getters or {})
        env: dict[str, Any] = {"__builtins__": {}, "abs": abs, "min": min, "max": max}
        gnames: dict[str, str] = {}
        for i, (name, g) in enumerate(getters.items()):
            env[f"_g{i}"] = g
            gnames[name] = f"_g{i}"

        class T(ast.NodeTransformer):
            def visit_Name(self, node: ast.Name) -> ast.AST:
                return self._leaf(node)

            def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
                return self._leaf(node)

            def visit_Subscript(self, node: ast.Subscript) -> ast.AST:
                return self._leaf(node)

            def visit_Call(self, node: ast.Call) -> ast.AST:
                node.args = [self.visit(a) for a in node.args]
                return node

            def _leaf(self, node: ast.AST) -> ast.AST:
                p = _path(node)
                assert p is not None
                if p in TIME_NAMES:
                    return ast.Name("_t", ast.Load())
                if p in plant_names:
                    return ast.Subscript(ast.Name("_v", ast.Load()),
                                         ast.Constant(plant_names[p]), ast.Load())
                if p in gnames:
                    return ast.Call(ast.Name(gnames[p], ast.Load()), [], [])
                raise _err(self_text, f"unknown name {p!r}")

        self_text = self.text
        tree = ast.fix_missing_locations(T().visit(_copy(self.tree)))
        body = ast.Expression(ast.Lambda(
            ast.arguments(posonlyargs=[], args=[ast.arg("_v"), ast.arg("_t")], kwonlyargs=[],
                          kw_defaults=[], defaults=[]), tree.body))
        code = compile(ast.fix_missing_locations(body), "<condition>", "eval")
        fn = eval(code, env)  # noqa: S307 - the tree was checked node by node
        return lambda values, t: bool(fn(values, t))

    # ------------------------------------------------------------------ vector
    def vector(self, column: Callable[[str], Any], time: Any) -> Any:
        """Evaluate on whole columns: ``column(name)`` gives an array; returns a bool array."""
        import numpy as np

        env = {"__builtins__": {}, "_np": np, "_t": time}
        cols: dict[str, str] = {}

        def leaf(node: ast.AST) -> ast.AST:
            p = _path(node)
            assert p is not None
            if p in TIME_NAMES:
                return ast.Name("_t", ast.Load())
            if p not in cols:
                cols[p] = f"_c{len(cols)}"
                env[cols[p]] = column(p)
            return ast.Name(cols[p], ast.Load())

        def npcall(fn: str, args: list[ast.AST]) -> ast.AST:
            return ast.Call(ast.Attribute(ast.Name("_np", ast.Load()), fn, ast.Load()), args, [])

        def conv(node: ast.AST) -> ast.AST:
            if isinstance(node, ast.Name | ast.Attribute | ast.Subscript):
                return leaf(node)
            if isinstance(node, ast.Constant):
                return node
            if isinstance(node, ast.BoolOp):
                fn = "logical_and" if isinstance(node.op, ast.And) else "logical_or"
                acc = conv(node.values[0])
                for v in node.values[1:]:
                    acc = npcall(fn, [acc, conv(v)])
                return acc
            if isinstance(node, ast.UnaryOp):
                if isinstance(node.op, ast.Not):
                    return npcall("logical_not", [conv(node.operand)])
                return ast.UnaryOp(node.op, conv(node.operand))
            if isinstance(node, ast.BinOp):
                return ast.BinOp(conv(node.left), node.op, conv(node.right))
            if isinstance(node, ast.Compare):
                parts = []
                left = conv(node.left)
                for op, right in zip(node.ops, node.comparators, strict=True):
                    r = conv(right)
                    parts.append(ast.Compare(left, [op], [r]))
                    left = r
                acc = parts[0]
                for p in parts[1:]:
                    acc = npcall("logical_and", [acc, p])
                return acc
            if isinstance(node, ast.Call):
                assert isinstance(node.func, ast.Name)
                args = [conv(a) for a in node.args]
                if node.func.id == "abs":
                    return npcall("abs", args)
                fn = "minimum" if node.func.id == "min" else "maximum"
                acc = args[0]
                for a in args[1:]:
                    acc = npcall(fn, [acc, a])
                return acc
            raise _err(self.text, f"{type(node).__name__} is not allowed")  # pragma: no cover

        body = ast.Expression(conv(self.tree.body))
        code = compile(ast.fix_missing_locations(body), "<condition>", "eval")
        out = eval(code, env)  # noqa: S307 - the tree was checked node by node
        return np.broadcast_to(np.asarray(out, dtype=bool), np.shape(time)).copy()


def _copy(tree: ast.Expression) -> ast.Expression:
    return ast.parse(ast.unparse(tree), mode="eval")


def parse_condition(text: str) -> Condition:
    """Parse and check a condition (PlcError PLC4013 when it is not one)."""
    if not isinstance(text, str) or not text.strip():
        raise _err(str(text), "it is empty")
    src = _normalise(text.strip())
    try:
        tree = ast.parse(src.strip(), mode="eval")
    except SyntaxError as e:
        raise _err(text, f"syntax error ({e.msg})") from None
    names: set[str] = set()

    def check(node: ast.AST) -> None:
        if isinstance(node, ast.Name | ast.Attribute | ast.Subscript):
            p = _path(node)
            if p is None:
                raise _err(text, f"{ast.unparse(node)!r} is not a signal or variable name")
            if p not in TIME_NAMES:
                names.add(p)
            return
        if isinstance(node, ast.Constant):
            if type(node.value) not in (int, float, bool):
                raise _err(text, f"{node.value!r} is not a number")
            return
        if isinstance(node, ast.BoolOp):
            for v in node.values:
                check(v)
            return
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not | ast.USub | ast.UAdd):
            check(node.operand)
            return
        if isinstance(node, ast.BinOp) and isinstance(node.op, _BIN):
            check(node.left)
            check(node.right)
            return
        if isinstance(node, ast.Compare) and all(isinstance(o, _CMP) for o in node.ops):
            check(node.left)
            for c in node.comparators:
                check(c)
            return
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and \
                node.func.id in _FUNCS and not node.keywords and node.args:
            if node.func.id != "abs" and len(node.args) < 2:
                raise _err(text, f"{node.func.id}() needs two or more arguments")
            if node.func.id == "abs" and len(node.args) != 1:
                raise _err(text, "abs() takes one argument")
            for a in node.args:
                check(a)
            return
        what = ast.unparse(node) if not isinstance(node, ast.expr_context) else "?"
        raise _err(text, f"{what!r} is not allowed (only names, numbers, arithmetic, "
                   "comparisons, and/or/not, abs/min/max)")

    check(tree.body)
    return Condition(text, tree, names)


def is_simple_name(text: str) -> bool:
    """True for a bare identifier (``LEVEL``)."""
    return re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", text) is not None
