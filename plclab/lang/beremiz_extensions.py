"""Names that a Beremiz project's extensions declare, and plclab does not run.

A Beremiz project (``plc.xml`` with a ``beremiz.xml`` beside it) may use globals and types that
no IEC file declares: its extensions (the ``NAME@EXT`` folders: Python ``py_ext``, the SVG HMI
``svghmi``, MQTT, OPC UA, ...) add them when Beremiz builds the project. plclab reads the IEC
part only, so such a name is unknown; instead of "no matching VAR_GLOBAL" (PLC0100) or "unknown
type" (PLC0102) the student learns which extension declares it (PLC0246) and how to stand in
for it in a simulation.
"""

from __future__ import annotations

import os
import re
from dataclasses import replace

from ..errors import Diagnostic, PlcError
from .dialect import choose, origin


def _chosen(text: str, given: str | None, filename: str) -> str | None:
    try:
        return choose(text, given, filename)
    except PlcError:  # an unknown pragma is reported elsewhere (PLC0170)
        return None

EXTENSIONS = {
    "py_ext": "Python (py_ext)", "svghmi": "SVG HMI (svghmi)", "wxglade_hmi": "wxGlade HMI",
    "mqtt": "MQTT", "opcua": "OPC UA", "modbus": "Modbus", "canfestival": "CANopen",
    "bacnet": "BACnet", "c_ext": "C code (c_ext)", "wamp": "WAMP",
}
_EXTERNAL = re.compile(r"^VAR_EXTERNAL (\S+) has no matching VAR_GLOBAL")
_CHANNEL = re.compile(r"a Beremiz extension \(the one of IEC channel (\d+)\)")
_CHANNEL_ATTR = re.compile(r"""IEC_Channel\s*=\s*["'](\d+)["']""")
# Beremiz svghmi/pous.xml: HMI_INT is INT, HMI_REAL REAL, HMI_STRING STRING, HMI_BOOL BOOL, and
# HMI_NODE (a node of the HMI tree, its "alive" flag) BOOL
_HMI_BASE = {"NODE": "BOOL"}
_TYPE = re.compile(r"^unknown type (HMI_[A-Z0-9_]+)")


def extensions_of(filename: str) -> list[str]:
    """The extensions of the Beremiz project ``filename`` belongs to (its ``NAME@EXT``
    folders), as readable names."""
    folder = os.path.dirname(os.path.abspath(filename))
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    found = []
    for n in names:
        ext = n.rpartition("@")[2].lower() if "@" in n else ""
        if ext and os.path.isdir(os.path.join(folder, n)):
            label = EXTENSIONS.get(ext, ext)
            if label not in found:
                found.append(label)
    return found


def extension_of_channel(filename: str, channel: str) -> str | None:
    """The readable name of the extension (``NAME@EXT`` folder beside ``filename``) whose
    ``baseconfnode.xml`` gives it IEC channel ``channel``: the first number of the located
    addresses it serves (``%I3.0`` -> channel 3), or None."""
    folder = os.path.dirname(os.path.abspath(filename))
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return None
    for n in names:
        if "@" not in n:
            continue
        try:
            with open(os.path.join(folder, n, "baseconfnode.xml"), encoding="utf-8") as fh:
                m = _CHANNEL_ATTR.search(fh.read(4096))
        except OSError:
            continue
        if m and m.group(1) == channel:
            ext = n.rpartition("@")[2].lower()
            return f"{EXTENSIONS.get(ext, ext)} ({n})"
    return None


def explain(diags: list[Diagnostic], sources: list[tuple[str, str]],
            given: str | None) -> list[Diagnostic]:
    """``diags`` with PLC0100/PLC0102 of names a Beremiz extension declares turned into
    PLC0246 naming the extension, and PLC0340 naming the extension of its IEC channel: files Beremiz wrote (:func:`dialect.origin`) and read in
    the dialect they are in (``matiec``, whether chosen by their origin, a ``{dialect}``
    pragma or ``given``); a pragma or option naming another dialect turns it off."""
    beremiz = {f: extensions_of(f) for text, f in sources
               if origin(text, f) is not None and _chosen(text, given, f) == "matiec"}
    if not beremiz:
        return diags
    out = []
    for d in diags:
        exts = beremiz.get(d.location.file) if d.location is not None else None
        m_chan = _CHANNEL.search(d.message) if d.code == "PLC0340" and exts is not None \
            else None
        if m_chan:  # name the extension that serves the address (ADR 0059)
            who = extension_of_channel(d.location.file, m_chan.group(1))
            if who is not None:
                d = replace(d, message=d.message.replace(
                    m_chan.group(0), f"Beremiz's {who} extension (IEC channel "
                    f"{m_chan.group(1)})"))
            out.append(d)
            continue
        m_ext = _EXTERNAL.match(d.message) if d.code == "PLC0100" else None
        m_type = _TYPE.match(d.message) if d.code == "PLC0102" else None
        if exts is None or not (m_ext or m_type):
            out.append(d)
            continue
        if m_type:
            name = m_type.group(1)
            base = _HMI_BASE.get(name[4:], name[4:])
            msg = (f"{name} is a type of Beremiz's SVG HMI extension (svghmi), which plclab does "
                   f"not run; to simulate the program declare TYPE {name} : "
                   f"{base}; END_TYPE in a file of your own")
        else:
            name = m_ext.group(1)
            who = (f"the Beremiz project's extension {exts[0]}" if len(exts) == 1 else
                   f"one of the Beremiz project's extensions ({', '.join(exts)})" if exts else
                   "an extension of the Beremiz project (Python, SVG HMI, WAMP, MQTT...)")
            msg = (f"VAR_EXTERNAL {name} is declared by {who}, which plclab does not run; to "
                   f"simulate the program declare {name} in a VAR_GLOBAL of a file of your own")
        out.append(replace(d, code="PLC0246", message=msg))
    return out
