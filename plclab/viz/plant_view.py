"""A plant that reads at a glance: filled water and piston strokes, actuators coloured by state,
switch labels that never overlap, the key value written on the picture, conveyor bottles
(upright and fallen drawn differently) and the plant's counters.

Pure Python: a :class:`Picture` is a list of static :class:`Shape` s and a function giving the
moving shapes at a time; :mod:`plclab.viz.recording` draws them with rerun. World coordinates are
metres with y up (the recording flips y for the screen).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

WATER = (60, 130, 230)
STEEL = (170, 170, 170)
ON = (60, 200, 80)
LAMP_ON = (250, 200, 40)
OFF = (110, 110, 110)
UPRIGHT = (60, 190, 120)
FALLEN = (240, 110, 40)
TEXT = (230, 230, 230)
HOT = (255, 80, 40)
HEATS = {"element": "HEATER"}
"""Geometry lines drawn hot while a signal is TRUE."""
COUNTERS = ("released", "good", "rejected", "fallen_passed", "unfilled_passed", "toppled")


@dataclass
class Shape:
    """``box`` (filled, rotated by ``angle``), ``outline`` (a polyline), ``dot`` (a filled
    circle with an optional label) or ``text`` (a label only). Shapes of one name are drawn
    as one entity (all upright bottles, say)."""

    kind: str
    name: str
    color: tuple[int, int, int] = STEEL
    x: float = 0.0
    y: float = 0.0
    w: float = 0.0
    h: float = 0.0
    angle: float = 0.0
    r: float = 0.0
    label: str = ""
    points: list[tuple[float, float]] = field(default_factory=list)


@dataclass
class Picture:
    static: list[Shape]
    frame: Callable[[int], list[Shape]]  # row index of the trace -> moving shapes
    bounds: tuple[float, float, float, float]  # x0, y0, x1, y1 (world, y up)


def _rect_outline(name: str, x: float, y: float, w: float, h: float,
                  color=STEEL) -> Shape:
    pts = [(x, y + h), (x, y), (x + w, y), (x + w, y + h)]
    return Shape("outline", name, color, points=pts)


def _fmt(v: float, unit: str) -> str:
    a = abs(v)
    txt = f"{v:.0f}" if a >= 100 else f"{v:.1f}" if a >= 10 else f"{v:.2f}"
    return f"{txt} {unit}".strip()


def picture(trace: Any, plant: Any, key: tuple[str, str, str, bool] | None = None
            ) -> Picture | None:
    """The picture of ``plant`` (an instance from :mod:`plants`) for ``trace``; ``key`` is the
    (column, label, unit, whole-number) whose current value is written above the plant."""
    try:
        geo = plant.geometry() or {}
    except Exception:  # noqa: BLE001 - a picture is optional
        geo = {}
    cols = trace.columns
    info = trace.meta.get("signal_info", {}) or {}
    units = trace.meta.get("units", {}) or {}
    static: list[Shape] = []
    moving: list[Callable[[int], list[Shape]]] = []
    xs: list[float] = []
    ys: list[float] = []
    drawn: set[str] = set()

    def extent(x0: float, y0: float, x1: float, y1: float) -> None:
        xs.extend((x0, x1))
        ys.extend((y0, y1))

    def val(col: str, i: int) -> float:
        return float(cols[col][i])

    for s in geo.get("shapes", []):
        kind, name = s.get("type"), s.get("name", "")
        if kind == "rect":
            if name == "bin":  # open at the top
                static.append(_rect_outline(name, s["x"], s["y"], s["w"], s["h"]))
            else:
                pts = [(s["x"], s["y"]), (s["x"] + s["w"], s["y"]),
                       (s["x"] + s["w"], s["y"] + s["h"]), (s["x"], s["y"] + s["h"]),
                       (s["x"], s["y"])]
                static.append(Shape("outline", name, STEEL, points=pts))
            extent(s["x"], s["y"], s["x"] + s["w"], s["y"] + s["h"])
        elif kind == "line":
            pts = [(s["x0"], s["y0"]), (s["x1"], s["y1"])]
            drive = HEATS.get(name)
            if drive in cols:  # a heating element glows while it is switched on
                moving.append(lambda i, pts=pts, c=cols[drive], name=name: [Shape(
                    "outline", name, HOT if c[i] else STEEL, points=pts)])
            else:
                static.append(Shape("outline", name, STEEL, points=pts))
            extent(s["x0"], s["y0"], s["x1"], s["y1"])
        elif kind in ("mark", "circle"):
            extent(s["x"], s["y"], s["x"], s["y"])
    if xs:
        size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-3)
    else:
        size = 1.0
        extent(0.0, 0.0, 1.0, 0.5)
    dot = 0.025 * size

    placed: list[tuple[float, float]] = []
    for s in geo.get("shapes", []):
        kind, name = s.get("type"), s.get("name", "")
        if kind == "circle":  # a fan (named by its contactor) or a vessel (a drum)
            r = float(s.get("r", dot))
            if name in cols and trace.kind(name) == "bool":
                r = max(r, 0.06 * size)  # a fan big enough to see its blades turn
            static.append(Shape("outline", f"{name}_rim", STEEL,
                                points=_circle(s["x"], s["y"], r)))
            extent(s["x"] - r, s["y"] - r - 0.1 * size, s["x"] + r, s["y"] + r)
            if name in cols and trace.kind(name) == "bool":
                drawn.add(name)
                moving.append(_fan(trace, name, s["x"], s["y"], r, 0.06 * size))
            else:
                level = _level_signal(trace, info)
                if level is not None:  # its value left of everything drawn so far
                    lx = min(xs) - LABEL_EM * size * (len(level) + 8) / 2
                    moving.append(_drum_water(trace, level, info, units, s["x"], s["y"], r,
                                              lx))
                    extent(lx - LABEL_EM * size * (len(level) + 8) / 2, s["y"], s["x"],
                           s["y"])
            continue
        if kind != "mark":
            continue
        r = float(s.get("r", dot))
        x = s["x"] + (3 * dot if kind == "mark" else 0.0)
        while any(abs(x - px) < 0.12 * size and abs(s["y"] - py) < 0.1 * size
                  for px, py in placed):
            x += 0.15 * size  # a label must not sit on its neighbour's
        placed.append((x, s["y"]))
        extent(x, s["y"], x, s["y"])
        if name in cols and trace.kind(name) == "bool":
            drawn.add(name)
            lamp = info.get(name, {}).get("kind") == "lamp"
            moving.append(_switch(name, x, s["y"], r, cols[name], lamp))
        else:
            static.append(Shape("dot", name, (120, 120, 120), x, s["y"], r=dot * 0.6,
                                label=name))

    fill = geo.get("fill")
    if fill and fill.get("signal") in cols:
        sig = fill["signal"]
        x0, y0, w = fill["x"], fill["y"], fill["w"]
        u = units.get(sig, "")

        extent(x0 - 0.3 * size, y0, x0, y0)

        def water(i: int, sig=sig, x0=x0, y0=y0, w=w, u=u) -> list[Shape]:
            h = max(val(sig, i), 0.0)
            return [Shape("box", "water", WATER, x0, y0, w, max(h, 1e-6)),
                    Shape("text", "level_value", TEXT, x0 - 0.15 * size, y0 + h,
                          label=f"{sig} {_fmt(h, u)}")]  # left: the switches are right
        moving.append(water)
    piston = geo.get("piston")
    if piston and piston.get("signal") in cols:
        sig, scale = piston["signal"], float(piston["scale"])
        cyl = next((s for s in geo.get("shapes", []) if s.get("name") == "cylinder"), None)
        cx, cw = ((cyl["x"], cyl["w"]) if cyl else (-0.05, 0.1))

        def stroke(i: int, sig=sig, scale=scale, cx=cx, cw=cw) -> list[Shape]:
            p = val(sig, i)
            y = p * scale
            return [Shape("box", "piston", WATER, cx + 0.1 * cw, min(y, 0.0), 0.8 * cw,
                          max(abs(y), 1e-6)),
                    Shape("text", "position_value", TEXT, cx + cw / 2, y - 0.02,
                          label=f"{sig} {_fmt(p, units.get(sig, ''))}")]
        moving.append(stroke)

    bottle = geo.get("bottle")
    if bottle:
        moving.append(_bottles(trace, bottle))
        counters = [(c, k) for k in COUNTERS for c in (k, f"snapshot:{k}") if c in cols]
        if counters:
            bx, by = (min(xs) + max(xs)) / 2, max(ys) + 0.12 * size

            def count_text(i: int, counters=counters, bx=bx, by=by) -> list[Shape]:
                txt = " · ".join(f"{k.replace('_', ' ')} {int(val(c, i))}"
                                for c, k in counters if not math.isnan(val(c, i)))
                return [Shape("text", "counters", TEXT, bx, by, label=txt)]
            moving.append(count_text)
            extent(bx, by, bx, by)

    # a light curtain beside the plant, the operator's hands under it (safety inputs that
    # are the story of a press): drawn as what they are, not as lamps
    curtains = [n for n, d in info.items() if d.get("type") == "bool" and n in cols
                and "CURTAIN" in n.upper()]
    for n in curtains:
        cx = min(xs) - 0.4 * size
        moving.append(_curtain(n, cx, min(ys), max(ys), cols[n], size))
        drawn.add(n)
        extent(cx - 0.1 * size, min(ys), cx, max(ys) + 0.1 * size)
    hands = [n for n, d in info.items() if d.get("type") == "bool" and n in cols
             and n.upper().startswith("HAND") and n not in drawn]
    hy = min(ys) - 0.18 * size
    x_a, x_b = min(xs), max(xs)
    for k, n in enumerate(hands):  # spread out under the plant, left hand left
        hx = (x_a + x_b) / 2 + 0.9 * size * (k - (len(hands) - 1) / 2)
        moving.append(_hand(n, hx, hy, 1.8 * dot, cols[n]))
        drawn.add(n)
        extent(hx - 0.1 * size, hy - 0.1 * size, hx + 0.1 * size, hy)
    # actuators, lamps and panel buttons the geometry does not place: a row under the plant
    kinds = ("actuator", "lamp") if geo.get("shapes") else ("actuator", "lamp", "sensor", "panel")
    row = [n for n, d in info.items() if d.get("type") == "bool" and n in cols
           and n not in drawn and d.get("kind") in kinds]
    analog_act = [n for n, d in info.items() if d.get("type") == "real" and n in cols
                  and d.get("kind") in ("actuator", "panel")]
    mid = (min(xs) + max(xs)) / 2
    per_row = 4
    longest = max((len(n) for n in row), default=0) + 4  # "NAME off", right of its dot
    step = max((max(xs) - min(xs)) / min(max(len(row), 1), per_row),
               0.55 * (max(ys) - min(ys)),  # tall, narrow vessels need a wider row
               LABEL_EM * longest * (max(ys) - min(ys)))  # labels never touch
    width = step * min(len(row), per_row)
    x_lo, x_hi = min(min(xs), mid - width / 2), max(max(xs), mid + width / 2)
    y_row = min(ys) - 0.12 * size
    gap = ROW_GAP * size  # a dot and its label under the one above, not on it
    for k, n in enumerate(row):
        r, c = divmod(k, per_row)
        in_row = min(per_row, len(row) - r * per_row)
        x = mid + step * (c + 0.5 - in_row / 2)
        lamp = info[n].get("kind") == "lamp"
        stagger = 0.45 * gap * (c % 2)  # neighbours' labels side by side never touch
        moving.append(_switch(n, x, y_row - r * 1.5 * gap - stagger, 1.6 * dot, cols[n],
                              lamp))
    if row:
        y_row -= 1.5 * gap * ((len(row) - 1) // per_row) + (0.45 * gap if len(row) > 1
                                                            else 0.0)
        extent(x_lo, y_row - 0.08 * size, x_hi, y_row)
    if analog_act:
        y_txt = y_row - 0.12 * size

        def act_text(i: int, names=analog_act, y=y_txt) -> list[Shape]:
            txt = "  ".join(f"{n} {_fmt(val(n, i), units.get(n, ''))}" for n in names)
            return [Shape("text", "actuator_values", TEXT, (x_lo + x_hi) / 2, y, label=txt)]
        moving.append(act_text)
        extent(x_lo, y_txt - 0.05 * size, x_hi, y_txt)
    if key and key[0] in cols and not (fill and fill.get("signal") == key[0]) \
            and not (piston and piston.get("signal") == key[0]):
        ky = max(ys) + 0.22 * size  # above the plant, not on its outline
        kc, kl, ku, whole = key

        def key_text(i: int, kc=kc, kl=kl, ku=ku, ky=ky, whole=whole) -> list[Shape]:
            v = val(kc, i)
            txt = f"{int(v)} {ku}".strip() if whole and not math.isnan(v) else _fmt(v, ku)
            return [Shape("text", "key_value", TEXT, mid, ky, label=f"{kl} {txt}")]
        moving.append(key_text)
        extent(x_lo, ky, x_hi, ky + 0.05 * size)

    def frame(i: int) -> list[Shape]:
        out: list[Shape] = []
        for f in moving:
            out += f(i)
        return out

    pad = 0.12 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-3)
    bounds = (min(xs) - pad, min(ys) - pad, max(xs) + 2.5 * pad, max(ys) + pad)
    return Picture(static, frame, bounds)


ROW_GAP = 0.2
"""Distance of two rows of actuators, a fraction of the plant's size."""
LABEL_EM = 0.045
"""Width of one label character as a fraction of the plant's size (the viewer's labels are
drawn at a fixed screen size; a plant about 600 px wide)."""


