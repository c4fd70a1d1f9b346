"""The student's failure diagram drawn straight to a PNG with Pillow (no matplotlib): a thin
renderer of a :class:`plclab.viz.failure_model.FailureDiagram` (ADR 0069).

The grader draws a diagram for every failed criterion of every failing submission, and with
matplotlib a small diagram cost about 75 ms of CPU (building the artists, laying out and
rasterising some twenty texts, encoding): the largest part of a failing submission's
grading after the simulation. This draws the same picture as
:func:`plclab.viz.failure_diagram.failure_figure` at 72 dpi -- the same description and the
same geometry (:meth:`~plclab.viz.failure_model.FailureDiagram.frame`), rows as bands of one plot, square waves for BOOLs, labelled bus
segments for small integers, lines for analog values with their range, thresholds dotted and
labelled, failure markers dashed across all rows with labels that never overlap, the time
axis with ticks -- in a few milliseconds (ADR 0033).

Lines are drawn at :data:`SCALE` times the size and reduced (a box filter), so they are
smooth; text uses DejaVu Sans (matplotlib's own font) when it is installed.
"""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .failure_model import PAD, FailureDiagram, Row, bool_rgb, spread

DPI = 72
SCALE = 2
"""Drawn at twice the size, then reduced: smooth lines and text."""
LABEL_MARGIN = 3 * SCALE  # supersampled pixels a marker label keeps from the right edge

GREEN = (44, 160, 44)
GREEN_FILL = (223, 241, 223)  # tab:green at alpha 0.15 on white
BLUE = (31, 119, 180)
ORANGE = (255, 127, 14)
RED = (214, 39, 40)
PURPLE = (148, 103, 189)
GRID = (217, 217, 217)
SPAN = (237, 242, 250)  # failure_diagram.SPAN_RGB: the window a criterion checks
BAND = (255, 237, 217)  # failure_diagram.BAND_RGB: a value band a criterion checks
RANGE = (102, 102, 102)
BLACK = (0, 0, 0)


@functools.lru_cache(maxsize=16)
def font(size_px: int) -> Any:
    """DejaVu Sans at ``size_px`` pixels (matplotlib's font file when it is installed,
    Pillow's own font otherwise)."""
    import io

    from PIL import ImageFont

    data = _font_bytes()
    if data:
        try:  # from memory: no file a forked grading child would share its offset with
            return ImageFont.truetype(io.BytesIO(data), size_px)
        except OSError:
            pass
    return ImageFont.load_default(size=size_px)


@functools.lru_cache(maxsize=1)
def _font_bytes() -> bytes | None:
    """The bytes of matplotlib's DejaVu Sans (None when matplotlib is not installed)."""
    import importlib.util

    spec = importlib.util.find_spec("matplotlib")
    for root in (spec.submodule_search_locations or []) if spec else []:
        path = os.path.join(root, "mpl-data", "fonts", "ttf", "DejaVuSans.ttf")
        try:
            with open(path, "rb") as fh:
                return fh.read(4 << 20)
        except OSError:
            continue
    return None


def nice_ticks(lo: float, hi: float, nbins: int = 8) -> list[float]:
    """Tick positions inside [lo, hi] at a 'nice' step (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 times a
    power of ten), at most ``nbins`` intervals: the steps of matplotlib's
    ``MaxNLocator(nbins=8)``, which the matplotlib drawing uses."""
    span = hi - lo
    if not span > 0 or not math.isfinite(span):
        return [lo]
    raw = span / nbins
    mag = 10 ** math.floor(math.log10(raw))
    step = next((k * mag for k in (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10) if k * mag >= raw * (1 - 1e-9)),
                10 * mag)
    first = math.ceil(lo / step - 1e-9) * step
    out = []
    k = 0
    while first + k * step <= hi + step * 1e-9:
        out.append(first + k * step)
        k += 1
    return out


def tick_labels(ticks: Sequence[float]) -> list[str]:
    """Labels with one number of decimals for all (``7.5 10.0 12.5``, ``112 120``)."""
    decimals = 0
    for t in ticks:
        while decimals < 6 and abs(round(t, decimals) - t) > 1e-9 * max(1.0, abs(t)):
            decimals += 1
    return [f"{t:.{decimals}f}" if abs(t) >= 0.5 * 10 ** -decimals else f"{0:.{decimals}f}"
            for t in ticks]


