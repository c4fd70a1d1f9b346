"""A still SVG picture of each plant for the site, drawn from the same shapes the rerun
recording uses (:func:`plclab.viz.plant_view.picture`), at the plant's state after reset."""

from __future__ import annotations

import math
from html import escape
from typing import Any


class _Still:
    """A one-row stand-in for a Trace: every signal at its value after reset."""

    def __init__(self, plant: Any) -> None:
        self.columns = {name: [plant.read(name)] for name in plant.signals}
        self.time = [0.0]  # the one row is at t = 0 (a fan's blades stand still)
        self.meta: dict[str, Any] = {"units": {n: s.unit for n, s in plant.signals.items()
                                               if getattr(s, "unit", "")}}

    def kind(self, name: str) -> str:
        return "bool" if isinstance(self.columns[name][0], bool) else "real"


def _rgb(c: tuple[int, int, int]) -> str:
    return f"rgb({c[0]},{c[1]},{c[2]})"


def plant_svg(plant: Any, width: int = 480) -> str:
    """The SVG text of ``plant`` (an instance from :mod:`plants`), or a signal panel for a
    plant without geometry."""
    from plclab.viz.plant_view import picture

    pic = picture(_Still(plant), plant)
    if pic is None or len(pic.static) + len(pic.frame(0)) < 2:  # no geometry to draw
        return _panel(plant, width)
    x0, y0, x1, y1 = pic.bounds
    scale = width / max(x1 - x0, 1e-9)
    height = max(60, int((y1 - y0) * scale))
    font = max(10.0, 0.035 * width)

    def px(x: float, y: float) -> tuple[float, float]:
        return (x - x0) * scale, (y1 - y) * scale

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" role="img" aria-label="{escape(plant.title)}">',
           f'<rect width="{width}" height="{height}" fill="#1e2430"/>']
    for s in pic.static + pic.frame(0):
        col = _rgb(s.color)
        if s.kind == "box":
            cx, cy = px(s.x + s.w / 2, s.y + s.h / 2)
            w, h = s.w * scale, s.h * scale
            out.append(f'<rect x="{cx - w / 2:.1f}" y="{cy - h / 2:.1f}" width="{w:.1f}" '
                       f'height="{h:.1f}" fill="{col}" transform="rotate('
                       f'{-math.degrees(s.angle):.1f} {cx:.1f} {cy:.1f})"/>')
        elif s.kind == "outline" and s.points:
            pts = " ".join(f"{a:.1f},{b:.1f}" for a, b in (px(*p) for p in s.points))
            out.append(f'<polyline points="{pts}" fill="none" stroke="{col}" '
                       'stroke-width="3" stroke-linejoin="round"/>')
        elif s.kind == "dot":
            cx, cy = px(s.x, s.y)
            out.append(f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{max(s.r * scale, 3):.1f}" '
                       f'fill="{col}"/>')
            if s.label:
                out.append(f'<text x="{cx + max(s.r * scale, 3) + 4:.1f}" y="{cy + font / 3:.1f}" '
                           f'font-size="{font:.0f}" fill="#e6e6e6" font-family="sans-serif">'
                           f'{escape(s.label)}</text>')
        elif s.kind == "text" and s.label:
            cx, cy = px(s.x, s.y)
            out.append(f'<text x="{cx:.1f}" y="{cy:.1f}" font-size="{font:.0f}" '
                       f'fill="{_rgb(s.color)}" font-family="sans-serif" text-anchor="middle">'
                       f'{escape(s.label)}</text>')
    out.append("</svg>")
    return "\n".join(out)


def _panel(plant: Any, width: int) -> str:
    """Sensors left, actuators right, the plant in the middle: for plants without geometry."""
    sigs = plant.signals
    left = [n for n, s in sigs.items() if s.kind == "sensor"]
    right = [n for n, s in sigs.items() if s.kind != "sensor"]
    rows = max(len(left), len(right), 1)
    height = 40 + 22 * rows
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" role="img" aria-label="{escape(plant.title)}">',
           f'<rect width="{width}" height="{height}" fill="#1e2430"/>',
           f'<rect x="{width * 0.35:.0f}" y="20" width="{width * 0.3:.0f}" height="{height - 40}" '
           'fill="none" stroke="#aaa" stroke-width="3"/>',
           f'<text x="{width / 2:.0f}" y="{height / 2:.0f}" fill="#e6e6e6" font-size="14" '
           f'text-anchor="middle" font-family="sans-serif">{escape(plant.name)}</text>']
    for i, n in enumerate(left):
        out.append(f'<text x="{width * 0.33:.0f}" y="{36 + 22 * i}" fill="#8fd" font-size="12" '
                   f'text-anchor="end" font-family="sans-serif">{escape(n)} &#8592;</text>')
    for i, n in enumerate(right):
        out.append(f'<text x="{width * 0.67:.0f}" y="{36 + 22 * i}" fill="#fd8" font-size="12" '
                   f'font-family="sans-serif">&#8592; {escape(n)}</text>')
    out.append("</svg>")
    return "\n".join(out)