def _circle(x: float, y: float, r: float, n: int = 48) -> list[tuple[float, float]]:
    return [(x + r * math.cos(2 * math.pi * k / n), y + r * math.sin(2 * math.pi * k / n))
            for k in range(n + 1)]


def _fan(trace: Any, name: str, x: float, y: float, r: float, gap: float,
         rev_per_s: float = 0.5):
    """A fan: three blades turning while its contactor is ON (the angle is the time it has
    run so far), green when on, grey when off; its state (ON, off) written under it."""
    import numpy as np

    on = np.asarray(trace.columns[name], dtype=bool)
    t = np.asarray(trace.time, dtype=float)
    dt = np.diff(t, prepend=t[0] if len(t) else 0.0)
    turned = np.cumsum(on * dt) * 2 * math.pi * rev_per_s

    def f(i: int) -> list[Shape]:
        a = float(turned[i])
        c = ON if on[i] else OFF
        blades = [Shape("outline", f"{name}/blades", c, points=[
            (x, y), (x + 0.9 * r * math.cos(a + k * 2 * math.pi / 3),
                     y + 0.9 * r * math.sin(a + k * 2 * math.pi / 3))]) for k in range(3)]
        return blades + [Shape("text", f"{name}/state", TEXT, x, y + r + gap,
                               label=f"{name} {'ON' if on[i] else 'off'}")]
    return f


