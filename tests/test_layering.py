"""The layers of plclab hold: no import cycles, no upward imports, a pure-Python core.

The import graph is read from the source with :mod:`ast` (nothing is imported): every ``import``
and ``from ... import`` of every module, at module level and inside functions, absolute and
relative. ``from pkg import name`` counts as an import of ``pkg.name`` when that is a module,
else of ``pkg``. The layers and the reason for each are in ``docs/adr/0013-layers-and-lazy-cli.md``.

``python tests/test_layering.py`` prints the graph between layers.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "plclab"

# (layer, module prefixes). Lowest first: a module may import its own layer and the layers
# above it in this list, never one below. Layers in one row share a rank and may not import
# each other. The most specific prefix wins; the root package ``plclab`` matches only itself.
LAYERS: list[list[tuple[str, tuple[str, ...]]]] = [
    # errors, the problem catalogue, name lists, the command table: standard library only.
    # plclab.i18n*: the language of messages (ADR 0063), read by errors' render().
    [("base", ("plclab.errors", "plclab.problems", "plclab.names", "plclab.cli_registry",
               "plclab.durations", "plclab.suggest", "plclab.i18n", "plclab.i18n_labs",
               "plclab.i18n_check"))],
    # signal conversions (4-20 mA, counts, Pt100): pure math on floats, used by the runtime's
    # analog scaling blocks and by the simulator's I/O channels.
    [("io", ("plclab.io",))],
    # the PLC core, bottom to top: language -> compiler -> runtime.
    [("lang", ("plclab.lang",))],
    [("compile", ("plclab.compile",))],
    [("runtime", ("plclab.runtime",))],
    # the core's front door: read, check, compile, load; run TEST blocks.
    [("api", ("plclab", "plclab.project", "plclab.testing"))],
    # the record of a run (NumPy is imported lazily, when a trace is built).
    [("trace", ("plclab.trace",))],
    # process data around a run (watch tables, alarms, archives, recipes): read the runtime,
    # write Trace events; the simulator, the grader and the panel use them (ADR 0061).
    [("process", ("plclab.process",))],
    # a PLC joined to a plant on one clock; writes a Trace.
    [("sim", ("plclab.sim",))],
    # readers of a Trace (viz) and the PLC behind a Modbus server: independent of each other.
    [("viz", ("plclab.viz",)), ("modbus", ("plclab.modbus",))],
    # the operator panel: a Simulation run in real time behind a small HTTP server, showing the
    # process data of the layer `process`.
    [("scada", ("plclab.scada",))],
    # the PLC behind an OPC UA server (asyncua, lazily): the panel's runner, scada's alarms.
    [("opcua", ("plclab.opcua",))],
    # labs and the autograder: run simulations, draw the diagrams of failures.
    [("grade", ("plclab.grade",))],
    # the course: chapters, their examples, figures from real runs and quizzes.
    [("course", ("plclab.course",))],
    # the language server: the core's front ends and checker for editors (pygls only in
    # plclab.lsp.server, imported by `plclab lsp`; docs/adr/0054-language-server.md); below
    # the site, whose playground editor calls its feature functions (docs/adr/0064).
    [("lsp", ("plclab.lsp",))],
    # the web site: pages from the course, labs, catalogue and plants; the playground's Python
    # side (plclab.site.playground_api, lab_check, editor_api) needs only the core, the
    # plants, the language server's feature functions and the highlighting lexers.
    [("site", ("plclab.site",))],
    # the command line: every `commands` module is a CLI front end of its package.
    [("cli", ("plclab.cli", "plclab.__main__", "plclab.sim.commands", "plclab.viz.commands",
              "plclab.grade.commands", "plclab.modbus.commands", "plclab.compile.commands",
              "plclab.viz.diagram_commands",
              "plclab.course.commands", "plclab.scada.commands",
              "plclab.site.commands", "plclab.lsp.commands", "plclab.opcua.commands"))],
]

# Layers that must import nothing outside the standard library and plclab (the PLC runs
# anywhere, even under Pyodide): the core and everything the core imports.
PURE_LAYERS = {"base", "io", "lang", "compile", "runtime"}

# Cycles that exist on purpose, for now. Each entry is the exact set of modules of one cycle
# (a strongly connected component); an entry that no longer matches the code fails the test,
# so remove it when the cycle is gone.
KNOWN_CYCLES: list[frozenset[str]] = [
    # none: add a cycle here only with the issue that removes it
]

# Cycles that exist only through imports under ``if TYPE_CHECKING:`` (never run, so they cannot
# leave a module half-initialised, but they still tie modules together). Same rules as above.
_CHECK = "plclab.lang.check."
KNOWN_TYPING_CYCLES: list[frozenset[str]] = [
    # The checker's context holds one object per pass and names their classes for the type
    # checker, while every pass names the context (Pass.cx) and asks the other passes through
    # it (self.cx.exprs.expr(...)): the passes call each other recursively by design. At run
    # time the passes import only pass_api and symbols (ADR 0061).
    frozenset(_CHECK + m for m in ("calls", "consts", "context", "declarations", "exprs", "oop",
                                    "pass_api", "program", "stmts")),
]


# ------------------------------------------------------------------------------ the graph


def module_files(root: Path = PACKAGE) -> dict[str, Path]:
    """Dotted module name -> file, for every .py file under *root* (a package is its __init__)."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def imported_names(module: str, path: Path, modules: dict[str, Path],
                   typing_too: bool = False) -> dict[str, int]:
    """Every module *module* imports (plclab's and others') -> the first line that does; with
    *typing_too*, also the imports under ``if TYPE_CHECKING:``."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: dict[str, int] = {}
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    # imports under `if TYPE_CHECKING:` are read by type checkers only, never run
    typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                   and ast.unparse(block.test).endswith("TYPE_CHECKING")
                   for stmt in block.body for n in ast.walk(stmt)}
    for node in ast.walk(tree):
        if id(node) in typing_only and not typing_too:
            continue
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                base_name = ".".join(base + ([node.module] if node.module else []))
            else:
                base_name = node.module or ""
            for a in node.names:
                sub = f"{base_name}.{a.name}"
                names.append(sub if sub in modules else base_name)
        for name in names:
            found.setdefault(name, node.lineno)
    return found


def owning_module(name: str, modules: dict[str, Path]) -> str | None:
    """The plclab module an imported dotted name belongs to (``plclab.x.y`` -> ``plclab.x``)."""
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


def import_graph(root: Path = PACKAGE, typing_too: bool = False
                 ) -> tuple[dict[str, dict[str, int]], dict[str, dict[str, int]]]:
    """(module -> modules of the package at *root* it imports -> line, module -> outside imports
    -> line), every module of the package included, edges inside one sub-package too."""
    modules = module_files(root)
    top = root.name
    inside: dict[str, dict[str, int]] = {m: {} for m in modules}
    outside: dict[str, dict[str, int]] = {m: {} for m in modules}
    for m, path in modules.items():
        for name, line in imported_names(m, path, modules, typing_too).items():
            if name == top or name.startswith(top + "."):
                target = owning_module(name, modules)
                if target and target != m:
                    inside[m].setdefault(target, line)
            else:
                outside[m].setdefault(name, line)
    return inside, outside


def strongly_connected(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """The cycles of *graph*: its strongly connected components of two or more modules."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:  # Tarjan's algorithm; the graph is a few hundred nodes deep
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def cycle_path(graph: dict[str, dict[str, int]], members: list[str]) -> list[str]:
    """One closed path through a component, for the failure message: a -> b -> ... -> a."""
    start, inside = members[0], set(members)
    paths = {start: [start]}
    todo = [start]
    while todo:  # breadth first: the shortest way back to start
        v = todo.pop(0)
        for w in graph[v]:
            if w == start:
                return paths[v] + [start]
            if w in inside and w not in paths:
                paths[w] = paths[v] + [w]
                todo.append(w)
    return members


