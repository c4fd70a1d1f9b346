"""Ladder diagrams as SVG, from the text format (``.ld``) or from PLCopen XML (LD and FBD).

Pure Python string building (no plotting library), for notebooks and the web site:

>>> from plclab.viz.ladder_svg import render_ld
>>> svg = render_ld('''PROGRAM P VAR a, q : BOOL; END_VAR
... |   a       q   |
... |---[ ]-----( )-|
... END_PROGRAM''')
>>> svg.startswith("<svg") and ">a</text>" in svg
True

In a notebook the returned :class:`Svg` displays itself.
"""

from __future__ import annotations

import os
from xml.sax.saxutils import escape

CW = 11  # width of one character cell of the text format, px
RH = 24  # height of one line, px
PAD = 16
FONT = "font-family='DejaVu Sans Mono, Consolas, monospace'"
WIRE = "stroke='#222' stroke-width='1.6' fill='none'"
RAIL = "stroke='#222' stroke-width='4'"
BOX = "stroke='#1f4e8c' stroke-width='1.6' fill='#eef4fb'"


class Svg(str):
    """An SVG document (a ``str``) that Jupyter displays as a picture."""

    def _repr_svg_(self) -> str:
        return str(self)

    def save(self, path: str | os.PathLike) -> None:
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(self)


def _doc(width: float, height: float, parts: list[str], title: str = "") -> Svg:
    head = (f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:.0f}' height='{height:.0f}' "
            f"viewBox='0 0 {width:.0f} {height:.0f}'>")
    t = f"<title>{escape(title)}</title>" if title else ""
    return Svg(head + t + "<rect width='100%' height='100%' fill='white'/>" + "".join(parts) +
               "</svg>")


def _text(x: float, y: float, s: str, anchor: str = "start", extra: str = "") -> str:
    size = "" if "font-size" in extra else "font-size='12'"
    return (f"<text x='{x:.1f}' y='{y:.1f}' text-anchor='{anchor}' {FONT} {size} {extra}>"
            f"{escape(s)}</text>")


def _line(x1: float, y1: float, x2: float, y2: float, style: str = WIRE) -> str:
    return f"<line x1='{x1:.1f}' y1='{y1:.1f}' x2='{x2:.1f}' y2='{y2:.1f}' {style}/>"


# ---------------------------------------------------------------------------------------------
# Text format


def render_ld(text: str, file: str = "<input>.ld", pou: str | None = None) -> Svg:
    """Draw every ladder network of a ``.ld`` source (or only those of POU ``pou``)."""
    from ..lang.frontends.ld import parse as parse_ld

    src, _ = parse_ld(text, file)  # the drawn networks; no need to lower them
    parts: list[str] = []
    y = PAD
    width = 200.0
    for p in src.pous:
        nets = getattr(p, "networks", None)
        if not nets or (pou is not None and p.name != pou.upper()):
            continue
        parts.append(_text(PAD, y + 12, f"{p.kind} {p.spelling or p.name}",
                           extra="font-weight='bold'"))
        y += 24
        for net in nets:
            w, h = _network(net, PAD, y, parts)
            width = max(width, w + 2 * PAD)
            y += h + 12
    return _doc(width, y + PAD, parts, "ladder diagram")