def _level_signal(trace: Any, info: dict[str, Any]) -> str | None:
    """The plant's level (a real sensor named ...LEVEL with a range), for a vessel drawn as a
    circle."""
    for n, d in info.items():
        if d.get("type") == "real" and "LEVEL" in n.upper() and n in trace.columns \
                and len(d.get("range") or ()) == 2 and d["range"][1] > d["range"][0]:
            return n
    return None


def _drum_water(trace: Any, sig: str, info: dict[str, Any], units: dict[str, str], x: float,
                y: float, r: float, label_x: float, slices: int = 10):
    """Water in a round drum: horizontal slices of the circle up to the level's share of its
    range; the level written left of the drum, outside it."""
    lo, hi = (float(v) for v in info[sig]["range"])
    col = trace.columns[sig]
    unit = units.get(sig, "")

    def f(i: int) -> list[Shape]:
        v = float(col[i])
        frac = min(max((v - lo) / (hi - lo), 0.0), 1.0) if v == v else 0.0
        top = y - r + 2 * r * frac
        out = []
        h = 2 * r / slices
        yb = y - r
        while yb < top - 1e-9:
            yt = min(yb + h, top)
            ym = (yb + yt) / 2
            half = math.sqrt(max(r * r - (ym - y) ** 2, 0.0)) * 0.96
            out.append(Shape("box", "water", WATER, x - half, yb, 2 * half, yt - yb))
            yb = yt
        return out + [Shape("text", "level_value", TEXT, label_x, y,
                            label=f"{sig} {_fmt(v, unit)}")]
    return f