def layer_of(module: str) -> tuple[str, int]:
    """(layer name, rank) of a plclab module: the most specific prefix of :data:`LAYERS`."""
    best: tuple[int, str, int] | None = None
    for rank, row in enumerate(LAYERS):
        for name, prefixes in row:
            for p in prefixes:
                hit = module == p or (p != "plclab" and module.startswith(p + "."))
                if hit and (best is None or len(p) > best[0]):
                    best = (len(p), name, rank)
    if best is None:
        raise LookupError(f"{module} is in no layer: add it to LAYERS in tests/test_layering.py "
                          "and docs/adr/0013-layers-and-lazy-cli.md")
    return best[1], best[2]


def is_stdlib(name: str) -> bool:
    return name.partition(".")[0] in sys.stdlib_module_names


# ------------------------------------------------------------------------------ the tests


def test_the_graph_is_read_from_every_module() -> None:
    inside, _ = import_graph()
    assert "plclab.lang.ast" in inside["plclab.lang.check.exprs"]  # relative, module level
    assert "plclab.runtime.plc" in inside["plclab.project"]        # relative, inside a function
    assert "plclab.lang.types" in inside["plclab.modbus.server"]   # absolute
    assert "plclab.compile.real32" in inside["plclab.runtime.rt_arith"]  # from .. import as


def test_every_module_is_in_a_layer() -> None:
    for module in module_files():
        layer_of(module)


def test_no_import_cycles() -> None:
    inside, _ = import_graph()
    found = [c for c in strongly_connected(inside) if frozenset(c) not in KNOWN_CYCLES]
    assert not found, "import cycles:\n" + "\n".join(
        " -> ".join(cycle_path(inside, c)) for c in found)


