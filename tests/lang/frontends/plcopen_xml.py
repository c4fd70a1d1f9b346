"""Small builders of PLCopen XML projects for the FBD and LD import tests."""

from __future__ import annotations


def project(pous: str, instances: str = "") -> str:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
  <fileHeader companyName="t" productName="t" productVersion="1" creationDateTime="2026-01-01T00:00:00"/>
  <contentHeader name="t"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
  <types><dataTypes/><pous>
{pous}
  </pous></types>
  <instances><configurations>{instances}</configurations></instances>
</project>
"""


def var(name: str, ty: str = "BOOL") -> str:
    t = f"<{ty}/>" if not ty.startswith("<") else ty
    return f'<variable name="{name}"><type>{t}</type></variable>'


def program(body: str, variables: str, name: str = "P", lang: str = "FBD") -> str:
    return (f'<pou name="{name}" pouType="program"><interface><localVars>{variables}'
            f'</localVars></interface><body><{lang}>{body}</{lang}></body></pou>')


def pos(x: int, y: int) -> str:
    return f'<position x="{x}" y="{y}"/>'


def conn(ref: int | None, pin: str | None = None) -> str:
    if ref is None:
        return "<connectionPointIn/>"
    fp = f' formalParameter="{pin}"' if pin else ""
    return f'<connectionPointIn><connection refLocalId="{ref}"{fp}/></connectionPointIn>'


def invar(lid: int, expr: str, x: int = 0, y: int = 0, extra: str = "") -> str:
    return (f'<inVariable localId="{lid}"{extra}>{pos(x, y)}<connectionPointOut/>'
            f'<expression>{expr}</expression></inVariable>')


def outvar(lid: int, expr: str, src: int, pin: str | None = None, x: int = 300, y: int = 0,
           extra: str = "", tag: str = "outVariable", eo: int = 0) -> str:
    order = f' executionOrderId="{eo}"' if eo else ""
    out = "<connectionPointOut/>" if tag == "inOutVariable" else ""
    return (f'<{tag} localId="{lid}"{order}{extra}>{pos(x, y)}{conn(src, pin)}{out}'
            f'<expression>{expr}</expression></{tag}>')


def block(lid: int, type_name: str, ins: dict[str, tuple[int, str | None]],
          outs: list[str], x: int = 100, y: int = 0, instance: str = "",
          pin_attrs: dict[str, str] | None = None, eo: int = 0,
          inouts: dict[str, tuple[int, str | None]] | None = None) -> str:
    """A block; ``ins`` maps a pin to (source localId, source pin); ``pin_attrs`` adds
    attributes (``negated="true"``, ``edge="rising"``) to the named pins."""
    attrs = pin_attrs or {}
    inst = f' instanceName="{instance}"' if instance else ""
    order = f' executionOrderId="{eo}"' if eo else ""

    def pins(d):
        return "".join(f'<variable formalParameter="{p}"{attrs.get(p, "")}>{conn(*src)}</variable>'
                       for p, src in d.items())
    o = "".join(f'<variable formalParameter="{p}"{attrs.get(p, "")}><connectionPointOut/>'
                f'</variable>' for p in outs)
    return (f'<block localId="{lid}" typeName="{type_name}"{inst}{order}>{pos(x, y)}'
            f'<inputVariables>{pins(ins)}</inputVariables>'
            f'<inOutVariables>{pins(inouts or {})}</inOutVariables>'
            f'<outputVariables>{o}</outputVariables></block>')
