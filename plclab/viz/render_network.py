"""LD and FBD networks as SVG, drawn from the network elements every front end makes
(:class:`plclab.lang.lower.network.Elem`): the text ladder format and PLCopen XML (LD and FBD)
go through the same drawing.

The layout is computed, not copied: an element's column is the length of the longest path of
wires feeding it; coils, output variables, jumps and returns stand in the last column, so the
right rail is one straight line for the whole POU; rows follow the wiring (each input pin on
the row of the output pin feeding it). Boxes are drawn as CODESYS and OpenPLC Editor draw them
(docs/adr/0048): the instance above, the type inside, every declared pin in declared order, each
operand at its pin; wires into one pin meet on one junction line; columns and boxes are as wide
as their measured text. With ``values`` (variable name -> value, e.g. from a Trace at a time),
contacts and coils that carry power are drawn green, wires carrying TRUE too, and each variable
shows its value, as an editor's online mode does.

>>> from plclab.viz.render_network import render_source
>>> svg = render_source('''PROGRAM P VAR a, q : BOOL; END_VAR
... |   a       q   |
... |---[ ]-----( )-|
... END_PROGRAM''', "p.ld", values={"A": True})
>>> svg.startswith("<svg") and "#1a7f37" in svg
True
"""
from __future__ import annotations

from typing import Any
from xml.sax.saxutils import escape

from ..errors import PlcError
from .ladder_svg import BOX, PAD, RAIL, WIRE, Svg
from .network_layout import (
    BOXES,
    ON,
    ON_WIRE,
    OPERAND,
    ROWH,
    NetworkLayout,
    box_title,
    mark_text,
    pin_of,
    svg_line,
    svg_text,
    text_w,
)


class _Wires:
    """Wire segments, merged before drawing: a segment drawn twice or two overlapping
    segments on one line become one line (one junction, never doubled lines)."""

    def __init__(self) -> None:
        self.segs: dict[bool, list[tuple[float, float, float, float]]] = {False: [], True: []}

    def add(self, x1: float, y1: float, x2: float, y2: float, live: bool = False) -> None:
        if abs(x1 - x2) < 0.05 and abs(y1 - y2) < 0.05:
            return
        self.segs[live].append((round(x1, 1), round(y1, 1), round(x2, 1), round(y2, 1)))

    def svg(self) -> list[str]:
        out = []
        for live in (False, True):
            style = ON_WIRE if live else WIRE
            out += [svg_line(*s, style) for s in merge_segments(self.segs[live])]
        return out


Segment = tuple[float, float, float, float]  # x1, y1, x2, y2


def merge_segments(segs: list[Segment]) -> list[Segment]:
    """Overlapping or touching collinear horizontal and vertical segments joined into one."""
    lines: dict[tuple[str, float], list[tuple[float, float]]] = {}
    other = []
    for x1, y1, x2, y2 in segs:
        if y1 == y2:
            lines.setdefault(("h", y1), []).append((min(x1, x2), max(x1, x2)))
        elif x1 == x2:
            lines.setdefault(("v", x1), []).append((min(y1, y2), max(y1, y2)))
        else:
            other.append((x1, y1, x2, y2))
    out = []
    for (kind, at), spans in sorted(lines.items()):
        spans.sort()
        cur = list(spans[0])
        merged = []
        for a, b in spans[1:]:
            if a <= cur[1] + 0.05:
                cur[1] = max(cur[1], b)
            else:
                merged.append(cur)
                cur = [a, b]
        merged.append(cur)
        for a, b in merged:
            out.append((a, at, b, at) if kind == "h" else (at, a, at, b))
    return out + other


