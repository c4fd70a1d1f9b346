"""How a plant's signals sit in Modbus tables and in the PLC's process image (no pymodbus).

A plant served by ``plclab plant-serve`` (remote I/O, like Factory I/O) and a plant coupled
directly to ``plclab serve --plant`` use the same order: the plant's signal table, split by
kind and type.

==================  =====================================  ==================================
Modbus table        plant signals, in signal order         PLC address (remote I/O)
==================  =====================================  ==================================
discrete inputs 0.  boolean sensors                        %IX0.0, %IX0.1, ... (k -> %IX k//8 . k%8)
input registers 0.  real sensors, scaled 0..27648          %IW64, %IW66, ... (k -> %IW 64+2k)
coils 0..           boolean actuators and lamps            %QX0.0, %QX0.1, ...
holding regs 0..    real actuators and lamps, 0..27648     %QW64, %QW66, ...
coils 1000..        boolean panel signals (buttons)        not wired to the PLC
holding regs 1000.  real panel signals, 0..27648           not wired to the PLC
input regs 1000..   info: counts of the six groups above,  read by the PLC's remote-I/O client
                    then plant time in ms (hi, lo word)
==================  =====================================  ==================================

plclab's words share bytes with its bits (``%IW0`` is ``%IX0.0..%IX1.7``), so the analog
values start at byte 64, as the analog channels of an S7-1200 CPU do (``%IW64``): bits use
bytes 0..63 (512 bits at most), words bytes 64..1023 (480 words at most).

Reals are scaled as on an S7 analog module: the low end of the signal's range is 0, the high
end 27648 (see :func:`plclab.modbus.addressing.to_register`).

The PLC writes an actuator only when its program declares a located output that covers the
coil's bit or the register's bytes; the others keep the plant's own value (the tank's
``PUMP_SPEED`` stays at its initial 100 % when the program only drives ``PUMP``).

>>> from plants import get_plant
>>> lay = plant_layout(get_plant("tank"))
>>> [s.name for s in lay.di], [s.name for s in lay.coils], [s.name for s in lay.hr]
(['LS1', 'LS2'], ['PUMP', 'FAULT_LAMP'], ['PUMP_SPEED'])
>>> plc_address("ir", 2)
'%IW68'
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import PlcError
from .addressing import MAPPED_BYTES, from_register, parse_address, to_register

PANEL_BASE = 1000  # coils / holding registers of panel signals
INFO_BASE = 1000  # input registers: n_di, n_ir, n_coils, n_hr, n_panel_coils, n_panel_hr, t_hi, t_lo
INFO_COUNT = 8
ANALOG_BYTE = 64  # first byte of the analog words in the PLC's image (%IW64, %QW64)
MAX_BITS = ANALOG_BYTE * 8  # 512 digital points a direction
MAX_WORDS = (MAPPED_BYTES - ANALOG_BYTE) // 2  # 480 analog points a direction

GROUPS = ("di", "ir", "coils", "hr", "panel_coils", "panel_hr")
GROUP_TABLE = {"di": "discrete input", "ir": "input register", "coils": "coil",
               "hr": "holding register", "panel_coils": "coil", "panel_hr": "holding register"}


@dataclass
class PlantLayout:
    di: list = field(default_factory=list)
    ir: list = field(default_factory=list)
    coils: list = field(default_factory=list)
    hr: list = field(default_factory=list)
    panel_coils: list = field(default_factory=list)
    panel_hr: list = field(default_factory=list)

    def counts(self) -> list[int]:
        return [len(getattr(self, g)) for g in GROUPS]


def plant_layout(plant) -> PlantLayout:
    """Split a plant's signals into the six Modbus groups, keeping the signal order."""
    lay = PlantLayout()
    for s in plant.signals.values():
        boolean = s.type == "bool"
        if s.kind == "sensor":
            (lay.di if boolean else lay.ir).append(s)
        elif s.kind in ("actuator", "lamp"):
            (lay.coils if boolean else lay.hr).append(s)
        elif s.kind == "panel":
            (lay.panel_coils if boolean else lay.panel_hr).append(s)
    return lay


def plc_address(group: str, k: int) -> str:
    """The PLC address that remote I/O joins to item ``k`` of ``group``."""
    if group in ("di", "coils"):
        return f"%{'I' if group == 'di' else 'Q'}X{k // 8}.{k % 8}"
    if group in ("ir", "hr"):
        return f"%{'I' if group == 'ir' else 'Q'}W{ANALOG_BYTE + 2 * k}"
    raise ValueError(f"{group} is not wired to the PLC")


