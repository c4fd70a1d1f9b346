"""LD and FBD networks as SVG, drawn from the network elements every front end makes
(:class:`plclab.lang.lower.network.Elem`): the text ladder format and PLCopen XML (LD and FBD)
go through the same drawing.

The layout is computed, not copied: an element's column is the length of the longest path of
wires feeding it; coils, output variables, jumps and returns stand in the last column, so the
right rail is one straight line for the whole POU; rows follow the wiring (a box's first input
on its own row, its other inputs below). Boxes show their type above, their instance name on
top and pin names on both sides. With ``values`` (variable name -> value, e.g. from a Trace at
a time), contacts and coils that carry power are drawn green, wires carrying TRUE too, and each
variable shows its value, as an editor's online mode does.

>>> from plclab.viz.render_network import render_source
>>> svg = render_source('''PROGRAM P VAR a, q : BOOL; END_VAR
... |   a       q   |
... |---[ ]-----( )-|
... END_PROGRAM''', "p.ld", values={"A": True})
>>> svg.startswith("<svg") and "#1a7f37" in svg
True
"""

from __future__ import annotations

import functools
from typing import Any
from xml.sax.saxutils import escape

from ..errors import PlcError
from ..lang import ast as A
from .ladder_svg import BOX, FONT, PAD, RAIL, WIRE, Svg

COLW = 150  # width of a column
ROWH = 40  # height of a row (one pin)
BOXW = 96
ON = "#1a7f37"  # power flows / TRUE
ON_WIRE = f"stroke='{ON}' stroke-width='2.6' fill='none'"
SINKS = {"coil", "outvar", "jump", "return"}


def _txt(x: float, y: float, s: str, anchor: str = "start", extra: str = "") -> str:
    size = "" if "font-size" in extra else "font-size='12' "
    return (f"<text x='{x:.1f}' y='{y:.1f}' {FONT} {size}text-anchor='{anchor}' "
            f"{extra}>{escape(s)}</text>")


def _ln(x1: float, y1: float, x2: float, y2: float, style: str = WIRE) -> str:
    return f"<line x1='{x1:.1f}' y1='{y1:.1f}' x2='{x2:.1f}' y2='{y2:.1f}' {style}/>"


def _fmt(v: Any) -> str:
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _var_text(e) -> str:
    from ..lang.unparse import expr

    return expr(e.var) if e.var is not None else ""


