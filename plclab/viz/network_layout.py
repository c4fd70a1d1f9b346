"""The layout of an LD or FBD network for :mod:`.render_network`: columns from the longest path
of wires, rows from the wiring, pins in declared order, measured widths, and whether power flows
(with ``values``). Also the small SVG text helpers the drawing shares.
"""


from __future__ import annotations

import functools
import re
from typing import Any
from xml.sax.saxutils import escape

from ..lang import ast as A
from .ladder_svg import FONT, WIRE
from .text_width import text_width

ROWH = 40  # height of a row (one pin)
ON = "#1a7f37"  # power flows / TRUE
ON_WIRE = f"stroke='{ON}' stroke-width='2.6' fill='none'"
SINKS = {"coil", "outvar", "jump", "return"}


def svg_text(x: float, y: float, s: str, anchor: str = "start", extra: str = "") -> str:
    size = "" if "font-size" in extra else "font-size='12' "
    return (f"<text x='{x:.1f}' y='{y:.1f}' {FONT} {size}text-anchor='{anchor}' "
            f"{extra}>{escape(s)}</text>")


def svg_line(x1: float, y1: float, x2: float, y2: float, style: str = WIRE) -> str:
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


class NetworkLayout:
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
        self.spelling: dict[str, str] = {}  # a pin (upper case) as its block declares it

    # -- structure ----------------------------------------------------------------------------
    def sources(self, e) -> list[tuple[str, int, str]]:
        """(input pin, source id, source pin) of ``e``, pins in order, left rail left out."""
        out = []
        for pin, refs in e.inputs.items():
            for i, sp in refs:
                if i >= 0 and self.elems[i].kind != "left":
                    out.append((pin, i, sp))
        return out

    def declared(self, type_name: str) -> tuple[list[str], list[str]] | None:
        """(inputs, outputs) of a block or function declared in the file or plclab's library;
        VAR_IN_OUT on both sides, as IEC 61131-3 draws them."""
        pou = self.pous.get(type_name.upper()) or _library_pous().get(type_name.upper())
        if pou is None:
            return None
        ins, outs = [], []
        for d in pou.decls:
            name = d.spelling or d.name
            self.spelling.setdefault(name.upper(), name)
            if d.section in ("VAR_INPUT", "VAR_IN_OUT"):
                ins.append(name.upper())
            if d.section in ("VAR_OUTPUT", "VAR_IN_OUT"):
                outs.append(name.upper())
        return ins, outs

    def arg_pins(self, e) -> list[str]:
        """The pin of each parameter written in a text box, in order: named ones by their
        name, positional ones by the function's formal parameters (IN1, IN2, ... for ADD, G,
        IN0, IN1 for SEL, K, IN0, IN1, ... for MUX)."""
        from ..lang.builtins import BUILTINS, conversion

        n = len(e.args)
        b = BUILTINS.get(e.type_name)
        if b is not None:
            params = list(b.params)
            if e.type_name == "MUX":
                params = ["K"] + [f"IN{i}" for i in range(max(n - 1, 2))]
            elif b.variadic:
                params += [f"IN{i + 1}" for i in range(len(params), n)]
        elif conversion(e.type_name) is not None:
            params = ["IN"]
        else:
            d = self.declared(e.type_name) if e.type_name else None
            params = d[0] if d is not None and e.kind == "func" else []
        params = params + [f"IN{i + 1}" for i in range(len(params), n)]
        return [(a.name or params[k]).upper() for k, a in enumerate(e.args)]

    def in_pins(self, e) -> list[str]:
        """The input pins of a box, top to bottom: the power flow's (LD), the wired ones, the
        ones given an operand, then the other declared inputs; [""] for other elements."""
        if e.kind not in BOXES:
            return [""]
        pins: list[str] = []
        if "" in e.inputs:
            pins.append(self.power_pins(e)[0].upper() if e.kind == "fb" else "EN")
        if "EN" in (p.upper() for p in e.inputs):
            pins.append("EN")
        if e.kind == "fb":  # a block's pins in the order it declares them, as editors draw
            d = self.declared(e.type_name)
            pins += [p for p in (d[0] if d is not None else []) if p not in pins]
        for p in e.inputs:
            if p and p.upper() not in pins:
                pins.append(p.upper())
        for a, p in zip(e.args, self.arg_pins(e), strict=True):
            if not a.output and p not in pins:
                pins.append(p)
        return pins or [""]

    def out_pins(self, e) -> list[str]:
        """The output pins of a box, top to bottom: the power flow's first (ENO of a function
        in a rung, then OUT), then the declared ones; [""] for other elements."""
        if e.kind == "cmp":
            return ["OUT"]
        if e.kind not in BOXES:
            return [""]
        outs = [p.upper() for p in getattr(e, "outs", []) or []]
        if not outs:
            if e.kind == "fb":
                known = self.power_pins(e) != ("EN", "ENO")
                outs = [self.power_pins(e)[1].upper()] if "" in e.inputs or known else \
                    [(e.out_pin or "OUT").upper()]
            else:
                outs = (["ENO"] if "" in e.inputs else []) + ["OUT"]
        if e.kind == "fb":  # declared order, as the inputs (ENO and the rung's pin first)
            d = self.declared(e.type_name)
            if d is not None:
                head = [p for p in outs[:1] if p == "ENO" or "" in e.inputs]
                outs = head + [p for p in d[1] if p not in head] + \
                    [p for p in outs if p not in head and p not in d[1]]
        for a, p in zip(e.args, self.arg_pins(e), strict=True):
            if a.output and p not in outs:
                outs.append(p)
        return outs

    def in_operands(self, e) -> dict[str, str]:
        """Input pin -> the operand written at it (a text box's parameters)."""
        from ..lang.unparse import expr

        return {p: expr(a.value) for a, p in zip(e.args, self.arg_pins(e), strict=True)
                if not a.output and a.value is not None}

    def out_operands(self, e) -> dict[str, str]:
        """Output pin -> the variable it writes (``ET=>x``; a function's ``-> x`` at OUT)."""
        from ..lang.unparse import expr

        out = {p: ("NOT " if a.negated else "") + expr(a.value)
               for a, p in zip(e.args, self.arg_pins(e), strict=True)
               if a.output and a.value is not None}
        if e.targets:
            out["OUT"] = ", ".join(expr(t) for t in e.targets)
        return out

    def pin_text(self, pin: str) -> str:
        return self.spelling.get(pin, pin)

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
        each input pin of a box stands on the row of the output that feeds it (the box grows),
        so wires run straight; the networks (sinks in order) stacked. Iterative."""
        order = [e for e in _topological(list(self.elems.values()), self) if e.kind != "left"]
        sinks = sorted((e for e in order if not self.consumers.get(e.id)),
                       key=lambda e: e.order)
        parent: dict[int, int] = {}
        kids: dict[int, list[tuple[str, int, str]]] = {}  # id -> (input pin, child, its pin)
        seen: set[int] = set()
        stack = [e.id for e in reversed(sinks)]
        while stack:
            i = stack.pop()
            if i in seen:
                continue
            seen.add(i)
            mine = []
            for pin, j, sp in self.sources(self.elems[i]):
                if j in seen or j in parent:
                    continue
                parent[j] = i
                mine.append((pin, j, sp))
            kids[i] = mine
            stack.extend(j for _, j, _ in reversed(mine))
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
            boxes = any(self.elems[i].kind in BOXES for i, _ in members)
            if boxes and not gap:
                free += 1  # room for the box titles above
            for i, r in members:
                self.row[i] = free + r
            free += size.get(root.id, 1) + (1 if boxes else 0)
            gap = boxes
        return free

    def out_row(self, e, pin: str) -> int:
        """The row of output ``pin`` of ``e``, counted from the row ``e`` is placed on."""
        base = self.pin_off.get(e.id, {}).get(self.in_pins(e)[0], 0)
        if e.kind not in BOXES:
            return base
        outs = self.out_pins(e)
        return base + (outs.index(pin.upper()) if pin and pin.upper() in outs else 0)

    def offsets(self, e, kids: list[tuple[str, int, str]], size: dict[int, int]):
        """(input pin -> row offset, (row offset, child) placements, rows taken) of ``e``:
        each pin on the row of the output of its first source."""
        pins = self.in_pins(e)
        by_pin: dict[str, list[tuple[int, str]]] = {}
        for pin, j, sp in kids:
            by_pin.setdefault(pin_of(pin, pins), []).append((j, sp))
        pin_off: dict[str, int] = {}
        places: list[tuple[int, int]] = []
        nxt, free = 0, 0  # the next pin's row; the first row below the children so far
        for pin in pins:
            cur = max(nxt, free) if by_pin.get(pin) else nxt
            arrive = None
            for j, sp in by_pin.get(pin, []):
                if places and self.elems[j].kind in BOXES:
                    cur += 1  # a row for the title of a box under another child
                places.append((cur, j))
                if arrive is None:
                    arrive = cur + self.out_row(self.elems[j], sp)
                cur += size.get(j, 1)
            pin_off[pin] = nxt if arrive is None else arrive
            nxt = pin_off[pin] + 1
            free = max(free, cur)
        outs = len(self.out_pins(e)) if e.kind in BOXES else 1
        return pin_off, places, max(nxt, free, pin_off[pins[0]] + outs)

    def base(self, e) -> int:
        """The row of the first pin of ``e`` (the wire row of a contact, coil or variable)."""
        return self.row[e.id] + self.pin_off.get(e.id, {}).get(self.in_pins(e)[0], 0)

    def box_rows(self, e) -> int:
        """How many rows the box of ``e`` spans, from its first pin's row."""
        offs = self.pin_off.get(e.id, {})
        first = offs.get(self.in_pins(e)[0], 0)
        return max(max(offs.values(), default=0) - first + 1, len(self.out_pins(e)))

    # -- values -------------------------------------------------------------------------------
    def value_of(self, text: str) -> Any:
        return self.values.get(text.upper())

    def flows(self, e) -> bool | None:
        """Power flowing out of ``e`` (LD) or its BOOL output value, when values are known."""
        if not self.values:  # no values, no power flow drawn
            return None
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
                cond = None if not isinstance(v, bool) or e.mode in ("P", "N") else \
                    (not v if e.mode == "/" else v)  # an edge: one scan, unknown from a value
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
        elif k == "func" and "" in e.inputs:  # EN -> ENO
            ins = [self.flows(self.elems[i]) if i >= 0 else True
                   for i, _ in e.inputs.get("", [])]
            out = True if any(x is True for x in ins) else (None if None in ins else False)
        else:
            out = None
        self.power[e.id] = out
        return out

    # -- sizes --------------------------------------------------------------------------------
    def label(self, e) -> str:
        """The variable of a contact, coil or variable box with its value when known."""
        name = _var_text(e)
        val = self.value_of(name) if name else None
        return name + (f" = {_fmt(val)}" if val is not None else "")

    def out_pin_label(self, e, pin: str) -> str:
        from ..lang.unparse import expr

        if e.instance is not None:
            v = self.value_of(f"{expr(e.instance)}.{pin}")
            if v is not None:
                return f"{self.pin_text(pin)} {_fmt(v)}"
        return self.pin_text(pin)

    def operand_label(self, text: str) -> str:
        """An operand with its value when it is a variable the values know."""
        v = self.value_of(text) if _VARIABLE.fullmatch(text) else None
        return text + (f" = {_fmt(v)}" if v is not None else "")

    def box_width(self, e) -> float:
        """Wide enough for the type, the instance name above, and on every row the input
        pin's name and the output pin's name side by side."""
        from ..lang.unparse import expr

        ins, outs = self.in_pins(e), self.out_pins(e)
        offs = self.pin_off.get(e.id, {})
        first = offs.get(ins[0], 0)
        left: dict[int, str] = {offs.get(p, n) - first: self.pin_text(p) for n, p in
                                enumerate(ins)}
        right = {n: self.out_pin_label(e, p) for n, p in enumerate(outs)}
        rows = set(left) | set(right)
        need = max((text_w(left.get(r, "")) + text_w(right.get(r, "")) + 20 for r in rows),
                   default=0)
        title = text_w(box_title(e), bold=True) + 16
        inst = text_w(expr(e.instance)) + 4 if e.instance is not None and e.type_name else 0
        return max(72.0, need, title, inst)

    def width(self, e) -> float:
        """The width an element takes in its column (wire stubs of contacts and coils
        included)."""
        k = e.kind
        if k in BOXES:
            return self.box_width(e)
        if k in ("contact", "coil"):
            return max(64.0, text_w(self.label(e)) + 10)
        if k in ("invar", "outvar", "inoutvar"):
            return max(64.0, text_w(self.label(e)) + 20)
        if k in ("jump", "label", "return"):
            return text_w(mark_text(e), bold=True) + 8
        return 20.0


