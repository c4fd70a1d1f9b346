"""Parse IEC literals given as text (``--set X=T#5s``, ``plc["X"] = "16#FF"``)."""

from __future__ import annotations

from typing import Any

from ..errors import PlcError
from ..lang import types as T


def parse_literal(text: str, ty: T.Type, path: str = "") -> Any:
    """Parse ``text`` as a literal of type ``ty`` using the ST lexer and checker rules.

    >>> from plclab.lang import types as T
    >>> parse_literal("T#1s500ms", T.TIME), parse_literal("16#FF", T.BYTE)
    (1500, 255)
    """
    from ..lang.lexer import Lexer

    t = T.resolve(ty)
    s = text.strip()
    if isinstance(t, T.EnumType):
        name = s.split("#")[-1].upper()
        if name in t.members:
            return t.members[name]
        raise PlcError("PLC3002", f"{path}: {s} is not a value of {t.name} ("
                       + ", ".join(t.members) + ")")
    if t.kind == "time" and not s.upper().startswith(("T#", "TIME#", "LT#", "LTIME#")) and \
            s[:1].isdigit() and not s.replace(".", "").isdigit():
        s = "T#" + s
    lx = Lexer(s, "<value>")
    toks = lx.tokens()
    neg = False
    if toks and toks[0].kind == "-":
        neg = True
        toks = toks[1:]
    if lx.diagnostics or len(toks) != 2:
        raise PlcError("PLC3002", f"{path}: '{text}' is not a literal of type {t}")
    tok = toks[0]
    v = tok.value
    if tok.kind in ("TRUE", "FALSE"):
        v = tok.kind == "TRUE"
    if neg and isinstance(v, int | float):
        v = -v
    if t is T.BOOL:
        if isinstance(v, bool) or v in (0, 1):
            return bool(v)
    elif t.kind in ("int", "bits") and tok.kind == "INT":
        if T.fits(v, t):
            return v
        raise PlcError("PLC3002", f"{path}: {v} does not fit {t}")
    elif t.kind == "real" and tok.kind in ("INT", "REAL"):
        from ..compile.real32 import f32 as _f32

        return _f32(float(v)) if t is T.REAL else float(v)
    elif t.kind == "time" and tok.kind == "TIME":
        return v if t is T.LTIME else int(v / 1_000_000)
    elif isinstance(t, T.StringType) and tok.kind in ("STRING", "WSTRING"):
        return v
    elif t.kind in ("date", "tod", "dt") and tok.kind in ("DATE", "TOD", "DT"):
        return v
    raise PlcError("PLC3002", f"{path}: '{text}' is not a literal of type {t}")