def _network(net, x0: float, y0: float, parts: list[str]) -> tuple[float, float]:
    lines = net.grid or net.lines
    width = max(len(t) for t in lines) + 1
    grid = [t.ljust(width) for t in lines]
    rows = len(grid)
    left, right = net.left, net.right

    def cx(c: float) -> float:
        return x0 + c * CW

    def cy(r: int) -> float:
        return y0 + r * RH + RH / 2

    covered: set[tuple[int, int]] = set()
    for e in net.elems:
        line, c0, c1 = e.geom
        r = line - net.first_line
        for c in range(c0, c1 + 1):
            covered.add((r, c))
        parts.append(_element(e, cx(c0), cx(c1 + 1), cy(r)))
    for r in range(rows):
        t = grid[r]
        for c in range(left + 1, (right if right is not None else width)):
            if (r, c) in covered:
                continue
            ch = t[c]
            if net.wire[r] and ch in "-+":
                if ch == "-" or t[c - 1] not in " |" or t[c + 1:c + 2] not in (" ", ""):
                    x1 = cx(c) if (ch == "-" or t[c - 1] not in " |") else cx(c + 0.5)
                    x2 = cx(c + 1) if (ch == "-" or t[c + 1:c + 2] not in (" ", "")) \
                        else cx(c + 0.5)
                    if c == left + 1:
                        x1 = cx(left + 0.5)
                    if right is not None and c + 1 == right:
                        x2 = cx(right + 0.5)
                    parts.append(_line(x1, cy(r), x2, cy(r)))
                if ch == "+":
                    up = r > 0 and grid[r - 1][c] in "|+"
                    down = r + 1 < rows and grid[r + 1][c] in "|+"
                    if up:
                        parts.append(_line(cx(c + 0.5), cy(r) - RH / 2, cx(c + 0.5), cy(r)))
                    if down:
                        parts.append(_line(cx(c + 0.5), cy(r), cx(c + 0.5), cy(r) + RH / 2))
                    parts.append(f"<circle cx='{cx(c + 0.5):.1f}' cy='{cy(r):.1f}' r='2.5' "
                                 "fill='#222'/>")
            elif not net.wire[r] and ch == "|":
                parts.append(_line(cx(c + 0.5), cy(r) - RH / 2, cx(c + 0.5), cy(r) + RH / 2))
    for line, c0, _c1, word in net.names:
        r = line - net.first_line
        parts.append(_text(cx(c0), cy(r) + 8, word, extra="fill='#0b3d91'"))
    top, bottom = y0, y0 + rows * RH
    parts.append(_line(cx(left + 0.5), top, cx(left + 0.5), bottom, RAIL))
    if right is not None:
        parts.append(_line(cx(right + 0.5), top, cx(right + 0.5), bottom, RAIL))
    return cx(width) - x0, rows * RH


def _element(e, x1: float, x2: float, y: float) -> str:
    """A contact, coil or box between x1 and x2 on the wire at height y."""
    w = x2 - x1
    mid = (x1 + x2) / 2
    k = e.kind
    if k == "contact":
        gap = min(8.0, w / 3)
        out = [_line(x1, y, mid - gap, y), _line(mid + gap, y, x2, y),
               _line(mid - gap, y - 9, mid - gap, y + 9), _line(mid + gap, y - 9, mid + gap, y + 9)]
        if e.mode == "/":
            out.append(_line(mid - gap - 2, y + 8, mid + gap + 2, y - 8))
        elif e.mode in ("P", "N"):
            out.append(_text(mid, y + 4, e.mode, "middle", "font-size='10'"))
        return "".join(out)
    if k == "coil":
        r = min(9.0, w / 3)
        out = [_line(x1, y, mid - r, y), _line(mid + r, y, x2, y),
               f"<path d='M {mid - r + 3:.1f} {y - r:.1f} A {r:.1f} {r:.1f} 0 0 0 "
               f"{mid - r + 3:.1f} {y + r:.1f}' {WIRE}/>",
               f"<path d='M {mid + r - 3:.1f} {y - r:.1f} A {r:.1f} {r:.1f} 0 0 1 "
               f"{mid + r - 3:.1f} {y + r:.1f}' {WIRE}/>"]
        if e.mode == "/":
            out.append(_line(mid - 4, y + 7, mid + 4, y - 7))
        elif e.mode:
            out.append(_text(mid, y + 4, e.mode, "middle", "font-size='10'"))
        return "".join(out)
    label = e.text[1:-1] if e.text.startswith("[") else e.text
    return (f"<rect x='{x1 + 1:.1f}' y='{y - 10:.1f}' width='{w - 2:.1f}' height='20' rx='3' "
            f"{BOX}/>" + _text(mid, y + 4, label, "middle", "fill='#1f4e8c'"))


# ---------------------------------------------------------------------------------------------
# PLCopen XML