BOXES = ("fb", "func", "cmp")
_VARIABLE = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)*")
LABEL = 12  # font size of names and pins
OPERAND = 11  # font size of the operands written at box pins


def text_w(s: str, size: float = LABEL, bold: bool = False) -> float:
    """Width of a text in the network's monospace font (bold is as wide)."""
    return text_width(s, size, "mono")


def box_title(e) -> str:
    from ..lang.unparse import expr

    if e.type_name:
        return e.type_name
    return expr(e.instance) if e.instance is not None else "?"  # a METHOD call: inst.Method


def mark_text(e) -> str:
    return {"jump": f">> {e.label}", "label": f"{e.label}:", "return": "RETURN"}.get(e.kind, "")


@functools.lru_cache(maxsize=1)
def _library_pous() -> dict[str, Any]:
    """plclab's library blocks written in ST (BLINKER, ...), by name."""
    from ..lang.frontends.st import parse_library

    return {p.name: p for f in parse_library() for p in f.pous}


def pin_of(pin: str, pins: list[str]) -> str:
    """The drawn pin an input arrives at: a text box's power flow ("") at its first pin."""
    if pin == "":
        return pins[0]
    return pin.upper() if pin.upper() in pins else pins[-1]


def _topological(elems: list, lay: NetworkLayout) -> list:
    from ..lang.lower.network import execution_order

    return execution_order(elems)
