"""Building blocks of plclab's PLCopen XML writer (:mod:`plclab.lang.plcopen_export`): the
namespace, elements, connections, generated names made legal, and the pins of a function
drawn as a block."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from . import ast as A

NS = "http://www.plcopen.org/xml/tc6_0201"
XHTML = "http://www.w3.org/1999/xhtml"
HIDDEN_PREFIX = "__"  # plclab's generated names; IEC forbids a double underscore


def sub(parent: ET.Element, tag: str, **attrs: str) -> ET.Element:
    """A child element in the PLCopen namespace."""
    return ET.SubElement(parent, f"{{{NS}}}{tag}", attrs)


def visible(name: str) -> str:
    """A generated name (``__LD_T1``) made a legal IEC identifier (``LD_T1_h``)."""
    return name.lstrip("_") + "_h" if name.startswith(HIDDEN_PREFIX) else name


def connect(cpi: ET.Element, ref: str, pin: str | None) -> None:
    sub(cpi, "connection", refLocalId=ref, **({"formalParameter": pin} if pin else {}))


def hide(text: str) -> str:
    """Generated names made legal identifiers in a body text."""
    return re.sub(r"\b__([A-Za-z0-9_]+)", lambda m: m.group(1) + "_h", text)


def text_body(holder: ET.Element, text: str) -> None:
    p = ET.SubElement(holder, f"{{{XHTML}}}p")
    p.text = text



def call_pins(e: A.Call, user_inputs: dict[str, list[str]]) -> list[str] | None:
    """The pin of each argument of a function call drawn as a block, or None when they are
    not known (positional arguments of an unknown function). ``user_inputs``: the input names
    of the project's own functions."""
    from .builtins import BUILTINS, conversion

    names = [a.name for a in e.args]
    if all(names):
        return [n.upper() for n in names if n]
    fname = e.func.name if isinstance(e.func, A.Name) else ""
    if fname in user_inputs:
        params = [n.upper() for n in user_inputs[fname]]
    elif fname in BUILTINS:
        b = BUILTINS[fname]
        params = list(b.params)
        if b.variadic:  # numbered on from the last INn: ADD IN3, IN4...; MUX K, IN0, IN1, IN2...
            last = max((int(p[2:]) for p in params if p[:2] == "IN" and p[2:].isdigit()),
                       default=0)
            params += [f"IN{last + 1 + k}" for k in range(len(e.args) - len(params))]
    elif conversion(fname) is not None:
        params = ["IN"]
    else:
        return None
    if len(params) < len(e.args):
        return None
    return [a.name.upper() if a.name else params[i] for i, a in enumerate(e.args)]