def test_known_cycles_are_not_stale() -> None:
    inside, _ = import_graph()
    actual = {frozenset(c) for c in strongly_connected(inside)}
    stale = [sorted(c) for c in KNOWN_CYCLES if c not in actual]
    assert not stale, (f"KNOWN_CYCLES lists cycles that no longer exist as listed: {stale}; "
                       "update or remove the entry (the current cycles: "
                       f"{[sorted(c) for c in actual]})")


def upward_imports(inside: dict[str, dict[str, int]]) -> list[str]:
    """The imports of *inside* that go to a higher layer or sideways, as sentences."""
    bad = []
    for m, targets in sorted(inside.items()):
        lm, rm = layer_of(m)
        for t, line in sorted(targets.items()):
            lt, rt = layer_of(t)
            if lm == lt or rt < rm:
                continue
            if any(m in c and t in c for c in KNOWN_CYCLES):
                continue  # reported by KNOWN_CYCLES
            bad.append(f"{m} (layer {lm}) imports {t} (layer {lt}) at line {line}")
    return bad


def test_no_upward_imports() -> None:
    inside, _ = import_graph()
    bad = upward_imports(inside)
    assert not bad, "imports that go up or sideways:\n" + "\n".join(bad)


def test_no_cycles_even_through_imports_for_type_checkers() -> None:
    inside, _ = import_graph(typing_too=True)
    actual = {frozenset(c) for c in strongly_connected(inside)}
    found = actual - set(KNOWN_CYCLES) - set(KNOWN_TYPING_CYCLES)
    assert not found, "import cycles (counting `if TYPE_CHECKING:` imports):\n" + "\n".join(
        " -> ".join(cycle_path(inside, sorted(c))) for c in found)
    stale = [sorted(c) for c in KNOWN_TYPING_CYCLES if c not in actual]
    assert not stale, f"KNOWN_TYPING_CYCLES lists cycles that no longer exist: {stale}"


def test_the_core_needs_only_the_standard_library() -> None:
    _, outside = import_graph()
    bad = [f"{m} imports {name} at line {line}"
           for m, names in sorted(outside.items()) if layer_of(m)[0] in PURE_LAYERS
           for name, line in sorted(names.items()) if not is_stdlib(name)]
    assert not bad, "the core imports outside the standard library:\n" + "\n".join(bad)


def test_the_core_never_imports_the_outer_layers() -> None:
    # The promise of DESIGN.md in the words of issue 12, checked on its own so that a change of
    # LAYERS cannot quietly drop it.
    inside, _ = import_graph()
    outer = ("sim", "grade", "viz", "cli", "modbus", "trace")
    bad = [f"{m} imports {t}" for m, targets in inside.items()
           if layer_of(m)[0] in ("lang", "compile", "runtime")
           for t in targets if layer_of(t)[0] in outer]
    assert not bad, "\n".join(bad)


def test_every_package_declares_its_layer_and_api() -> None:
    import importlib

    folders = sorted({p.parent for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts})
    for folder in folders:
        init = folder / "__init__.py"
        assert init.is_file(), f"{folder} has no __init__.py"
        tree = ast.parse(init.read_text(encoding="utf-8"))
        doc = ast.get_docstring(tree)
        assert doc and len(doc.split()) >= 10, f"{init}: say in a docstring what the layer is"
        name = ".".join(folder.relative_to(PACKAGE.parent).parts)
        module = importlib.import_module(name)
        assert isinstance(getattr(module, "__all__", None), list), f"{name} has no __all__"
        for attr in module.__all__:  # each declared name exists (lazy ones are imported now)
            assert getattr(module, attr, None) is not None or importlib.import_module(
                f"{name}.{attr}"), f"{name}.__all__ names {attr}, which does not exist"