def _loc(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _kid(el, name: str):
    return next((c for c in el if isinstance(c.tag, str) and _loc(c.tag) == name), None)


def _kids(el, name: str):
    return [c for c in el if isinstance(c.tag, str) and _loc(c.tag) == name]


def _num(s) -> float:
    try:
        return float(s or 0)
    except ValueError:
        return 0.0


def _pos(el) -> tuple[float, float]:
    p = _kid(el, "position")
    return (_num(p.get("x")), _num(p.get("y"))) if p is not None else (0.0, 0.0)


def _rel(cp, base: tuple[float, float]) -> tuple[float, float]:
    r = _kid(cp, "relPosition") if cp is not None else None
    if r is None:
        return base
    return base[0] + _num(r.get("x")), base[1] + _num(r.get("y"))


def render_xml(text: str, pou: str | None = None) -> Svg:
    """Draw the LD and FBD bodies of a PLCopen XML project (or only POU ``pou``)."""
    from ..lang.frontends.plcopen import parse_xml_safely

    root = parse_xml_safely(text)  # refuses DOCTYPE/ENTITY declarations
    parts: list[str] = []
    y = PAD
    width = 200.0
    for p in root.iter():
        if not isinstance(p.tag, str) or _loc(p.tag) != "pou":
            continue
        if pou is not None and (p.get("name") or "").upper() != pou.upper():
            continue
        body = _kid(p, "body")
        net = None
        if body is not None:
            net = next((c for c in body if isinstance(c.tag, str) and _loc(c.tag) in ("LD", "FBD")),
                       None)
        if net is None:
            continue
        parts.append(_text(PAD, y + 12, f"{p.get('name')} ({_loc(net.tag)})",
                           extra="font-weight='bold'"))
        y += 24
        w, h = _graphic(net, PAD, y, parts)
        width = max(width, w + 2 * PAD)
        y += h + 16
    return _doc(width, y + PAD, parts, "PLCopen diagram")


def _graphic(net, x0: float, y0: float, parts: list[str]) -> tuple[float, float]:
    elems = [c for c in net if isinstance(c.tag, str)]
    by_id = {c.get("localId"): c for c in elems if c.get("localId") is not None}
    minx = min((_pos(c)[0] for c in elems), default=0.0)
    miny = min((_pos(c)[1] for c in elems), default=0.0)
    maxx, maxy = 0.0, 0.0

    def tr(pt: tuple[float, float]) -> tuple[float, float]:
        return x0 + pt[0] - minx, y0 + pt[1] - miny + 12

    def out_point(src, pin: str, near: float = 0.0) -> tuple[float, float]:
        base = _pos(src)
        if _loc(src.tag) == "block":
            ov = _kid(src, "outputVariables")
            for v in _kids(ov, "variable") if ov is not None else []:
                if (v.get("formalParameter") or "").upper() == pin.upper() or not pin:
                    return _rel(_kid(v, "connectionPointOut"), base)
        pts = [_rel(cp, base) for cp in _kids(src, "connectionPointOut")]
        return min(pts, key=lambda q: abs(q[1] - near)) if pts else base

    def wires(cpi, dest_pt) -> None:
        for con in _kids(cpi, "connection") if cpi is not None else []:
            pts = [_pos_of(q) for q in _kids(con, "position")]
            if len(pts) < 2:
                src = by_id.get(con.get("refLocalId"))
                if src is None:
                    continue
                a = out_point(src, con.get("formalParameter") or "", dest_pt[1])
                midx = (a[0] + dest_pt[0]) / 2
                pts = [dest_pt, (midx, dest_pt[1]), (midx, a[1]), a]
            d = " ".join(f"{tr(q)[0]:.1f},{tr(q)[1]:.1f}" for q in pts)
            parts.append(f"<polyline points='{d}' {WIRE}/>")

    for el in elems:
        k = _loc(el.tag)
        x, y = _pos(el)
        w = _num(el.get("width", 30))
        h = _num(el.get("height", 20))
        maxx, maxy = max(maxx, x + w - minx), max(maxy, y + h - miny)
        X, Y = tr((x, y))
        if k in ("leftPowerRail", "rightPowerRail"):
            parts.append(_line(X + w / 2, Y, X + w / 2, Y + h, RAIL))
        elif k in ("contact", "coil"):
            v = _kid(el, "variable")
            name = (v.text or "").strip() if v is not None else ""

            class _E:
                kind = k
                mode = ("P" if el.get("edge") == "rising" else "N" if el.get("edge") == "falling"
                        else "S" if el.get("storage") == "set" else "R" if el.get("storage") ==
                        "reset" else "/" if el.get("negated") in ("true", "1") else "")
                text = ""

            parts.append(_element(_E, X, X + w, Y + h / 2))
            parts.append(_text(X + w / 2, Y - 4, name, "middle", "fill='#0b3d91'"))
        elif k == "block":
            parts.append(f"<rect x='{X:.1f}' y='{Y:.1f}' width='{w:.1f}' height='{h:.1f}' rx='3' "
                         f"{BOX}/>")
            parts.append(_text(X + w / 2, Y + 14, el.get("typeName", ""), "middle",
                               "font-weight='bold' fill='#1f4e8c'"))
            if el.get("instanceName"):
                parts.append(_text(X + w / 2, Y - 4, el.get("instanceName", ""), "middle",
                                   "fill='#0b3d91'"))
            for grp, anchor in (("inputVariables", "start"), ("outputVariables", "end")):
                g = _kid(el, grp)
                for v in _kids(g, "variable") if g is not None else []:
                    cp = _kid(v, "connectionPointIn" if anchor == "start" else
                              "connectionPointOut")
                    px, py = tr(_rel(cp, (x, y)))
                    dx = 4 if anchor == "start" else -4
                    parts.append(_text(px + dx, py + 4, v.get("formalParameter", ""), anchor,
                                       "font-size='10'"))
        elif k in ("inVariable", "outVariable", "inOutVariable"):
            ex = _kid(el, "expression")
            parts.append(f"<rect x='{X:.1f}' y='{Y:.1f}' width='{w:.1f}' height='{h:.1f}' rx='8' "
                         "stroke='#555' fill='#fafafa'/>")
            parts.append(_text(X + w / 2, Y + h / 2 + 4, (ex.text or "").strip()
                               if ex is not None else "", "middle"))
        elif k in ("connector", "continuation"):
            parts.append(f"<rect x='{X:.1f}' y='{Y:.1f}' width='{w:.1f}' height='{h:.1f}' rx='10' "
                         "stroke='#555' fill='#fff'/>")
            parts.append(_text(X + w / 2, Y + h / 2 + 4, el.get("name", ""), "middle"))
        elif k == "comment":
            c = _kid(el, "content")
            txt = " ".join("".join(c.itertext()).split()) if c is not None else ""
            parts.append(_text(X, Y + 12, txt, extra="fill='#777' font-style='italic'"))
        if k == "block":
            g = _kid(el, "inputVariables")
            for v in _kids(g, "variable") if g is not None else []:
                cpi = _kid(v, "connectionPointIn")
                wires(cpi, _rel(cpi, (x, y)))
        else:
            for cpi in _kids(el, "connectionPointIn"):
                wires(cpi, _rel(cpi, (x, y)))
    return maxx + 20, maxy + 24


def _pos_of(q) -> tuple[float, float]:
    return _num(q.get("x")), _num(q.get("y"))


def render(source: str | os.PathLike, pou: str | None = None) -> Svg:
    """Draw a ``.ld`` or PLCopen ``.xml`` file (a path), or ladder text given directly."""
    s = str(source)
    if os.path.splitext(s)[1].lower() in (".ld", ".xml") and os.path.exists(s):
        with open(s, encoding="utf-8-sig") as fh:
            text = fh.read()
        if s.lower().endswith(".xml"):
            return render_xml(text, pou)
        return render_ld(text, s, pou)
    if s.lstrip().startswith("<"):
        return render_xml(s, pou)
    return render_ld(s, "<input>.ld", pou)


__all__ = ["Svg", "render", "render_ld", "render_xml"]