def render_elems(elems: list, title: str = "", values: dict[str, Any] | None = None,
                 ladder: bool = True, pous: dict[str, Any] | None = None) -> Svg:
    """Draw one POU's network elements; ``ladder``: with power rails; ``pous``: the file's POUs
    by name (the pins of its function blocks)."""
    lay = NetworkLayout(elems, values, pous)
    last = lay.columns()
    nrows = lay.rows()
    drawn = [e for e in elems if e.kind != "left" and e.id in lay.row]
    # columns as wide as what they hold: operands left of the boxes, the widest element,
    # the output operands right of them
    ncol = last + 1
    lefts, widths, rights = [12.0] * ncol, [64.0] * ncol, [22.0] * ncol
    for e in drawn:
        c = lay.col[e.id]
        widths[c] = max(widths[c], lay.width(e))
        if e.kind in BOXES:
            ops = [lay.operand_label(t) for t in lay.in_operands(e).values()]
            lefts[c] = max([lefts[c]] + [text_w(t, OPERAND) + 14 for t in ops])
            outs = [lay.operand_label(t) for t in lay.out_operands(e).values()]
            rights[c] = max([rights[c]] + [text_w(t, OPERAND) + 14 for t in outs])
    x0 = PAD + (30 if ladder else 0)
    y0 = PAD + 28
    starts = [float(x0)]
    for c in range(ncol):
        starts.append(starts[c] + lefts[c] + widths[c] + rights[c] + 16)

    def x_left(e) -> float:
        return starts[lay.col[e.id]] + lefts[lay.col[e.id]]

    def w_of(e) -> float:
        return lay.width(e) if e.kind in BOXES or e.kind in ("invar", "outvar", "inoutvar") \
            else widths[lay.col[e.id]]

    def y_row(r: float) -> float:
        return y0 + r * ROWH + ROWH / 2

    def out_point(i: int, pin: str) -> tuple[float, float]:
        s = lay.elems[i]
        return x_left(s) + w_of(s), y_row(lay.row[i] + lay.out_row(s, pin))

    parts: list[str] = []
    wires = _Wires()
    if title:
        parts.append(svg_text(PAD, PAD + 12, title, extra="font-weight='bold'"))
    right = starts[last] + lefts[last] + widths[last] + 24
    rail = x0 - 12
    for e in drawn:
        r = lay.row[e.id]
        xl = x_left(e)
        pins = lay.in_pins(e)
        offs = lay.pin_off.get(e.id, {})
        by_pin: dict[str, list[tuple[int, str]]] = {}
        for pin, refs in e.inputs.items():
            by_pin.setdefault(pin_of(pin, pins), []).extend(refs)
        stagger = 0
        for pin, refs in by_pin.items():
            ty = y_row(r + offs.get(pin, 0))
            feeds = []
            for i, sp in refs:
                if i < 0 or lay.elems[i].kind == "left":
                    wires.add(rail, ty, xl, ty, bool(values))
                    continue
                sx, sy = out_point(i, sp)
                feeds.append((sx, sy, lay.flows(lay.elems[i]) is True, i))
            if not feeds:
                continue
            back = [f for f in feeds if f[0] > xl - 12]
            ahead = [f for f in feeds if f[0] <= xl - 12]
            for sx, sy, live, i in back:  # a wire back to the left (a loop): go below
                lo_c, hi_c = lay.col[e.id], lay.col.get(i, lay.col[e.id])
                top_r = min(lay.row.get(i, r), r)
                between = [x for x in drawn if lo_c <= lay.col.get(x.id, -1) <= hi_c and
                           top_r <= lay.row[x.id] <= r + lay.box_rows(e)]
                low = y_row(max(lay.base(x) + (lay.box_rows(x) if x.kind in BOXES else 1) - 1
                                for x in between)) + ROWH / 2
                mid = xl - 10
                for a in ((sx, sy, sx + 10, sy), (sx + 10, sy, sx + 10, low),
                          (sx + 10, low, mid, low), (mid, low, mid, ty), (mid, ty, xl, ty)):
                    wires.add(*a, live)
            if not ahead:
                continue
            # one junction: every source's wire ends on one vertical line, right after the
            # rightmost source (a second pin of the same box fed from another row beside it)
            needs_vertical = any(abs(sy - ty) > 0.5 for _, sy, _, _ in ahead)
            jx = max(sx for sx, _, _, _ in ahead) + 10 + (6 * stagger if needs_vertical else 0)
            jx = min(jx, xl - 6)
            stagger += needs_vertical
            for sx, sy, live, _ in ahead:
                wires.add(sx, sy, jx, sy, live)
            levels = sorted({sy for _, sy, _, _ in ahead} | {ty})
            for a, b in zip(levels, levels[1:], strict=False):
                far = [f for f in ahead if (f[1] <= a if b <= ty else f[1] >= b)]
                wires.add(jx, a, jx, b, any(f[2] for f in far))
            wires.add(jx, ty, xl, ty, any(f[2] for f in ahead))
        parts.append(_draw(e, lay, xl, w_of(e), y_row(lay.base(e))))
        if e.kind == "coil" and ladder:
            wires.add(xl + w_of(e), y_row(lay.base(e)), right, y_row(lay.base(e)),
                      lay.flows(e) is True)
    parts = wires.svg() + parts
    width = right + PAD + 24
    height = y0 + nrows * ROWH + PAD
    if ladder:
        parts.append(svg_line(rail, y0, rail, y0 + nrows * ROWH, RAIL))
        if any(e.kind == "coil" for e in elems):
            parts.append(svg_line(right, y0, right, y0 + nrows * ROWH, RAIL))
    body = "".join(parts)
    return Svg(f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:.0f}' "
               f"height='{height:.0f}' viewBox='0 0 {width:.0f} {height:.0f}'>"
               f"<title>{escape(title or 'network')}</title>"
               f"<rect width='100%' height='100%' fill='white'/>{body}</svg>")


