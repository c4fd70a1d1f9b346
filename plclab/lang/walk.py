"""Walking the AST: the children of every node class, a pre-order walk, and a visitor base.

Every node class of :mod:`plclab.lang.ast` has an entry in :data:`CHILDREN`; a class without one
(a new node nobody taught the walker) raises :class:`UnhandledNode`, an internal error, instead
of being skipped. :class:`NodeVisitor` dispatches ``visit_<Class>`` the same way: a pass that
dispatches on node classes cannot silently ignore a new one (``tests/lang/test_walk_coverage.py``
enumerates the classes and fails when one is missing).

>>> from plclab.errors import Location
>>> loc = Location("x.st", 1, 1)
>>> e = A.Binary(loc, "+", A.Name(loc, "A"), A.Literal(loc, 1, "INT"))
>>> [type(n).__name__ for n in walk(e)]
['Binary', 'Name', 'Literal']
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

from . import ast as A


class UnhandledNode(TypeError):
    """Internal error: a tree walker or a pass met a node class it has no case for."""

    def __init__(self, who: str, node: object) -> None:
        cls = type(node).__name__
        super().__init__(f"internal error: {who} has no case for the AST node class {cls}; "
                         f"add one (visit_{cls}) and run tests/lang/test_walk_coverage.py")


def flat(items: list[Any]) -> list[Any]:
    """Nodes of a list whose items may be None or tuples of nodes (CASE ranges, array
    repeats)."""
    out: list[Any] = []
    for x in items:
        if isinstance(x, tuple):
            out.extend(y for y in x if y is not None)
        elif x is not None:
            out.append(x)
    return out


def _body(*bodies: list[A.Stmt] | None) -> list[Any]:
    return [s for b in bodies if b for s in b]


CHILDREN: dict[type, Callable[[Any], list[Any]]] = {
    # type expressions
    A.NamedTypeRef: lambda n: [a.value for a in n.args or ()],
    A.StringTypeRef: lambda n: flat([n.length]),
    A.ArrayTypeRef: lambda n: flat(n.ranges) + [n.elem],
    A.SubrangeTypeRef: lambda n: [n.base, n.lo, n.hi],
    A.EnumTypeRef: lambda n: flat([v for _, v, _ in n.members] + [n.base]),
    A.StructTypeRef: lambda n: list(n.fields),
    A.RefTypeRef: lambda n: [n.target],
    # expressions
    A.Literal: lambda n: [],
    A.Name: lambda n: [],
    A.DirectAddr: lambda n: [],
    A.Member: lambda n: [n.obj],
    A.Index: lambda n: [n.obj, *n.indices],
    A.Unary: lambda n: [n.operand],
    A.Binary: lambda n: [n.left, n.right],
    A.Call: lambda n: [n.func, *n.args],
    A.Arg: lambda n: flat([n.value]),
    A.ArrayInit: lambda n: flat(n.items),
    A.StructInit: lambda n: [v for _, v, _ in n.fields],
    # statements
    A.Assign: lambda n: [n.target, n.value],
    A.CallStmt: lambda n: [n.call],
    A.If: lambda n: [x for c, b in n.branches for x in (c, *b)] + _body(n.orelse),
    A.CaseBranch: lambda n: flat(n.labels) + n.body,
    A.Case: lambda n: [n.selector, *n.branches] + _body(n.orelse),
    A.For: lambda n: flat([n.var, n.start, n.end, n.step]) + n.body,
    A.While: lambda n: [n.cond, *n.body],
    A.Repeat: lambda n: [*n.body, n.cond],
    A.Exit: lambda n: [],
    A.Continue: lambda n: [],
    A.Return: lambda n: [],
    A.Empty: lambda n: [],
    A.Label: lambda n: [],
    A.Jump: lambda n: flat([n.cond]),
    # declarations
    A.VarDecl: lambda n: [n.type] + flat([n.init]),
    A.Pou: lambda n: flat([*n.decls, n.return_type]) + n.body + list(n.methods) + list(
        n.access_paths),
    # a body the lowering has not translated yet: front-end data (IL instructions, network
    # elements), not AST nodes; the lowering empties Pou.pending before any pass walks a tree
    A.PendingBody: lambda n: [],
    A.TypeDecl: lambda n: [n.type] + flat([n.init]),
    A.GlobalVars: lambda n: list(n.decls),
    A.TaskDecl: lambda n: flat([n.interval, n.priority, n.single]),
    A.ProgramInstance: lambda n: flat([n.call]),
    A.ConfigVar: lambda n: [n.type] + flat([n.init]),
    A.AccessPath: lambda n: [n.type],
    A.Configuration: lambda n: [*n.globals, *(d for ds in n.resource_globals.values() for d in ds),
                                *n.tasks, *n.instances, *n.config_vars, *n.access_paths],
    A.TestBlock: lambda n: [*n.decls, *n.body],
    A.SourceFile: lambda n: [*n.types, *n.globals, *n.pous, *n.configs, *n.config_vars,
                             *n.tests],
}


def children(node: Any) -> list[Any]:
    """The nodes directly inside ``node``, in source order."""
    get = CHILDREN.get(type(node))
    if get is None:
        raise UnhandledNode("plclab.lang.walk.children", node)
    return get(node)


def walk(node: Any) -> Iterator[Any]:
    """``node`` and every node inside it, pre-order. An explicit stack, not recursion: trees
    may be nested thousands of levels deep."""
    stack = [node]
    pop, extend, get = stack.pop, stack.extend, CHILDREN.get  # the checker's inner loop
    while stack:
        n = pop()
        yield n
        kids = get(type(n))
        if kids is None:
            raise UnhandledNode("plclab.lang.walk.children", n)
        extend(reversed(kids(n)))


class NodeVisitor:
    """Dispatch on the node's class to ``visit_<Class>(node, *args)``; a class without a method
    raises :class:`UnhandledNode` (never skipped). Subclasses may add arguments (an expected
    type, a flag) that every ``visit_`` method of the class accepts."""

    _methods: dict[type, Callable[..., Any]] = {}

    def __init_subclass__(cls, **kw: Any) -> None:
        super().__init_subclass__(**kw)
        cls._methods = {}

    def visit(self, node: Any, *args: Any) -> Any:
        method = self._methods.get(type(node))
        if method is None:
            method = getattr(type(self), "visit_" + type(node).__name__, None)
            if method is None:
                raise UnhandledNode(type(self).__qualname__, node)
            self._methods[type(node)] = method
        return method(self, node, *args)

    @classmethod
    def handles(cls, node_class: type) -> bool:
        """True if the visitor has a ``visit_`` method for ``node_class``."""
        return callable(getattr(cls, "visit_" + node_class.__name__, None))
