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
        if not name.startswith("%"):  # an address's dot is not a program prefix
            out.setdefault(name.split(".", 1)[-1], v)
    return out


def pou_values(values: dict[str, Any], pou: Any) -> tuple[dict[str, Any], list[str]]:
    """The values of a trace as the POU ``pou`` names them, and the POU's variables the trace
    has no value for (each with its address).

    A variable recorded under the POU's name (``Main.PUMP``) is taken first; a variable
    located at an address (``PUMP AT %QX0.0``) then takes the address's value, which is what
    the PLC saw (a plant signal of the same name is the plant's side of the wiring); other
    names as they are."""
    from ..lang import ast as A
    from ..lang.types import ELEMENTARY

    tr = {str(k).upper(): v for k, v in values.items()}
    prefix = pou.name.upper() + "."
    out = dict(tr)
    out.update({k[len(prefix):]: v for k, v in tr.items() if k.startswith(prefix)})
    missing = []
    for d in pou.decls:
        n = d.name.upper()
        addr = (d.address or "").upper()
        if prefix + n in tr:
            continue
        if addr and addr in tr:
            out[n] = tr[addr]
        elif n not in tr and isinstance(d.type, A.NamedTypeRef) and d.type.name in ELEMENTARY:
            missing.append((d.spelling or d.name) + (f" (AT {d.address})" if addr else ""))
    return out, missing


def display_name(path: str) -> str:
    """A file's name as a title shows it: relative to the current folder when inside it,
    else the file's name alone (never a machine's absolute path)."""
    p = Path(path)
    if not p.is_absolute():
        return p.as_posix()
    try:
        return p.resolve().relative_to(Path.cwd().resolve()).as_posix()
    except (ValueError, OSError):
        return p.name


def render_file(path: str, pou: str | None = None, values: dict[str, Any] | None = None,
                source: str = "") -> str:
    """The SVG text of the POU ``pou`` (default: the first) of a source file; ``values``: a
    trace's values at one moment (from :func:`trace_values`), ``source`` how to name it."""
    from ..project import read_sources

    [(text, _)] = read_sources([path])
    return _render(text, display_name(path), pou, values, source)


def _render(text: str, name: str, pou: str | None, values, source: str = "") -> str:
    from .render_network import parse_source

    src = parse_source(text, name)
    chosen = [p for p in src.pous if pou is None or p.name == pou.upper()]
    if not chosen:
        names = ", ".join(p.spelling or p.name for p in src.pous) or "none"
        raise PlcError("PLC4040", f"{name} has no POU named {pou}; its POUs: {names}")
    p = chosen[0]
    if values is None:
        return _draw_pou(text, name, p, None)
    values, missing = pou_values(values, p)
    svg = _draw_pou(text, name, p, values)
    if not missing:
        return svg
    shown = ", ".join(missing[:8]) + (f" and {len(missing) - 8} more" if len(missing) > 8
                                      else "")
    watch = ",".join(m.split(" ")[0] for m in missing[:8])
    return _with_note(svg, [f"No value in {source or 'the trace'} for {shown}:",
                            "the trace did not record them (located variables are shown by "
                            "their address's value when the trace has it);",
                            f"record them with plclab sim ... --watch {watch}"])


def _with_note(svg: str, lines: list[str]) -> str:
    """The SVG with ``lines`` written under the drawing (the picture grows to hold them)."""
    import re
    from xml.sax.saxutils import escape

    m = re.match(r"<svg[^>]*?width=['\"]([\d.]+)['\"] height=['\"]([\d.]+)['\"] "
                 r"viewBox=['\"]0 0 [\d.]+ [\d.]+['\"]", svg)
    if m is None:
        return svg
    w, h = float(m.group(1)), float(m.group(2))
    from .text_width import text_width

    w2 = max(w, max(text_width(t, 12) for t in lines) + 32)
    h2 = h + 18 * len(lines) + 12
    head = (f"<svg xmlns='http://www.w3.org/2000/svg' width='{w2:.0f}' height='{h2:.0f}' "
            f"viewBox='0 0 {w2:.0f} {h2:.0f}'")
    note = "".join(f"<text class='note' x='16' y='{h + 16 + 18 * k:.0f}' font-size='12' "
                   f"font-family='DejaVu Sans, Arial, sans-serif' fill='#b35900'>"
                   f"{escape(t)}</text>" for k, t in enumerate(lines))
    body = svg[m.end():]
    end = body.rstrip().rfind("</svg>")
    return (head + body[:end] + f"<rect y='{h:.0f}' width='100%' height='{h2 - h:.0f}' fill='white'/>" + note
            + body[end:])


def _draw_pou(text: str, name: str, p: Any, values) -> str:
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
    svg = render_file(ns.file, ns.pou, values,
                      f"{display_name(ns.at)} at t = {ns.time}" if ns.at else "")
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