def _draw(e, lay: NetworkLayout, xl: float, w: float, y: float) -> str:
    """One element from xl, ``w`` wide, its (first) wire at height y."""
    k = e.kind
    xr = xl + w
    mid = (xl + xr) / 2
    live = lay.flows(e) is True
    color = ON if live else "#222"
    if k in ("contact", "coil"):
        style = f"stroke='{color}' stroke-width='2' fill='none'"
        fed = any(lay.flows(lay.elems[i]) is True if i >= 0 else lay.values
                  for i, _ in e.inputs.get("", []))
        out = [svg_line(xl, y, mid - 9, y, ON_WIRE if fed else WIRE),
               svg_line(mid + 9, y, xr, y, ON_WIRE if live else WIRE)]
        if k == "contact":
            out += [svg_line(mid - 9, y - 11, mid - 9, y + 11, style),
                    svg_line(mid + 9, y - 11, mid + 9, y + 11, style)]
        else:
            out.append(f"<path d='M{mid - 6:.1f},{y - 11:.1f} A11,11 0 0 0 {mid - 6:.1f},"
                       f"{y + 11:.1f} M{mid + 6:.1f},{y - 11:.1f} A11,11 0 0 1 {mid + 6:.1f},"
                       f"{y + 11:.1f}' {style}/>")
        mark = {"/": "/", "P": "P", "N": "N", "S": "S", "R": "R"}.get(e.mode, "")
        if mark:
            out.append(svg_text(mid, y + 4, mark, "middle", f"fill='{color}'"))
        out.append(svg_text(mid, y - 15, lay.label(e), "middle",
                        "class='name' fill='#0b3d91'"))
        return "".join(out)
    if k in BOXES:
        return _box(e, lay, xl, w, y)
    if k in ("invar", "outvar", "inoutvar"):
        return (f"<rect class='var' x='{xl:.1f}' y='{y - 11:.1f}' width='{w:.1f}' height='22' "
                f"rx='11' stroke='{color}' fill='#fffbe6'/>" +
                svg_text(mid, y + 4, lay.label(e), "middle"))
    if k == "conn":
        return f"<circle cx='{mid:.1f}' cy='{y:.1f}' r='3' fill='#222'/>" + svg_line(xl, y, xr, y)
    if k in ("jump", "label", "return"):
        return svg_text(xl, y + 4, mark_text(e), extra="font-weight='bold' fill='#8a3ffc'")
    return ""