class _Canvas:
    """Inches and data coordinates to the pixels of the supersampled image."""

    def __init__(self, width_in: float, height_in: float, record: bool = False) -> None:
        from PIL import Image, ImageDraw

        self.k = DPI * SCALE
        self.w = int(width_in * DPI) * SCALE  # whole pixels as matplotlib's Agg counts them
        self.h = int(height_in * DPI) * SCALE
        self.img = Image.new("RGB", (self.w, self.h), (255, 255, 255))
        self.draw = ImageDraw.Draw(self.img)
        self.record = record  # keep each text drawn with its box (for tests and readers)
        self.texts: list[tuple[str, tuple[float, float, float, float]]] = []

    def px(self, points: float) -> int:
        """A line width in points as whole pixels (at least one)."""
        return max(1, int(round(points * SCALE)))

    def text(self, xy: tuple[float, float], text: str, size_pt: float, fill: Any,
             anchor: str) -> None:
        f = font(int(round(size_pt * SCALE)))
        self.draw.text(xy, text, font=f, fill=fill, anchor=anchor)
        if self.record:
            self.texts.append((text, self.draw.textbbox(xy, text, font=f, anchor=anchor)))

    def dashed(self, a: tuple[float, float], b: tuple[float, float], fill: Any, width: int,
               on: float, off: float) -> None:
        """A straight dashed line (``on``/``off`` in pixels)."""
        (x0, y0), (x1, y1) = a, b
        length = math.hypot(x1 - x0, y1 - y0)
        if length <= 0:
            return
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        s = 0.0
        while s < length:
            e = min(length, s + on)
            self.draw.line([(x0 + ux * s, y0 + uy * s), (x0 + ux * e, y0 + uy * e)],
                           fill=fill, width=width)
            s = e + off


def label_place(cv: _Canvas, x: float, y: float, label: str, size_pt: float = 7,
                right: float | None = None) -> tuple[float, str]:
    """Where a failure marker's ``label`` goes for the line at pixel ``x``: right of the line
    (anchor ``ls``), or, when its box would pass ``right`` (the plot's right edge; default
    the picture's edge less a margin), right-aligned left of the line (``rs``), so the label
    never runs off the plot or is cut at the picture's edge."""
    f = font(int(round(size_pt * SCALE)))
    gap = 2 * SCALE
    edge = min(cv.w - LABEL_MARGIN, right if right is not None else cv.w)
    if cv.draw.textbbox((x + gap, y), label, font=f, anchor="ls")[2] <= edge:
        return x + gap, "ls"
    return max(min(x - gap, edge), cv.draw.textlength(label, font=f)), "rs"


def label_box(cv: _Canvas, x: float, y: float, label: str, size_pt: float = 7,
              right: float | None = None) -> tuple[float, float, float, float]:
    """The pixel box of the label :func:`label_place` puts at the line at ``x``."""
    at, anchor = label_place(cv, x, y, label, size_pt, right)
    return cv.draw.textbbox((at, y), label, font=font(int(round(size_pt * SCALE))),
                            anchor=anchor)


