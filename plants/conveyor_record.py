"""What a conveyor shows: the snapshot the simulation records every scan and the geometry a
viewer draws.

The snapshot holds the counters, five values of the line (:data:`LINE_KEYS`) and four keys a
bottle slot, ``bottleN.id/x/y/angle`` (NaN when the slot is free). :class:`SnapshotLayout`
works the keys and their places out once, so a scan copies a template instead of looping over
the slots. :func:`line_geometry` reads the conveyor's stations (its public parameters).
"""

from __future__ import annotations

from typing import Any

__all__ = ["LINE_KEYS", "SnapshotLayout", "line_geometry"]

NAN = float("nan")
LINE_KEYS = ("spilled_volume", "filled_volume", "belt_speed", "cylinder", "on_belt")


class SnapshotLayout:
    """The keys of a conveyor's snapshot (*max_bottles* slots) and where each is in a row."""

    def __init__(self, max_bottles: int) -> None:
        self.slot_keys = [(f"bottle{i}.id", f"bottle{i}.x", f"bottle{i}.y", f"bottle{i}.angle")
                          for i in range(max_bottles)]
        self._template: dict[str, float] | None = None  # see snapshot()
        self._row: tuple[Any, ...] | None = None  # see row()

    def snapshot(self, counts: dict[str, int], line: tuple[float, ...], bottles: list[Any]
                 ) -> dict[str, float]:
        """The snapshot: *counts*, the *line* values (in the order of :data:`LINE_KEYS`) and
        every slot's bottle id/x/y/angle (NaN = free) of *bottles*."""
        tmpl = self._template
        if tmpl is None or len(tmpl) != len(counts) + len(LINE_KEYS) + 4 * len(self.slot_keys):
            # the keys in their order, every slot free: one copy a scan instead of a loop
            tmpl = {k: 0.0 for k in counts}
            for k in LINE_KEYS:
                tmpl[k] = 0.0
            for slot_keys in self.slot_keys:
                for k in slot_keys:
                    tmpl[k] = NAN
            self._template = tmpl
        out = tmpl.copy()
        for k, v in counts.items():
            out[k] = float(v)
        for k, v in zip(LINE_KEYS, line, strict=True):
            out[k] = v
        keys = self.slot_keys
        for b in bottles:
            k_id, k_x, k_y, k_a = keys[b.slot]
            out[k_id] = float(b.id)
            out[k_x] = b.x
            out[k_y] = b.y
            out[k_a] = b.angle
        return out

    def row(self, counts: dict[str, int], line: tuple[float, ...], bottles: list[Any]
            ) -> list[float]:
        """:meth:`snapshot`'s values in its keys' order, built without a dict: what the
        simulation records every scan."""
        lay = self._row
        if lay is None:
            keys = list(self.snapshot(counts, line, bottles))
            pos = {k: i for i, k in enumerate(keys)}
            tmpl = [NAN if k.startswith("bottle") else 0.0 for k in keys]
            lay = self._row = (tmpl, [pos[k] for k in counts], pos[LINE_KEYS[0]],
                               [pos[k[0]] for k in self.slot_keys])
        tmpl, count_pos, first, slot_pos = lay
        out = tmpl.copy()
        for i, v in zip(count_pos, counts.values(), strict=True):
            out[i] = float(v)
        out[first:first + len(LINE_KEYS)] = line
        for b in bottles:
            i = slot_pos[b.slot]
            out[i] = float(b.id)
            out[i + 1] = b.x
            out[i + 2] = b.y
            out[i + 3] = b.angle
        return out


def line_geometry(c: Any) -> dict[str, Any]:
    """The belt, the eyes, the reject plate, the nozzle, the fill eye and the bin, and the
    bottles' size and slots: what a viewer draws (``Plant.geometry``)."""
    return {
        "shapes": [
            {
                "type": "line",
                "name": "belt",
                "x0": 0.0,
                "y0": 0.0,
                "x1": c.belt_length,
                "y1": 0.0,
            },
            {"type": "mark", "name": "X1", "x": c.x_eye, "y": c.eye_x1_height},
            {"type": "mark", "name": "X2", "x": c.x_eye, "y": c.eye_x2_height},
            {
                "type": "rect",
                "name": "reject_plate",
                "x": c.x_reject - c.plate_width / 2,
                "y": 0.0,
                "w": c.plate_width,
                "h": c.bottle_height,
            },
            {
                "type": "mark",
                "name": "nozzle",
                "x": c.x_fill,
                "y": c.bottle_height + 0.05,
            },
            {
                "type": "mark",
                "name": "FILL_EYE",
                "x": c.x_fill + c.fill_eye_offset,
                "y": min(0.5 * c.bottle_height, 0.1),
            },
            {
                "type": "rect",
                "name": "bin",
                "x": c.belt_length,
                "y": -0.5,
                "w": 0.5,
                "h": 0.4,
            },
        ],
        "bottle": {
            "w": c.bottle_width,
            "h": c.bottle_height,
            "slots": c.max_bottles,
            "prefix": "bottle",
        },
    }