class _Layout:
    """Columns, rows and pins of the elements of one POU's network."""

    def __init__(self, elems: list, values: dict[str, Any] | None,
                 pous: dict[str, Any] | None = None) -> None:
        self.elems = {e.id: e for e in elems}
        self.pous = pous or {}  # the POUs of the drawn file, by name
        self.values = {k.upper(): v for k, v in (values or {}).items()}
        self.consumers: dict[int, list] = {}
        for e in elems:
            for refs in e.inputs.values():
                for i, _ in refs:
                    self.consumers.setdefault(i, []).append(e)
        self.col: dict[int, int] = {}
        self.row: dict[int, int] = {}
        self.pin_off: dict[int, dict[str, int]] = {}
        self.power: dict[int, bool | None] = {}

    # -- structure ----------------------------------------------------------------------------
    def sources(self, e) -> list[tuple[str, int, str]]:
        """(input pin, source id, source pin) of ``e``, pins in order, left rail left out."""
        out = []
        for pin, refs in e.inputs.items():
            for i, sp in refs:
                if i >= 0 and self.elems[i].kind != "left":
                    out.append((pin, i, sp))
        return out

    def in_pins(self, e) -> list[str]:
        if e.kind not in ("fb", "func"):
            return [""]
        pins = [p for p in e.inputs if p != ""] + [a.name for a in e.args if a.name]
        if "" in e.inputs:
            pins.insert(0, self.power_pins(e)[0])
        return pins or [""]

    def out_pins(self, e) -> list[str]:
        if e.kind not in ("fb", "func"):
            return [""]
        outs = list(getattr(e, "outs", []) or [])
        if not outs:
            known = e.kind == "fb" and self.power_pins(e) != ("EN", "ENO")
            outs = [self.power_pins(e)[1]] if "" in e.inputs or known else \
                [e.out_pin or "OUT"]
        return outs

    def power_pins(self, e) -> tuple[str, str]:
        """(input, output) pins that carry a ladder box's power flow: the block spec's, else
        the first BOOL input and output of the block's declaration (the file's or plclab's
        library), else EN/ENO."""
        from ..lang.builtins import BLOCKS

        b = BLOCKS.get(e.type_name)
        if b is not None and b.power:
            return b.power
        pou = self.pous.get(e.type_name) or _library_pous().get(e.type_name)
        if pou is not None:
            def first(section: str) -> str | None:
                return next((d.spelling or d.name for d in pou.decls if d.section == section and
                             isinstance(d.type, A.NamedTypeRef) and d.type.name == "BOOL"), None)
            i, o = first("VAR_INPUT"), first("VAR_OUTPUT")
            if i and o:
                return i, o
        return ("EN", "ENO")

    def columns(self) -> int:
        order = _topological(list(self.elems.values()), self)
        for e in order:
            srcs = [self.col[i] + 1 for _, i, _ in self.sources(e) if i in self.col]
            self.col[e.id] = max(srcs, default=0)
        last = max((c for i, c in self.col.items() if self.elems[i].kind not in SINKS),
                   default=0) + 1
        for e in order:
            if e.kind in SINKS:
                self.col[e.id] = last
        return last

    def rows(self) -> int:
        """Rows from the sinks back, as a tree: each element belongs to its first consumer;
        each input pin of a box stands on the row of what feeds it (the box grows), so wires
        run straight; the networks (sinks in order) stacked. Iterative."""
        order = [e for e in _topological(list(self.elems.values()), self) if e.kind != "left"]
        sinks = sorted((e for e in order if not self.consumers.get(e.id)),
                       key=lambda e: e.order)
        parent: dict[int, int] = {}
        kids: dict[int, list[tuple[str, int]]] = {}  # id -> (input pin, child id)
        seen: set[int] = set()
        stack = [e.id for e in reversed(sinks)]
        while stack:
            i = stack.pop()
            if i in seen:
                continue
            seen.add(i)
            mine = []
            for pin, j, _ in self.sources(self.elems[i]):
                if j in seen or j in parent:
                    continue
                parent[j] = i
                mine.append((pin, j))
            kids[i] = mine
            stack.extend(j for _, j in reversed(mine))
        size: dict[int, int] = {}
        places: dict[int, list[tuple[int, int]]] = {}
        for e in order:  # sources first: children are sized before their parent
            self.pin_off[e.id], places[e.id], size[e.id] = self.offsets(e, kids.get(e.id, []),
                                                                        size)
        free, gap = 0, True
        for root in sinks:
            members, todo = [], [(root.id, 0)]
            while todo:
                i, r = todo.pop()
                members.append((i, r))
                todo.extend((j, r + off) for off, j in places.get(i, []))
            boxes = any(self.elems[i].kind in ("fb", "func") for i, _ in members)
            if boxes and not gap:
                free += 1  # room for the box titles above
            for i, r in members:
                self.row[i] = free + r
            free += size.get(root.id, 1) + (1 if boxes else 0)
            gap = boxes
        return free

    def offsets(self, e, kids: list[tuple[str, int]], size: dict[int, int]):
        """(input pin -> row offset, (row offset, child) placements, rows taken) of ``e``."""
        pins = self.in_pins(e)
        by_pin: dict[str, list[int]] = {}
        for pin, j in kids:
            by_pin.setdefault(_pin_of(pin, pins), []).append(j)
        pin_off: dict[str, int] = {}
        places: list[tuple[int, int]] = []
        nxt = 0
        for pin in pins:
            pin_off[pin] = cur = nxt
            for j in by_pin.get(pin, []):
                places.append((cur, j))
                cur += size.get(j, 1)
            nxt = max(nxt + 1, cur)
        outs = len(self.out_pins(e)) if e.kind in ("fb", "func") else 1
        return pin_off, places, max(nxt, outs)

    def box_rows(self, e) -> int:
        """How many rows the box of ``e`` spans (its last input or output pin + 1)."""
        offs = self.pin_off.get(e.id, {})
        return max(max(offs.values(), default=0) + 1, len(self.out_pins(e)))

    # -- values -------------------------------------------------------------------------------
    def value_of(self, text: str) -> Any:
        return self.values.get(text.upper())

    def flows(self, e) -> bool | None:
        """Power flowing out of ``e`` (LD) or its BOOL output value, when values are known."""
        if e.id in self.power:
            return self.power[e.id]
        self.power[e.id] = None  # cycles: unknown
        k = e.kind
        if k == "left":
            out: bool | None = True
        elif k in ("contact", "coil", "conn"):
            ins = [self.flows(self.elems[i]) if i >= 0 else True
                   for i, _ in e.inputs.get("", [])]
            feed = True if any(x is True for x in ins) else (None if None in ins else False)
            if k == "contact":
                v = self.value_of(_var_text(e))
                cond = None if not isinstance(v, bool) else (not v if e.mode == "/" else v)
                out = None if feed is None or cond is None else (feed and cond)
            else:
                out = feed
        elif k in ("invar", "inoutvar"):
            v = self.value_of(_var_text(e))
            out = v if isinstance(v, bool) else None
        elif k == "func" and e.type_name in ("AND", "OR", "XOR", "NOT"):
            ins = [self.flows(self.elems[i]) for refs in e.inputs.values() for i, _ in refs
                   if i >= 0]
            ins = [(not x) if x is not None and pin in e.neg_in else x
                   for pin, x in zip([p for p, refs in e.inputs.items() for _ in refs], ins,
                                     strict=False)]
            if None in ins or not ins:
                out = None
            elif e.type_name == "NOT":
                out = not ins[0]
            elif e.type_name == "AND":
                out = all(ins)
            elif e.type_name == "OR":
                out = any(ins)
            else:
                out = sum(bool(x) for x in ins) % 2 == 1
        elif k == "fb" and e.instance is not None:
            from ..lang.unparse import expr

            v = self.value_of(f"{expr(e.instance)}.{self.out_pins(e)[0]}")
            out = v if isinstance(v, bool) else None
        else:
            out = None
        self.power[e.id] = out
        return out