def _curtain(name: str, x: float, y0: float, y1: float, col: Any, size: float):
    """A light curtain: a column of beams, green while the field is clear (TRUE), red and
    broken in the middle while something is in it."""

    def f(i: int) -> list[Shape]:
        clear = bool(col[i])
        beams = []
        n = 7
        for k in range(n):
            yy = y0 + (y1 - y0) * (k + 0.5) / n
            if not clear and k in (n // 2 - 1, n // 2, n // 2 + 1):
                continue  # the broken beams: the hand is there
            beams.append(Shape("outline", f"{name}/beams", ON if clear else HOT,
                               points=[(x - 0.06 * size, yy), (x, yy)]))
        return beams + [Shape("text", f"{name}/state", TEXT, x - 0.03 * size,
                              y1 + 0.12 * size,
                              label=f"{name} {'clear' if clear else 'BROKEN'}")]
    return f


def _hand(name: str, x: float, y: float, r: float, col: Any):
    """A two-hand button with the operator's hand on it (green) or off it (grey)."""

    def f(i: int) -> list[Shape]:
        on = bool(col[i])
        return [Shape("dot", name, ON if on else OFF, x, y, r=r,
                      label=f"{name} {'pressed' if on else 'released'}")]
    return f


def _switch(name: str, x: float, y: float, r: float, col: Any, lamp: bool):
    on_color = LAMP_ON if lamp else ON

    def f(i: int) -> list[Shape]:
        on = bool(col[i])
        return [Shape("dot", name, on_color if on else OFF, x, y, r=r,
                      label=f"{name} {'ON' if on else 'off'}")]
    return f


def _bottles(trace: Any, bottle: dict[str, Any]):
    """Upright bottles as green boxes, fallen ones (tilted more than 60 degrees) orange."""
    prefix = bottle.get("prefix", "bottle")
    slots = [k for k in range(int(bottle.get("slots", 0))) if f"{prefix}{k}.x" in trace.columns]
    w, h = float(bottle["w"]), float(bottle["h"])
    cols = trace.columns

    def f(i: int) -> list[Shape]:
        up: list[Shape] = []
        down: list[Shape] = []
        for k in slots:
            x = float(cols[f"{prefix}{k}.x"][i])
            if math.isnan(x):
                continue
            y = float(cols[f"{prefix}{k}.y"][i])
            a = float(cols[f"{prefix}{k}.angle"][i]) if f"{prefix}{k}.angle" in cols else 0.0
            fallen = abs(math.sin(a)) > math.sin(math.radians(60))
            (down if fallen else up).append(Shape(
                "box", "bottles/fallen" if fallen else "bottles/upright",
                FALLEN if fallen else UPRIGHT, x - w / 2, y - h / 2, w, h, a))
        return up + down
    return f
