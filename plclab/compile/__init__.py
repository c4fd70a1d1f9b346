"""The compiler: a checked AST becomes Python source, compiled once to code objects.

The middle layer of the PLC core (``docs/adr/0013-layers-and-lazy-cli.md``): it imports
:mod:`plclab.lang` and the standard library, never the runtime. :func:`generate` (in
:mod:`~plclab.compile.codegen`) turns a checked :class:`~plclab.lang.check.Project` into a
:class:`Compiled` that :class:`plclab.runtime.plc.Plc` runs; :func:`~plclab.compile.real32.f32`
is the REAL rounding both the compiler and the generated code use.

Importing this package is cheap: the code generator is imported on first use of its names.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Compiled", "f32", "generate"]


def __getattr__(name: str) -> Any:
    if name in ("Compiled", "generate"):
        from . import codegen

        return getattr(codegen, name)
    if name == "f32":
        from .real32 import f32

        return f32
    raise AttributeError(f"module 'plclab.compile' has no attribute {name!r}")
