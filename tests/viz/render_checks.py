"""Checks that read a rendered SVG back: what an engineer looking at a CODESYS or OpenPLC
Editor drawing takes for granted (used by tests/viz/test_render_checks.py).

Each check returns a list of failures (empty: the picture passes), so a test can both assert
a render passes and that a wrong picture is caught."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from plclab.viz.text_width import text_width

SVG = "{http://www.w3.org/2000/svg}"


def _f(el, name: str, default: float = 0.0) -> float:
    v = el.get(name)
    return float(v) if v not in (None, "") else default


def wires(root: ET.Element) -> list[tuple[float, float, float, float]]:
    """Every wire line (not rails, contacts' plates, bars or pin stubs of operands)."""
    out = []
    for ln in root.iter(f"{SVG}line"):
        style = (ln.get("stroke-width") or "") + (ln.get("class") or "")
        if "4" == ln.get("stroke-width") or "bar" in style or ln.get("stroke-width") == "2":
            continue
        out.append((_f(ln, "x1"), _f(ln, "y1"), _f(ln, "x2"), _f(ln, "y2")))
    return out


def doubled_lines(svg: str) -> list[str]:
    """Two wires on one line that overlap, or two parallel wires closer than 5 px side by
    side (the doubled junction lines of a branch drawn once per wire)."""
    root = ET.fromstring(svg)
    vs = [(x1, min(y1, y2), max(y1, y2)) for x1, y1, x2, y2 in wires(root) if x1 == x2]
    hs = [(y1, min(x1, x2), max(x1, x2)) for x1, y1, x2, y2 in wires(root) if y1 == y2]
    bad = []
    for kind, segs in (("vertical", vs), ("horizontal", hs)):
        for i, (a, lo, hi) in enumerate(segs):
            for b, lo2, hi2 in segs[i + 1:]:
                overlap = min(hi, hi2) - max(lo, lo2)
                iec_double = kind == "horizontal" and abs(abs(a - b) - 3) < 0.1 and \
                    abs(lo - lo2) < 0.5 and abs(hi - hi2) < 0.5  # an SFC simultaneous branch
                if abs(a - b) < 5 and overlap > 1 and not iec_double:
                    bad.append(f"{kind} wires at {a:g} and {b:g} overlap over {overlap:g} px")
    return bad


def _font(el, inherited: str) -> tuple[float, str]:
    size = _f(el, "font-size", 12.0)
    fam = el.get("font-family") or inherited
    bold = el.get("font-weight") == "bold" or "name" in (el.get("class") or "").split()
    return size, "mono" if "Mono" in fam else "sans-bold" if bold else "sans"


def text_boxes(svg: str) -> list[tuple[str, float, float, float, float]]:
    """(text, left, top, right, bottom) of every text, its width measured in its font."""
    root = ET.fromstring(svg)
    fam = root.get("font-family") or ""
    out = []
    for t in root.iter(f"{SVG}text"):
        s = "".join(t.itertext())
        if not s.strip() or "note" in (t.get("class") or ""):
            continue
        size, font = _font(t, fam)
        w = text_width(s, size, font)
        x, y = _f(t, "x"), _f(t, "y")
        anchor = t.get("text-anchor") or "start"
        left = x - w / 2 if anchor == "middle" else x - w if anchor == "end" else x
        out.append((s, left, y - 0.75 * size, left + w, y + 0.2 * size))
    return out


def rects(svg: str) -> list[tuple[float, float, float, float]]:
    root = ET.fromstring(svg)
    out = []
    for r in root.iter(f"{SVG}rect"):
        if r.get("width", "").endswith("%"):
            continue
        x, y = _f(r, "x"), _f(r, "y")
        out.append((x, y, x + _f(r, "width"), y + _f(r, "height")))
    return out


def text_overflows(svg: str) -> list[str]:
    """A text that starts inside a box (block, step, action, variable) and ends outside it,
    or two texts that overlap."""
    bad = []
    boxes = text_boxes(svg)
    rs = rects(svg)
    for s, l, t, r, b in boxes:
        cx, cy = l + 1, (t + b) / 2
        inside = [q for q in rs if q[0] <= cx <= q[2] and q[1] <= cy <= q[3]]
        if inside:  # the innermost box holding the text's start
            q = min(inside, key=lambda q: (q[2] - q[0]) * (q[3] - q[1]))
            if l < q[0] - 0.5 or r > q[2] + 0.5:
                bad.append(f"{s!r} ({l:.0f}..{r:.0f}) overflows its box ({q[0]:.0f}..{q[2]:.0f})")
    for i, (s, l, t, r, b) in enumerate(boxes):
        for s2, l2, t2, r2, b2 in boxes[i + 1:]:
            if min(r, r2) - max(l, l2) > 1 and min(b, b2) - max(t, t2) > 1:
                bad.append(f"{s!r} and {s2!r} overlap")
    return bad


def arrows_on_lines(svg: str) -> list[str]:
    """A jump arrow whose tip or target name lies on (within 6 px of) a horizontal line:
    the arrow reads as landing on a convergence."""
    root = ET.fromstring(svg)
    hs = [(y1, min(x1, x2), max(x1, x2)) for x1, y1, x2, y2 in wires(root) if y1 == y2]
    names = {(round(l), round(b)): (s, l, t, r, b) for s, l, t, r, b in text_boxes(svg)}
    bad = []
    for p in root.iter(f"{SVG}path"):
        if p.get("class") != "jump":
            continue
        nums = [float(v) for v in re.findall(r"-?[\d.]+", p.get("d", ""))]
        tip_x, tip_y = nums[4], nums[5]
        for y, lo, hi in hs:
            if lo - 6 <= tip_x <= hi + 6 and abs(y - tip_y) < 6:
                bad.append(f"the arrow to {p.get('data-target')} ends on a line at y={y:g}")
        for s, l, t, r, b in names.values():
            if s != p.get("data-target") or abs(l - tip_x - 10) > 1:
                continue
            for y, lo, hi in hs:
                if t - 2 <= y <= b + 2 and lo < r and hi > l:
                    bad.append(f"a line at y={y:g} runs through the jump target {s!r}")
    return bad


def box_operands(svg: str) -> dict[int, dict[str, list[str]]]:
    """Box (its data-elem id) -> pin -> the operands drawn at it (inputs and outputs)."""
    root = ET.fromstring(svg)
    out: dict[int, dict[str, list[str]]] = {}
    for g in root.iter(f"{SVG}g"):
        if g.get("class") != "box":
            continue
        pins: dict[str, list[str]] = {}
        for t in g.iter(f"{SVG}text"):
            cls = (t.get("class") or "").split()
            if "operand" in cls:
                pins.setdefault(f"{cls[1]}:{t.get('data-pin')}", []).append(
                    (t.text or "").split(" = ")[0])
        out[int(g.get("data-elem", "-1"))] = pins
    return out


def missing_operands(svg: str, elems: list) -> list[str]:
    """Each parameter written in a text box (``PT:=T#5s``, ``a, b -> c``, ``CV=>n``) must be
    drawn at a pin of that box, inputs left and outputs right."""
    from plclab.lang.unparse import expr

    drawn = box_operands(svg)
    bad = []
    for e in elems:
        if e.kind not in ("fb", "func", "cmp"):
            continue
        pins = drawn.get(e.id)
        if pins is None:
            bad.append(f"box {e.text!r} not drawn")
            continue
        ins = [v for k, vs in pins.items() if k.startswith("in:") for v in vs]
        outs = [v for k, vs in pins.items() if k.startswith("out:") for v in vs]
        for a in e.args:
            if a.value is None:
                continue
            side = outs if a.output else ins
            if expr(a.value) not in side:
                bad.append(f"{e.text!r}: operand {expr(a.value)} not drawn at a pin")
        for t in e.targets:
            if not any(expr(t) in o.split(", ") for o in pins.get("out:OUT", [])):
                bad.append(f"{e.text!r}: result {expr(t)} not drawn at OUT")
        if len(ins) != sum(1 for a in e.args if not a.output and a.value is not None):
            bad.append(f"{e.text!r}: {len(ins)} input operands drawn")
    return bad