def _box(e, lay: NetworkLayout, xl: float, w: float, y: float) -> str:
    """A block as CODESYS and OpenPLC Editor draw it: the instance above, the type inside at
    the top, input pins left and output pins right, each with the operand written at it."""
    from ..lang.unparse import expr

    ins, outs = lay.in_pins(e), lay.out_pins(e)
    offs = lay.pin_off.get(e.id, {})
    first = offs.get(ins[0], 0)
    h = (lay.box_rows(e) - 1) * ROWH + 40
    top = y - 27
    xr = xl + w
    name = escape(box_title(e))
    out = [f"<g class='box' data-type='{name}' data-elem='{e.id}'>",
           f"<rect x='{xl:.1f}' y='{top:.1f}' width='{w:.1f}' height='{h:.1f}' rx='3' {BOX}/>",
           svg_text(xl + w / 2, top + 12, box_title(e), "middle",
                "class='type' font-weight='bold' fill='#1f4e8c'")]
    if e.instance is not None and e.type_name:
        out.append(svg_text(xl + w / 2, top - 4, expr(e.instance), "middle",
                        "class='instance' fill='#0b3d91'"))
    ops_in, ops_out = lay.in_operands(e), lay.out_operands(e)
    for n, p in enumerate(ins):
        py = y + (offs.get(p, n) - first) * ROWH
        out.append(svg_text(xl + 4, py + 4, lay.pin_text(p), extra=f"class='pin in' data-pin='{p}'"))
        if p in e.neg_in:  # the IEC negation circle on the pin
            out.append(f"<circle cx='{xl - 4:.1f}' cy='{py:.1f}' r='4' fill='white' "
                       "stroke='#1f4e8c' stroke-width='1.4'/>")
        if p in ops_in:
            out.append(svg_line(xl - 8, py, xl, py))
            out.append(svg_text(xl - 6, py - 4, lay.operand_label(ops_in[p]), "end",
                            f"class='operand in' data-pin='{p}' font-size='{OPERAND}' "
                            "fill='#0b3d91'"))
    for n, p in enumerate(outs):
        py = y + n * ROWH
        out.append(svg_text(xr - 4, py + 4, lay.out_pin_label(e, p), "end",
                        f"class='pin out' data-pin='{p}'"))
        if p in ops_out:
            out.append(svg_line(xr, py, xr + 8, py))
            out.append(svg_text(xr + 6, py - 4, lay.operand_label(ops_out[p]),
                            extra=f"class='operand out' data-pin='{p}' font-size='{OPERAND}' "
                            "fill='#0b3d91'"))
    out.append("</g>")
    return "".join(out)


def parse_source(text: str, file: str):
    """One source file parsed by its front end, not lowered (networks stay elements); the
    first error as a PlcError."""
    from ..lang.frontends.registry import for_file

    src, diags = for_file(file).parse(text, file)
    errors = [d for d in diags if d.severity == "error"]
    if errors:
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    return src


def _networks(src) -> list[tuple[Any, list]]:
    out = []
    for p in src.pous:
        nets = [b for b in p.pending if b.kind == "NETWORK"]
        if nets:
            out.append((p, [e for b in nets for e in b.payload]))
    return out


def network_pous(text: str, file: str) -> list[tuple[Any, list]]:
    """(POU, its network elements) for each LD/FBD POU of a source (parsed, not lowered)."""
    return _networks(parse_source(text, file))


def render_source(text: str, file: str, pou: str | None = None,
                  values: dict[str, Any] | None = None) -> Svg:
    """The network of POU ``pou`` (default: the first LD/FBD POU) of a source as SVG."""
    src = parse_source(text, file)
    chosen = [(p, els) for p, els in _networks(src) if pou is None or p.name == pou.upper()]
    if not chosen:
        raise PlcError("PLC4040", f"{file} has no LD or FBD body" + (
            f" named {pou}" if pou else "") + "; plclab render draws LD and FBD networks, SFC "
            "charts and ST/IL listings: name a POU with --pou")
    p, els = chosen[0]
    return render_elems(els, f"{p.kind} {p.spelling or p.name} ({p.language})", values,
                        ladder=p.language != "FBD", pous={q.name: q for q in src.pous})