@functools.lru_cache(maxsize=1)
def _library_pous() -> dict[str, Any]:
    """plclab's library blocks written in ST (BLINKER, ...), by name."""
    from ..lang.frontends.st import parse_library

    return {p.name: p for f in parse_library() for p in f.pous}


def _pin_of(pin: str, pins: list[str]) -> str:
    """The drawn pin an input arrives at: a text box's power flow ("") at its first pin."""
    return pin if pin in pins else pins[0] if pin == "" else pins[-1]


def _topological(elems: list, lay: _Layout) -> list:
    from ..lang.lower.network import execution_order

    return execution_order(elems)


def render_elems(elems: list, title: str = "", values: dict[str, Any] | None = None,
                 ladder: bool = True, pous: dict[str, Any] | None = None) -> Svg:
    """Draw one POU's network elements; ``ladder``: with power rails; ``pous``: the file's POUs
    by name (the pins of its function blocks)."""
    lay = _Layout(elems, values, pous)
    ncols = lay.columns()
    nrows = lay.rows()
    x0 = PAD + (30 if ladder else 0)
    y0 = PAD + 28

    def x_left(e) -> float:
        return x0 + lay.col[e.id] * COLW + (COLW - BOXW) / 2

    def y_row(r: float) -> float:
        return y0 + r * ROWH + ROWH / 2

    def out_point(i: int, pin: str) -> tuple[float, float]:
        s = lay.elems[i]
        outs = lay.out_pins(s)
        k = outs.index(pin) if pin in outs else 0
        return x_left(s) + BOXW, y_row(lay.row.get(i, 0) + k)

    parts: list[str] = []
    if title:
        parts.append(_txt(PAD, PAD + 12, title, extra="font-weight='bold'"))
    right = x0 + ncols * COLW + (COLW - BOXW) / 2 + BOXW + 24
    for e in elems:
        if e.kind == "left" or e.id not in lay.row:
            continue
        r = lay.row[e.id]
        xl, xr = x_left(e), x_left(e) + BOXW
        pins = lay.in_pins(e)
        offs = lay.pin_off.get(e.id, {})
        for pin, refs in e.inputs.items():
            ty = y_row(r + offs.get(_pin_of(pin, pins), 0))
            for n, (i, sp) in enumerate(refs):
                if i < 0 or lay.elems[i].kind == "left":
                    parts.append(_ln(x0 - 12, ty, xl, ty, ON_WIRE if values else WIRE))
                    continue
                sx, sy = out_point(i, sp if lay.elems[i].kind in ("fb", "func") else "")
                live = lay.flows(lay.elems[i]) is True
                style = ON_WIRE if live else WIRE
                mid = xl - 10 - 4 * n
                if sx > mid:  # a wire back to the left (a loop through a variable): go below
                    lo_c, hi_c = lay.col[e.id], lay.col.get(i, lay.col[e.id])
                    top_r = min(lay.row.get(i, r), r)
                    between = [x for x in lay.elems.values() if x.id in lay.row and
                               lo_c <= lay.col.get(x.id, -1) <= hi_c and lay.row[x.id] >= top_r
                               and lay.row[x.id] <= r + lay.box_rows(e)]
                    low = y_row(max(lay.row[x.id] + lay.box_rows(x) - 1 for x in between)) + \
                        ROWH / 2
                    parts.append(_ln(sx, sy, sx + 10, sy, style))
                    parts.append(_ln(sx + 10, sy, sx + 10, low, style))
                    parts.append(_ln(sx + 10, low, mid, low, style))
                    parts.append(_ln(mid, low, mid, ty, style))
                else:
                    parts.append(_ln(sx, sy, mid, sy, style))
                    parts.append(_ln(mid, sy, mid, ty, style))
                parts.append(_ln(mid, ty, xl, ty, style))
        parts.append(_draw(e, lay, xl, xr, y_row(r)))
        if e.kind in ("coil",) and ladder:
            parts.append(_ln(xr, y_row(r), right, y_row(r),
                             ON_WIRE if lay.flows(e) is True else WIRE))
    width = right + PAD + 60
    height = y0 + nrows * ROWH + PAD
    if ladder:
        parts.append(_ln(x0 - 12, y0, x0 - 12, y0 + nrows * ROWH, RAIL))
        if any(e.kind == "coil" for e in elems):
            parts.append(_ln(right, y0, right, y0 + nrows * ROWH, RAIL))
    body = "".join(parts)
    return Svg(f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:.0f}' "
               f"height='{height:.0f}' viewBox='0 0 {width:.0f} {height:.0f}'>"
               f"<title>{escape(title or 'network')}</title>"
               f"<rect width='100%' height='100%' fill='white'/>{body}</svg>")