def format_plant_map(plant, lay: PlantLayout | None = None) -> str:
    """The table printed by ``plclab plant-serve``."""
    lay = lay or plant_layout(plant)
    lines = [f"Plant {plant.name!r} as a Modbus TCP server (device id 1, numbers 0-based; "
             "reals scaled low..high -> 0..27648):"]
    for g in GROUPS:
        base = PANEL_BASE if g.startswith("panel") else 0
        for k, s in enumerate(getattr(lay, g)):
            plc = plc_address(g, k) if not g.startswith("panel") else "(panel)"
            rng = "" if s.type == "bool" else f" {s.range[0]:g}..{s.range[1]:g} {s.unit}"
            lines.append(f"  {GROUP_TABLE[g]:<17} {base + k:<5} {s.name:<12} {s.kind:<8} "
                         f"{plc:<8}{rng}")
    lines.append(f"  input registers   {INFO_BASE}..{INFO_BASE + INFO_COUNT - 1} info: counts "
                 "(di, ir, coils, hr, panel coils, panel hr), plant time ms (hi, lo)")
    return "\n".join(lines)


def covered_outputs(plc) -> set[tuple[int, int]]:
    """The (byte, bit) pairs of %Q that the program's located variables drive."""
    from .addressing import located_variables

    out: set[tuple[int, int]] = set()
    for _, address, _ in located_variables(plc):
        area, size, byte, bit = parse_address(address)
        if area != "Q":
            continue
        if size == "X":
            out.add((byte, bit))
        else:
            n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
            out.update((b, i) for b in range(byte, byte + n) for i in range(8))
    return out


def coil_covered(covered: set, k: int) -> bool:
    return (k // 8, k % 8) in covered


def register_covered(covered: set, k: int) -> bool:
    b0 = ANALOG_BYTE + 2 * k
    return any((b, i) in covered for b in (b0, b0 + 1) for i in range(8))


# -- process-image helpers (used by local coupling and by remote I/O) ------------------------
def set_bit(buf: bytearray, k: int, value: bool) -> None:
    """Set bit ``k`` (``%?X k//8 . k%8``) if it lies in the digital bytes 0..63 (and in
    ``buf``: an image smaller than the map never grows or raises)."""
    byte, bit = divmod(k, 8)
    if byte >= min(len(buf), ANALOG_BYTE):
        return
    if value:
        buf[byte] |= 1 << bit
    else:
        buf[byte] &= 0xFF ^ (1 << bit)


def get_bit(buf: bytes, k: int) -> bool:
    byte, bit = divmod(k, 8)
    return bool(buf[byte] >> bit & 1) if byte < min(len(buf), ANALOG_BYTE) else False


def set_word(buf: bytearray, k: int, value: int) -> None:
    """Set analog word ``k`` (``%?W 64+2k``), big-endian."""
    b = ANALOG_BYTE + 2 * k
    if b + 2 <= min(len(buf), MAPPED_BYTES):
        buf[b:b + 2] = (int(value) & 0xFFFF).to_bytes(2, "big")


def get_word(buf: bytes, k: int) -> int:
    b = ANALOG_BYTE + 2 * k
    return int.from_bytes(buf[b:b + 2], "big") if b + 2 <= len(buf) else 0


class PlantCoupling:
    """Join a plant to a PLC directly, in the order above (``plclab serve --plant``).

    Call :meth:`to_plc` before a scan (sensors -> input terminals), :meth:`from_plc` after it
    (output terminals -> actuators) and ``plant.step(dt)`` for the scan's virtual time.
    """

    def __init__(self, plant, plc) -> None:
        self.plant = plant
        self.plc = plc
        self.layout = lay = plant_layout(plant)
        covered = covered_outputs(plc)
        self._coils = [(k, s.name) for k, s in enumerate(lay.coils) if coil_covered(covered, k)]
        self._hr = [(k, s.name, s.range[0], s.range[1]) for k, s in enumerate(lay.hr)
                    if register_covered(covered, k)]
        self._di = [(k, s.name) for k, s in enumerate(lay.di)]
        self._ir = [(k, s.name, s.range[0], s.range[1]) for k, s in enumerate(lay.ir)]
        need = ANALOG_BYTE + 2 * len(lay.ir) if lay.ir else (len(lay.di) + 7) // 8
        if need > plc.image_size:
            raise PlcError("PLC3010", f"plant {plant.name!r} in signal order needs the first "
                           f"{need} bytes of the process image, but the PLC has "
                           f"{plc.image_size}; load the program with a larger image_size")

    def to_plc(self) -> None:
        p, inp = self.plant, self.plc.inputs
        for k, name in self._di:
            set_bit(inp, k, bool(p.read(name)))
        for k, name, lo, hi in self._ir:
            set_word(inp, k, to_register(p.read(name), lo, hi))

    def from_plc(self) -> None:
        p, out = self.plant, self.plc.outputs
        for k, name in self._coils:
            p.write(name, get_bit(out, k))
        for k, name, lo, hi in self._hr:
            p.write(name, from_register(get_word(out, k), lo, hi))
