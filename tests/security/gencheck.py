"""The design rule on generated code, checked on its syntax tree and tokens.

"User text reaches generated code only as mangled identifiers or ``repr()`` literals"
(DESIGN.md, principle 2). So in the generated Python source:

* there is no ``import`` statement, and nothing calls ``__import__``, ``eval``, ``exec``,
  ``open``, ``getattr``, ``compile`` or ``globals``;
* every name is either one of the fixed names the code generator itself uses (runtime helpers,
  a few builtins, its own temporaries) or a mangled user identifier: upper case
  ``[A-Z0-9_]`` with a generated prefix (``F_``, ``P_``, ``S_``, ``E_``, ``v_``), or an upper-case
  attribute of an object (``self.X``, ``_G.X``);
* a mangled identifier never starts with ``__`` without ending with it: Python would mangle it
  as a private name inside a class and the program would read another attribute;
* outside string literals, the text never holds a lower-case payload word.
"""

from __future__ import annotations

import ast
import io
import keyword
import re
import tokenize

from plclab.runtime.rt import HELPERS

METHOD_NAME = re.compile(r"^m_[A-Z0-9_]+$")  # a METHOD of a block (ADR 0021, 0039)
MANGLED = re.compile(r"^(?:[FPSE]|v|m)_[A-Z0-9_]+$")  # m_: methods (ADR 0021, 0039)
UPPER = re.compile(r"^[A-Z0-9_]+$")
TEMPS = re.compile(r"^_(?:r|c|f|t|test_)\d+$")
RUNTIME_NAMES = {"_B", "_CTX", "_F32", "_G", "_I", "_M", "_P", "_Q", "_fb", "_pc", "n", "self",
                 "__slots__", "_Globals", "_Programs", "_sync_in", "_sync_out", "__init__",
                 "_body", "_copy", "_math",
                 "_itf", "_INIT_RETAINS",  # ADR 0021: a block's interfaces, FB_init's flag
                 "_fbinit",  # ADR 0052: the values a : FB(k := 3) gives FB_init
                 "_sync_init",  # ADR 0056: located variables written to the image at restart
                 "_LOC"}  # ADR 0056: each located variable's value at the last image copy
BUILTINS = {"abs", "float", "int", "len", "list", "max", "min", "range", "bool", "str", "round"}
METHODS = {"__new__", "_body", "_copy", "advance_ns", "from_bytes", "to_bytes", "left", "start",
           "step", "now", "now_ns", "first_scan", "scan_count", "limit",
           "get", "set",  # get/set: a reference's target (ADR 0021)
           "data", "dims"}  # an ARRAY[*] argument's elements and bounds (ADR 0060)
FORBIDDEN_CALLS = {"__import__", "eval", "exec", "open", "getattr", "setattr", "compile",
                   "globals", "locals", "vars", "breakpoint", "input", "delattr"}


# hidden variables of the IL, LD, SFC and edge lowerings (``__CR_INT``, ``__LD_M3``, ``__SFC_TR0``,
# ``__EDGE_MEM__X``):
# private names, which work only because nothing outside their class reads them
HIDDEN = re.compile(r"^__(?:CR|LD|SFC|EDGE)_[A-Z0-9_]+$")


def _private(name: str) -> bool:
    return name.startswith("__") and not name.endswith("__") and not HIDDEN.match(name)


def problems(source: str, words: tuple[str, ...] = ("pwned_sentinel",)) -> list[str]:
    """Every way ``source`` breaks the rule (empty when it keeps it)."""
    out: list[str] = []
    allowed = RUNTIME_NAMES | BUILTINS | set(HELPERS)

    def name_ok(n: str) -> bool:
        return (n in allowed or bool(TEMPS.match(n))
                or bool(MANGLED.match(n)))

    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            out.append(f"line {node.lineno}: an import statement")
        elif isinstance(node, ast.Name):
            if not name_ok(node.id):
                out.append(f"line {node.lineno}: name {node.id!r} is not generated or mangled")
            if node.id in FORBIDDEN_CALLS:
                out.append(f"line {node.lineno}: uses {node.id}")
        elif isinstance(node, ast.Attribute):
            a = node.attr
            if _private(a):
                out.append(f"line {node.lineno}: attribute {a!r} is a private name")
            elif not (UPPER.match(a) or a in METHODS or a in RUNTIME_NAMES
                      or METHOD_NAME.match(a)):
                out.append(f"line {node.lineno}: attribute {a!r} is not mangled")
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            if not name_ok(node.name):
                out.append(f"line {node.lineno}: definition {node.name!r}")
        elif isinstance(node, ast.arg):
            if not name_ok(node.arg):
                out.append(f"line {node.lineno}: parameter {node.arg!r}")
    code = [t.string for t in tokenize.generate_tokens(io.StringIO(source).readline)
            if t.type not in (tokenize.STRING, tokenize.COMMENT)]
    text = " ".join(code)
    for w in words:
        if w in text:
            out.append(f"{w!r} appears outside a string literal")
    for i, t in enumerate(code):
        if t == "global" and code[i + 1:i + 2] == ["_G"]:
            continue  # _Globals.__init__ publishes the instance so initial values can read it
        if keyword.iskeyword(t) and t in ("import", "lambda", "global", "nonlocal", "async",
                                          "await", "yield", "del"):
            out.append(f"keyword {t!r} in generated code")
    return out