def failure_png(d: FailureDiagram, path: str | os.PathLike | None = None,
                drawn: list[tuple[str, tuple[int, int, int, int]]] | None = None) -> bytes:
    """The PNG of the description ``d`` (72 dpi). Writes ``path`` when given; returns the
    PNG's bytes. ``drawn``, when given, receives every text drawn with its pixel box in the
    PNG (for tests: which items are there, and where). Draws ``d`` and nothing else."""
    import io

    lo, hi, width = d.lo, d.hi, d.width
    h_in, left, right_in, frac = d.frame()
    cv = _Canvas(width, h_in, record=drawn is not None)
    ax_l = left * cv.w
    ax_r = (1 - right_in / width) * cv.w
    ax_b = cv.h - 0.45 / h_in * cv.h  # pixel y of the axes' bottom (y grows down)
    ax_t = ax_b - frac * cv.h
    ax_w, ax_h = ax_r - ax_l, ax_b - ax_t
    total = float(sum(r.height for r in d.rows)) or 1.0
    span = (hi - lo) or 1.0

    def X(t: Any) -> Any:
        return ax_l + (t - lo) / span * ax_w

    def Y(v: Any) -> Any:  # height in the stacked bands (0 .. total) to pixels
        return ax_b - v / total * ax_h

    for a, b, _text in d.spans:  # the window the criterion looks at, under everything
        a, b = max(lo, a if a is not None else lo), min(hi, b if b is not None else hi)
        if b > a:
            cv.draw.rectangle([X(a), ax_t, X(b), ax_b], fill=SPAN)
    top = total
    for r in d.rows:
        base = top - r.height
        y0, y1 = base + PAD * r.height, top - PAD * r.height
        cv.text((ax_l - 0.01 * ax_w, Y((y0 + y1) / 2)), r.caption, 8, BLACK, "rm")
        _row(cv, r, lo, hi, Y(y0), Y(y1), X, ax_l, ax_r, ax_w)
        cv.draw.line([(ax_l, Y(base)), (ax_r, Y(base))], fill=GRID, width=cv.px(0.6))
        top = base
    for t in d.markers:
        x = X(t)
        cv.dashed((x, ax_t), (x, ax_b), RED, cv.px(0.8), 3 * SCALE, 2 * SCALE)
    for t, label, level in d.labels:
        y = ax_b - (1.02 + 0.17 * level / (frac * h_in)) * ax_h
        x, anchor = label_place(cv, X(t), y, label, right=ax_r + 4 * SCALE)
        cv.text((x, y), label, 7, RED, anchor)
    # the time axis: the bottom spine, ticks pointing out, labels, its name
    cv.draw.line([(ax_l, ax_b), (ax_r, ax_b)], fill=BLACK, width=cv.px(0.8))
    ticks = [t for t in nice_ticks(lo, hi) if lo - 1e-9 <= t <= hi + 1e-9]
    tick_len = 3.5 * SCALE
    for t, text in zip(ticks, tick_labels(ticks), strict=True):
        x = X(t)
        cv.draw.line([(x, ax_b), (x, ax_b + tick_len)], fill=BLACK, width=cv.px(0.8))
        cv.text((x, ax_b + tick_len + 3.5 * SCALE), text, 7, BLACK, "mt")
    cv.text(((ax_l + ax_r) / 2, ax_b + tick_len + 3.5 * SCALE + 7 * SCALE * 1.2 + 3.5 * SCALE),
            d.xlabel, 8, BLACK, "mt")
    if d.title:
        cv.text((cv.w / 2, d.TITLE_Y * cv.k), d.title, 10, BLACK, "mt")
    for k, (kind, text) in enumerate(d.header()):
        cv.text((cv.w / 2, d.header_y(k) * cv.k), text, 8,
                BLACK if kind == "caption" else ORANGE if kind == "note" else RANGE, "mt")
    img = cv.img.reduce(SCALE)
    if drawn is not None:
        drawn += [(text, tuple(int(round(c / SCALE)) for c in box))  # type: ignore[misc]
                  for text, box in cv.texts]
    buf = io.BytesIO()
    from PIL.PngImagePlugin import PngInfo

    info = PngInfo()  # the title and the lines under it as PNG text too, for readers and tests
    if d.title:
        info.add_text("Title", d.title)
    if d.texts_under_title():
        info.add_text("Description", "\n".join(text for _, text in d.texts_under_title()))
    img.save(buf, format="PNG", compress_level=6, pnginfo=info)
    data = buf.getvalue()
    if path is not None:
        Path(path).write_bytes(data)
    return data


def _fill(rgb: tuple[int, int, int]) -> tuple[int, int, int]:
    """``rgb`` at alpha 0.15 on white (GREEN_FILL for GREEN)."""
    return tuple(int(round(255 - 0.15 * (255 - c))) for c in rgb)  # type: ignore[return-value]