def _draw(e, lay: _Layout, xl: float, xr: float, y: float) -> str:
    """One element between xl and xr, its wire at height y."""
    k = e.kind
    mid = (xl + xr) / 2
    name = _var_text(e)
    val = lay.value_of(name) if name else None
    shown = f" = {_fmt(val)}" if val is not None else ""
    live = lay.flows(e) is True
    color = ON if live else "#222"
    if k in ("contact", "coil"):
        style = f"stroke='{color}' stroke-width='2' fill='none'"
        out = [_ln(xl, y, mid - 9, y, ON_WIRE if live else WIRE),
               _ln(mid + 9, y, xr, y, ON_WIRE if live else WIRE)]
        if k == "contact":
            out += [_ln(mid - 9, y - 11, mid - 9, y + 11, style),
                    _ln(mid + 9, y - 11, mid + 9, y + 11, style)]
        else:
            out.append(f"<path d='M{mid - 6:.1f},{y - 11:.1f} A11,11 0 0 0 {mid - 6:.1f},"
                       f"{y + 11:.1f} M{mid + 6:.1f},{y - 11:.1f} A11,11 0 0 1 {mid + 6:.1f},"
                       f"{y + 11:.1f}' {style}/>")
        mark = {"/": "/", "P": "P", "N": "N", "S": "S", "R": "R"}.get(e.mode, "")
        if mark:
            out.append(_txt(mid, y + 4, mark, "middle", f"fill='{color}'"))
        out.append(_txt(mid, y - 15, name + shown, "middle", "fill='#0b3d91'"))
        return "".join(out)
    if k in ("fb", "func"):
        from ..lang.unparse import expr

        ins, outs = lay.in_pins(e), lay.out_pins(e)
        offs = lay.pin_off.get(e.id, {})
        h = (lay.box_rows(e) - 1) * ROWH + 26
        top = y - 13
        out = [f"<rect x='{xl:.1f}' y='{top:.1f}' width='{BOXW}' height='{h:.1f}' rx='3' {BOX}/>",
               _txt(mid, top - 4, e.type_name, "middle", "font-weight='bold'")]
        if e.instance is not None:
            out.append(_txt(mid, top - 16, expr(e.instance), "middle", "fill='#0b3d91'"))
        for n, p in enumerate(ins):
            py = y + offs.get(p, n) * ROWH
            out.append(_txt(xl + 4, py + 4, p))
            if p in e.neg_in:  # the IEC negation circle on the pin
                out.append(f"<circle cx='{xl - 4:.1f}' cy='{py:.1f}' r='4' fill='white' "
                           "stroke='#1f4e8c' stroke-width='1.4'/>")
            for a in e.args:
                if a.name == p and a.value is not None:
                    out.append(_txt(xl - 4, py - 4, expr(a.value), "end",
                                    "font-size='10' fill='#0b3d91'"))
        for n, p in enumerate(outs):
            shown_v = ""
            if e.instance is not None:
                v = lay.value_of(f"{expr(e.instance)}.{p}")
                shown_v = f" {_fmt(v)}" if v is not None else ""
            out.append(_txt(xr - 4, y + n * ROWH + 4, p + shown_v, "end"))
        for t in e.targets:
            out.append(_txt(xr + 4, y - 4, "-> " + expr(t), extra="fill='#0b3d91'"))
        return "".join(out)
    if k in ("invar", "outvar", "inoutvar"):
        return (f"<rect x='{xl:.1f}' y='{y - 11:.1f}' width='{BOXW}' height='22' rx='11' "
                f"stroke='{color}' fill='#fffbe6'/>" + _txt(mid, y + 4, name + shown, "middle"))
    if k == "conn":
        return f"<circle cx='{mid:.1f}' cy='{y:.1f}' r='3' fill='#222'/>" + _ln(xl, y, xr, y)
    if k in ("jump", "label", "return"):
        text = {"jump": f">> {e.label}", "label": f"{e.label}:", "return": "RETURN"}[k]
        return _txt(xl, y + 4, text, extra="font-weight='bold' fill='#8a3ffc'")
    return ""


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
