"""``plclab render`` (draw a program) and ``plclab export`` (write it as PLCopen XML).

``plclab render FILE [--pou NAME] [--svg|--png] [-o OUT] [--at TRACE --time T]`` draws the
POU's body: LD and FBD as networks (:mod:`plclab.viz.render_network`, the same drawing for the
text ladder format and PLCopen XML), SFC through :mod:`plclab.viz.render_sfc` when it is
installed, ST and IL as highlighted listings (:mod:`plclab.viz.render_listing`). With
``--at TRACE --time T`` the values of the trace at time T are shown (power flow in green).
SVG goes to standard output unless ``-o`` names a file; PNG needs ``-o``.

``plclab export FILE... --to plcopen [--fbd] [-o OUT]`` writes PLCopen XML
(:mod:`plclab.lang.plcopen_export`).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..cli_registry import arg, command
from ..errors import PlcError


def _write(data: str | bytes, out: str | None) -> None:
    if out is None:
        if isinstance(data, bytes):
            raise PlcError("PLC4044", "a PNG picture needs a file: add -o picture.png")
        sys.stdout.write(data)
        return
    try:
        Path(out).write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))
    except OSError as e:
        raise PlcError("PLC3014", f"cannot write {out}: {e.strerror or e}; check the folder "
                       "exists and is writable") from None


def trace_values(path: str, time: str | None) -> dict[str, Any]:
    """Variable name -> value of a saved trace at ``time`` (seconds or an IEC duration); each
    value is known by its full name and by its name without the program prefix."""
    from ..durations import parse_duration
    from ..trace import load

    if time is None:
        raise PlcError("PLC4045", "--at TRACE needs --time T (e.g. --time 2.5 or --time T#2s5ms)")
    ns = parse_duration(time)
    if ns is None:
        raise PlcError("PLC4045", f"--time {time}: write seconds (2.5) or a duration (T#2s500ms)")
    t = ns / 1e9
    tr = load(path)
    out: dict[str, Any] = {}
    for name in tr.names:
        v = tr.value_at(name, t)
        v = v.item() if hasattr(v, "item") else v  # numpy scalars -> bool, int, float
        out[name] = v
        out.setdefault(name.split(".", 1)[-1], v)
    return out


def render_file(path: str, pou: str | None = None, values: dict[str, Any] | None = None) -> str:
    """The SVG text of the POU ``pou`` (default: the first) of a source file."""
    from ..project import read_sources

    [(text, name)] = read_sources([path])
    return _render(text, name, pou, values)


def _render(text: str, name: str, pou: str | None, values) -> str:
    from .render_network import parse_source

    src = parse_source(text, name)
    chosen = [p for p in src.pous if pou is None or p.name == pou.upper()]
    if not chosen:
        names = ", ".join(p.spelling or p.name for p in src.pous) or "none"
        raise PlcError("PLC4040", f"{name} has no POU named {pou}; its POUs: {names}")
    p = chosen[0]
    if any(b.kind == "NETWORK" for b in p.pending):
        from .render_network import render_source

        return render_source(text, name, p.name, values)
    if any(b.kind == "SFC" for b in p.pending) or p.language == "SFC":
        from .render_sfc import render_sfc_svg

        return render_sfc_svg(p, values=values)
    from .render_listing import render_listing

    title = f"{name}: {p.kind} {p.spelling or p.name} ({p.language})"
    if name.lower().endswith(".xml"):  # the body's text, not the XML around it
        from ..lang.plcopen_export import xml_body_text

        body = xml_body_text(text, name, p.name, p.language if p.language == "IL" else "ST")
        return render_listing((body or "").strip("\n"), title, values)
    last = p.end_loc.line if p.end_loc is not None else None
    return render_listing(text, title, values, p.loc.line, last)


@command("render")
@arg("file", metavar="FILE", help="a source file (.st, .il, .ld, .xml)")
@arg("--pou", default=None, help="the POU to draw (default: the first)")
@arg("--svg", dest="fmt", action="store_const", const="svg", default="svg",
     help="write SVG (the default)")
@arg("--png", dest="fmt", action="store_const", const="png", help="write PNG (needs -o)")
@arg("-o", "--output", metavar="OUT", default=None, help="the picture file (default: stdout)")
@arg("--at", metavar="TRACE", default=None, help="a saved trace: show its values ...")
@arg("--time", metavar="T", default=None, help="... at this time (seconds or T#...)")
def render(ns: argparse.Namespace) -> int:
    """The ``render`` sub-command."""
    values = trace_values(ns.at, ns.time) if ns.at else None
    svg = render_file(ns.file, ns.pou, values)
    if ns.fmt == "png":
        if ns.output is None:
            raise PlcError("PLC4044", "a PNG picture needs a file: add -o picture.png")
        try:
            import cairosvg
        except (ImportError, OSError):  # OSError: cairosvg installed, the cairo library not
            raise PlcError("PLC4044", "PNG output needs the cairosvg package (pip install "
                           "cairosvg); or write SVG with --svg") from None
        _write(cairosvg.svg2png(bytestring=svg.encode("utf-8")), ns.output)
    else:
        _write(svg, ns.output)
    return 0


@command("export")
@arg("files", nargs="+", metavar="FILE", help="source files (.st, .il, .ld, .xml)")
@arg("--to", choices=("plcopen",), default="plcopen", help="the format (plcopen: TC6 XML)")
@arg("--fbd", action="store_true",
     help="draw bodies of assignments and block calls as FBD networks (else ST/IL text)")
@arg("-o", "--output", metavar="OUT", default=None, help="the XML file (default: stdout)")
def export(ns: argparse.Namespace) -> int:
    """The ``export`` sub-command."""
    from ..lang.plcopen_export import export_plcopen
    from ..project import check_sources, parse_sources, read_sources

    sources = read_sources(ns.files)
    project, diags = check_sources(sources)
    if project is None:
        errors = [d for d in diags if d.severity == "error"]
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    files, _ = parse_sources(sources)
    xml = export_plcopen(files[-len(sources):], fbd=ns.fbd, name=Path(ns.files[0]).stem,
                         sources={n: t for t, n in sources})
    _write(xml, ns.output)
    return 0