def _row(cv: _Canvas, r: Row, lo: float, hi: float, py0: float, py1: float, X: Any,
         ax_l: float, ax_r: float, ax_w: float) -> None:
    """One row between the pixel heights py0 (its low edge) and py1 (its high edge)."""
    import numpy as np

    s = r.series
    d = cv.draw
    times = np.asarray(s.times, dtype=float)
    if s.kind == "bool":
        if not len(times):
            return
        on = np.asarray(s.values, dtype=bool)
        rgb = bool_rgb(s.name)  # inputs blue, outputs green: as everywhere
        edges = np.clip(X(np.append(times, hi)), ax_l, ax_r)
        # the step line as one float32 buffer (Pillow reads it without a Python object per
        # point: objects made in a grading child cost page faults, ADR 0033)
        ys = np.where(on, py1, py0)
        step = np.empty((2 * len(on), 2), dtype=np.float32)
        step[0::2, 0], step[1::2, 0] = edges[:-1], edges[1:]
        step[0::2, 1] = step[1::2, 1] = ys
        if on.any():  # the filled ON stretches: one polygon down to the low edge
            area = np.concatenate(([[step[0, 0], py0]], step, [[step[-1, 0], py0]]))
            d.polygon(area.astype(np.float32), fill=_fill(rgb))
        d.line(step, fill=rgb, width=cv.px(1.2))
    elif s.kind == "real":

        vlo, vhi = r.value_range

        def vy(v: float) -> float:
            return py0 + (v - vlo) / (vhi - vlo) * (py1 - py0)

        for a, b, label in r.bands:  # under the curve: shaded, dashed edges, one label
            d.rectangle([ax_l, min(vy(a), vy(b)), ax_r, max(vy(a), vy(b))], fill=BAND)
            for v in (a, b):
                cv.dashed((ax_l, vy(v)), (ax_r, vy(v)), ORANGE, cv.px(0.9), 4 * SCALE,
                          2 * SCALE)
            cv.text((ax_r + 0.005 * ax_w, vy((a + b) / 2)), label, 7, ORANGE, "lm")
        vals = np.asarray(s.values, dtype=float)
        ys = py0 + (vals - vlo) / (vhi - vlo) * (py1 - py0)
        xy = np.stack([X(times), ys], axis=1).astype(np.float32)
        ok = np.isfinite(ys)
        # NaN gaps split the line
        for part in np.split(np.arange(len(ys)), np.flatnonzero(~ok)):
            part = part[ok[part]]
            if len(part) > 1:
                d.line(np.ascontiguousarray(xy[part]), fill=BLUE, width=cv.px(1.0))
        for text, y in zip(r.range_texts(), (py0, py1), strict=True):
            cv.text((ax_l - 0.003 * ax_w, y), text, 6, RANGE, "rm")
        at = spread([vy(value) for value, _ in r.limits], 8.5 * SCALE)  # labels never overlap
        for (value, _label), text, ty in zip(r.limits, r.limit_texts(), at, strict=True):
            y = vy(value)
            lw = 0.9
            cv.dashed((ax_l, y), (ax_r, y), ORANGE, cv.px(lw), 1.0 * lw * SCALE,
                      1.65 * lw * SCALE)
            cv.text((ax_r + 0.005 * ax_w, ty), text, 7, ORANGE, "lm")
    else:
        ch = s.changes()
        mid, dy = (py0 + py1) / 2, (py1 - py0) / 2
        for k, (t, v) in enumerate(ch):
            t_end = ch[k + 1][0] if k + 1 < len(ch) else hi
            dt = min((t_end - t) * 0.08, (hi - lo) * 0.004)
            xs4 = [X(t), X(t + dt), X(t_end - dt), X(t_end)]
            hexagon = [(xs4[0], mid), (xs4[1], mid + dy), (xs4[2], mid + dy), (xs4[3], mid),
                       (xs4[2], mid - dy), (xs4[1], mid - dy), (xs4[0], mid)]
            d.line(hexagon, fill=PURPLE, width=cv.px(1.0))
            if t_end - t > (hi - lo) * 0.02:
                cv.text(((xs4[0] + xs4[3]) / 2, mid), s.label(v), 7, BLACK, "mm")