def test_a_cycle_and_an_upward_import_are_caught() -> None:
    graph = {"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}, "d": {"a": 1}}
    assert strongly_connected(graph) == [["a", "b", "c"]]
    assert cycle_path(graph, ["a", "b", "c"]) == ["a", "b", "c", "a"]
    assert layer_of("plclab.lang.check")[1] < layer_of("plclab.sim.simulation")[1]
    assert layer_of("plclab.sim.commands")[0] == "cli"
    assert layer_of("plclab")[0] == "api" and layer_of("plclab.errors")[0] == "base"


def _package(root: Path, files: dict[str, str]) -> Path:
    """A throw-away package ``plclab`` under *root* with the given modules (path -> source)."""
    pkg = root / "plclab"
    for rel, text in files.items():
        path = pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return pkg


def test_a_planted_circle_inside_one_package_is_found(tmp_path: Path) -> None:
    # Two modules of one sub-package import each other: one at module level and relatively,
    # the other inside a function and absolutely; a third only under TYPE_CHECKING.
    pkg = _package(tmp_path, {
        "__init__.py": "",
        "lang/__init__.py": "",
        "lang/a.py": "from .b import f\n",
        "lang/b.py": "def f():\n    from plclab.lang import a\n    return a\n",
        "lang/c.py": ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                      "    from .d import D\n"),
        "lang/d.py": "from . import c\n",
        "lang/e.py": "from . import a\n",  # imports the cycle, is not part of it
    })
    inside, _ = import_graph(pkg)
    assert strongly_connected(inside) == [["plclab.lang.a", "plclab.lang.b"]]
    assert cycle_path(inside, ["plclab.lang.a", "plclab.lang.b"]) == [
        "plclab.lang.a", "plclab.lang.b", "plclab.lang.a"]
    typed, _ = import_graph(pkg, typing_too=True)
    assert strongly_connected(typed) == [["plclab.lang.a", "plclab.lang.b"],
                                         ["plclab.lang.c", "plclab.lang.d"]]
    # a -> b, b -> a, d -> c, e -> a; lines 1 + 3 + 3 + 1 + 1 (the two __init__ are empty)
    assert tree_summary(pkg) == [
        "modules 7, imports between them 4, lines 9",
        "longest: plclab.lang.b (3), plclab.lang.c (3), plclab.lang.a (1); over 600 lines: 0",
        "cycles: 1, through typing-only imports too: 2"]


def test_a_planted_upward_import_is_found(tmp_path: Path) -> None:
    pkg = _package(tmp_path, {
        "__init__.py": "",
        "runtime/__init__.py": "",
        "runtime/plc.py": "import json\nfrom ..sim import simulation\nfrom ..lang import ast\n",
        "sim/__init__.py": "",
        "sim/simulation.py": "from plclab.runtime.plc import Plc\n",
        "lang/__init__.py": "",
        "lang/ast.py": "",
    })
    inside, outside = import_graph(pkg)
    assert upward_imports(inside) == [
        "plclab.runtime.plc (layer runtime) imports plclab.sim.simulation (layer sim) at line 2"]
    assert outside["plclab.runtime.plc"] == {"json": 1}
    assert upward_imports({"plclab.viz.x": {"plclab.modbus.y": 3}}) == [
        "plclab.viz.x (layer viz) imports plclab.modbus.y (layer modbus) at line 3"]  # sideways


def layer_graph() -> dict[str, dict[str, int]]:
    """Layer -> layers it imports -> how many module imports."""
    inside, _ = import_graph()
    out: dict[str, dict[str, int]] = {}
    for m, targets in inside.items():
        lm = layer_of(m)[0]
        for t in targets:
            lt = layer_of(t)[0]
            if lt != lm:
                out.setdefault(lm, {}).setdefault(lt, 0)
                out[lm][lt] += 1
    return out


def tree_summary(root: Path = PACKAGE) -> list[str]:
    """The import tree in a few numbers (for the closing note of a restructuring): modules and
    imports between them, the longest modules, the cycles (also through typing-only imports)."""
    inside, _ = import_graph(root)
    typed, _ = import_graph(root, typing_too=True)
    lines = {m: len(p.read_text(encoding="utf-8").splitlines()) for m, p in
             module_files(root).items()}
    longest = sorted(lines.items(), key=lambda kv: (-kv[1], kv[0]))[:3]
    return [f"modules {len(lines)}, imports between them {sum(map(len, inside.values()))}, "
            f"lines {sum(lines.values())}",
            "longest: " + ", ".join(f"{m} ({n})" for m, n in longest)
            + f"; over 600 lines: {sum(n > 600 for n in lines.values())}",
            f"cycles: {len(strongly_connected(inside))}, through typing-only imports too: "
            f"{len(strongly_connected(typed))}"]


if __name__ == "__main__":
    order = [name for row in LAYERS for name, _ in row]
    for lm in order:
        deps = layer_graph().get(lm, {})
        print(f"{lm:8} -> " + ", ".join(f"{lt} ({n})" for lt, n in
                                        sorted(deps.items(), key=lambda kv: order.index(kv[0]))))
    inside, _ = import_graph()
    for c in strongly_connected(inside):
        print("cycle:", " -> ".join(cycle_path(inside, c)))
    for line in tree_summary():
        print(line)


def test_no_private_name_is_imported_from_another_module() -> None:
    """A name starting with one underscore is its module's own business: another module that
    needs it must get a public name (``from x import f as _f`` of a public ``f`` is fine)."""
    found = []
    for module, path in module_files().items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith(
                    "plclab")):
                found += [f"{module}:{node.lineno} imports {a.name}" for a in node.names
                          if a.name.startswith("_") and not a.name.startswith("__")]
    assert not found, "\n".join(found)
