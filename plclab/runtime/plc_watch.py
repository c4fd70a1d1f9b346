"""Forcing, trigger points, one-shot modifications and outputs in STOP of
:class:`~plclab.runtime.plc.Plc` (ADR 0025, 0034; a mixin, moved out of plc.py)."""


from __future__ import annotations

from typing import Any

from ..errors import PlcError
from .plc_limits import (
    ADDR_RE,
    SIZE_BYTES,
)
from .plc_vars import convert_in


class ForcingAndWatch:
    """Forcing and watch-table trigger points (a mixin of Plc)."""

    # -- forcing ------------------------------------------------------------------------------
    def force(self, path: str, value: Any) -> None:
        """Force a variable or address: it keeps ``value`` whatever the program or input does."""
        v = self.var(path)
        self.forced[path.upper()] = (v, convert_in(value, v.type, path))

    def unforce(self, path: str | None = None) -> None:
        if path is None:
            self.forced.clear()
        else:
            self.forced.pop(path.upper(), None)

    def _apply_forced_inputs(self) -> None:
        self._apply_inputs(self.forced.items())

    def _apply_inputs(self, items: Any) -> None:
        """Write values into the input image (or the variables) before the program reads them."""
        for key, (v, val) in items:
            if key.startswith("%I"):
                self._write_bytes(self.image_in, *self._addr_parts(key), val)
            elif key.startswith("%M"):
                self._write_bytes(self.memory, *self._addr_parts(key), val)
            elif v.address and v.address.startswith("%I"):
                self._write_address(v.address, val, v.type, physical=False)
            elif not key.startswith("%"):
                v.set(val)

    def _apply_forced_outputs(self) -> None:
        self._apply_outputs(self.forced.items())

    def _apply_outputs(self, items: Any) -> None:
        """Write values into the variables and the output image after the program ran."""
        for key, (v, val) in items:
            if key.startswith("%Q"):
                self._write_bytes(self.image_out, *self._addr_parts(key), val)
            elif key.startswith("%M"):
                self._write_bytes(self.memory, *self._addr_parts(key), val)
            elif not key.startswith("%") and not (v.address and v.address.startswith("%I")):
                v.set(val)
                if v.address and v.address.startswith("%Q"):
                    area_size = self._addr_parts(v.address)
                    self._write_bytes(self.image_out, *area_size, val)

    def _unforce_image(self, held: bytes) -> None:
        """A forced output *address* acts on the terminal, not on the output image the program
        and its located variables see (as S7's force of a peripheral output): after the
        terminals are written, its bits of the image go back to what the program wrote (ADR
        0056; the image is loaded into located variables at the next scan start)."""
        for key in self.forced:
            if key.startswith("%Q"):
                size, byte, bit = self._addr_parts(key)
                if size == "X":
                    mask = 1 << int(bit)
                    self.image_out[byte] = (self.image_out[byte] & ~mask & 0xFF) | \
                        (held[byte] & mask)
                else:
                    n = SIZE_BYTES[size]
                    self.image_out[byte:byte + n] = held[byte:byte + n]

    @staticmethod
    def _addr_parts(addr: str):
        m = ADDR_RE.fullmatch(addr.upper())
        assert m
        return m.group(2) or "X", int(m.group(3)), m.group(4)

    # -- trigger points, modify, outputs in STOP (ADR 0025; 001 lines 3890-4080) ----------------
    def modify(self, path: str, value: Any, at: str = "scan_start") -> None:
        """Write ``value`` to a variable or address ONCE at a trigger point (``"scan_start"``,
        after the inputs are read: best for inputs; ``"scan_end"``, before the outputs are
        written: best for outputs), unlike :meth:`force`, which holds it every scan."""
        if at not in ("scan_start", "scan_end"):
            raise PlcError("PLC6001", f"modify at {at!r}: a value is modified at 'scan_start' "
                           "or 'scan_end'")
        v = self.var(path)
        self.modified[at][path.upper()] = (v, convert_in(value, v.type, path))
        self._hooked = True
        self._reselect()

    def enable_outputs_in_stop(self, enable: bool = True) -> None:
        """TIA Portal's *Enable peripheral outputs*: in STOP, modified outputs reach the
        terminals (to test the wiring). Only in STOP, only with nothing forced; RUN clears it."""
        if enable and self.state == "RUN":
            raise PlcError("PLC6002", "outputs can be enabled only in STOP; call plc.stop() "
                           "first")
        if enable and self.forced:
            raise PlcError("PLC6002", "outputs cannot be enabled in STOP while values are "
                           f"forced ({', '.join(self.forced)}); call plc.unforce() first")
        self.outputs_enabled_in_stop = bool(enable)
        if enable:
            self.image_out[:] = bytes(self.image_size)

    @property
    def _watched(self) -> bool:
        return self._hooked

    def _rewatch(self) -> None:
        """Recompute ``_hooked`` after a trigger list or a pending modification changed."""
        self._hooked = any(self._watch_parts)
        self._reselect()

    def _take(self, at: str) -> list[tuple[str, Any]]:
        items = list(self.modified[at].items())
        self.modified[at].clear()
        self._rewatch()
        return items

    def _fire(self, at: str) -> None:
        for fn in tuple(self.triggers[at]):
            fn(self, at)

    def _stop_scan(self) -> None:
        """A scan in STOP: the program does not run; outputs are off unless enabled, when
        modified outputs reach the terminals. Watch tables still sample."""
        if self.outputs_enabled_in_stop:
            self._apply_outputs(self._take("scan_end") + self._take("scan_start"))
            self.outputs[:] = self.image_out
        else:
            self.outputs[:] = bytes(self.image_size)
        if self.triggers["scan_start"] or self.triggers["scan_end"]:
            self.image_in[:] = self.inputs
            self._fire("scan_start")
            self._fire("scan_end")


class TriggerHooks(list):
    """The callbacks of one trigger point (``plc.triggers[at]``): a list that calls
    ``changed()`` after every change, so the PLC keeps one flag instead of testing every
    trigger point on each ``scan()`` call (ADR 0034)."""

    __slots__ = ("_changed",)

    def __init__(self, changed: Any) -> None:
        super().__init__()
        self._changed = changed

    def __iadd__(self, other: Any) -> TriggerHooks:
        super().__iadd__(other)
        self._changed()
        return self


def _notifying(name: str, base: type = list) -> Any:
    method = getattr(base, name)

    def changed(self: Any, *args: Any) -> Any:
        out = method(self, *args)
        self._changed()
        return out

    changed.__name__ = name
    return changed


for _name in ("append", "extend", "insert", "remove", "pop", "clear", "__setitem__",
              "__delitem__"):
    setattr(TriggerHooks, _name, _notifying(_name))
del _name


class ForcedTable(dict):
    """``plc.forced``: the forced values, a dict that calls ``changed()`` after every change, so
    the generated scan learns that forcing is active without testing the table on each call
    (ADR 0058)."""

    __slots__ = ("_changed",)

    def __init__(self, changed: Any) -> None:
        super().__init__()
        self._changed = changed

    def __ior__(self, other: Any) -> ForcedTable:
        super().__ior__(other)
        self._changed()
        return self


for _name in ("__setitem__", "__delitem__", "pop", "popitem", "clear", "update", "setdefault"):
    setattr(ForcedTable, _name, _notifying(_name, dict))
del _name
