"""The checker in passes, behind a symbol table (see :mod:`.checker` for the order).

``from plclab.lang.check import Checker, check, Project`` is the entry point; the compiler
also reads the symbols the passes attach to the AST (:class:`VarSym`, :class:`EnumSym`,
:class:`ProgSym`, :class:`CallInfo`), and the runtime, the simulator and the Modbus server ask
``project.symbols`` (a :class:`SymbolTable`) about variables.
"""

from .calls import CallInfo
from .checker import Checker, Project, check
from .declarations import MAX_IMAGE_BYTES
from .symbols import EnumSym, LocatedVar, ProgSym, Scope, SymbolTable, VarSym, instance_label

__all__ = [
    "MAX_IMAGE_BYTES",
    "CallInfo",
    "Checker",
    "EnumSym",
    "LocatedVar",
    "ProgSym",
    "Project",
    "Scope",
    "SymbolTable",
    "VarSym",
    "check",
    "instance_label",
]
