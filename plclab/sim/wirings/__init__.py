"""Default wiring tables, one per plant, here and as TOML files beside this module
(``plclab/sim/wirings/<plant>.toml``, :data:`FOLDER`: the tables to copy and edit for a lab).

The layout follows an S7-1200 with a signal board: digital inputs from ``%IX0.0``, digital
outputs from ``%QX0.0``, analog inputs from ``%IW64`` and analog outputs from ``%QW64`` (2 bytes
each). Digital inputs have the 3 ms input filter of a general-purpose input (the textbook's
2-3 ms); push buttons bounce for 2 ms. Contactor coils are driven through relay outputs
(10 ms to close, 5 ms to open), valves and lamps through transistor outputs. Analog inputs are
4-20 mA transmitters over the signal's range in S7 counts (0..27648).

Signals that a typical program does not write are left unwired so that they keep the plant's
default (the tank's ``PUMP_SPEED`` stays at 100 %); ``plclab/sim/wirings/tank_vfd.toml`` shows
how to wire it to an analog output.

>>> w = default_wiring("tank")
>>> [(r.plc, r.signal, r.module) for r in w][:3]
[('%IX0.0', 'LS1', 'di'), ('%IX0.1', 'LS2', 'di'), ('%QX0.0', 'PUMP', 'do')]
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..errors import did_you_mean, sim_error
from ..wiring import Wiring

__all__ = ["DEFAULTS", "FOLDER", "as_wiring", "default_wiring"]

FOLDER = Path(__file__).resolve().parent
"""The wiring tables as TOML files: ``<plant>.toml`` (the same rows as :data:`DEFAULTS`) and
variants (``tank_vfd.toml``); package data, so an installed plclab has them too."""

_FILTER = 3.0
_BUTTON = {"filter_ms": _FILTER, "bounce_ms": 2.0}
_SWITCH = {"filter_ms": _FILTER}
_RELAY = {"kind": "relay"}
_TRANSISTOR = {"kind": "transistor"}
_AI = {"signal_range": "4-20mA", "convention": "s7"}


def _di(plc: str, signal: str, desc: str, **p: Any) -> dict[str, Any]:
    return {"plc": plc, "signal": signal, "module": "di", **(p or _SWITCH), "description": desc}


def _do(plc: str, signal: str, desc: str, **p: Any) -> dict[str, Any]:
    return {"plc": plc, "signal": signal, "module": "do", **(p or _TRANSISTOR),
            "description": desc}


def _ai(plc: str, signal: str, lo: float, hi: float, desc: str, **p: Any) -> dict[str, Any]:
    return {"plc": plc, "signal": signal, "module": "ai", "lo": lo, "hi": hi, **_AI, **p,
            "description": desc}


def _ao(plc: str, signal: str, lo: float, hi: float, desc: str, **p: Any) -> dict[str, Any]:
    return {"plc": plc, "signal": signal, "module": "ao", "lo": lo, "hi": hi,
            "signal_range": "0-10V", "convention": "s7", **p, "description": desc}


DEFAULTS: dict[str, tuple[str, list[dict[str, Any]]]] = {
    "motor": ("Start/stop station, contactor K1 with its auxiliary contact, overload relay, "
              "speed and current transmitters (textbook Fig. 113)", [
        _di("%IX0.0", "START", "start push button, NO", **_BUTTON),
        _di("%IX0.1", "STOP", "stop push button, NC: TRUE while not pressed", **_BUTTON),
        _di("%IX0.2", "OL_RESET", "overload relay reset button, NO", **_BUTTON),
        _di("%IX0.3", "RUN", "auxiliary contact of K1: TRUE when the main contacts are closed"),
        _di("%IX0.4", "OVERLOAD", "overload relay contact 97-98: TRUE = tripped"),
        _do("%QX0.0", "K1", "contactor coil K1 through a relay output", **_RELAY),
        _ai("%IW64", "SPEED", 0.0, 1500.0, "shaft speed transmitter 0..1500 rpm"),
        _ai("%IW66", "CURRENT", 0.0, 63.0, "line current transmitter 0..63 A"),
    ]),
    "tank": ("Hydro-accumulator: two level switches, the pump contactor and a level "
             "transmitter (textbook Fig. 31)", [
        _di("%IX0.0", "LS1", "low level switch: TRUE when the liquid is at or above it"),
        _di("%IX0.1", "LS2", "high level switch: TRUE when the liquid is at or above it"),
        _do("%QX0.0", "PUMP", "pump motor contactor through a relay output", **_RELAY),
        _ai("%IW64", "LEVEL", 0.0, 2.0, "level transmitter 0..2 m, 4-20 mA"),
    ]),
    "sump": ("Mine dewatering station: level switches, pressure switch, priming pump and three "
             "main pumps (textbook Fig. 120-121)", [
        _di("%IX0.0", "NY", "low level switch (NY)"),
        _di("%IX0.1", "WY", "high level switch (WY)"),
        _di("%IX0.2", "PWY", "raised high level switch (PWY)"),
        _di("%IX0.3", "AWY", "emergency high level switch (AWY)"),
        _di("%IX0.4", "DAWL", "pressure switch: pump system primed"),
        _do("%QX0.0", "ZAL", "priming (vacuum) pump contactor", **_RELAY),
        _do("%QX0.1", "NS1", "main pump 1 contactor", **_RELAY),
        _do("%QX0.2", "NS2", "main pump 2 contactor", **_RELAY),
        _do("%QX0.3", "NS3", "main pump 3 contactor", **_RELAY),
        _ai("%IW64", "LEVEL", 0.0, 5.0, "sump level transmitter 0..5 m"),
    ]),
    "heater": ("Water heater: element contactor, thyristor and steam valve set points, fill "
               "and drain valves, level and temperature instruments", [
        _di("%IX0.0", "LEVEL_MIN", "min level switch: TRUE when the water is at or above it"),
        _di("%IX0.1", "LEVEL_MAX", "max level switch: TRUE when the water is at or above it"),
        _di("%IX0.2", "TEMP_MAX", "over-temperature thermostat: TRUE when hot"),
        _do("%QX0.0", "HEATER", "heating element contactor (full power)", **_RELAY),
        _do("%QX0.1", "FILL_VALVE", "cold water fill valve"),
        _do("%QX0.2", "DRAIN_VALVE", "drain valve"),
        _ai("%IW64", "TEMP", -20.0, 120.0, "water temperature transmitter -20..120 degC"),
        _ai("%IW66", "LEVEL", 0.0, 1.0, "level transmitter 0..1 m"),
        _ao("%QW64", "POWER", 0.0, 100.0, "thyristor power set point 0..100 % (0-10 V)"),
        _ao("%QW66", "STEAM_VALVE", 0.0, 100.0, "steam valve position 0..100 % (0-10 V)"),
    ]),
    "conveyor": ("Bottle conveyor: buttons, photo-eyes, reject cylinder and filling station "
                 "(textbook Fig. 115-117)", [
        _di("%IX0.0", "START", "start push button, NO", **_BUTTON),
        _di("%IX0.1", "STOP", "stop push button, NC: TRUE while not pressed", **_BUTTON),
        _di("%IX0.2", "X1", "high photo-eye (neck height): TRUE = beam broken"),
        _di("%IX0.3", "X2", "low photo-eye (body height): TRUE = beam broken"),
        _di("%IX0.4", "CYL_EXTENDED", "reject cylinder end switch: fully out"),
        _di("%IX0.5", "CYL_RETRACTED", "reject cylinder end switch: fully in"),
        _di("%IX0.6", "FILL_EYE", "bottle-in-position eye before the nozzle"),
        _do("%QX0.0", "CONVEYOR", "belt motor contactor", **_RELAY),
        _do("%QX0.1", "REJECT", "reject cylinder solenoid valve"),
        _do("%QX0.2", "FILL_VALVE", "filling nozzle valve"),
        _ai("%IW64", "FILL_LEVEL", 0.0, 100.0, "fill of the bottle under the nozzle 0..100 %"),
    ]),
    "ventilation": ("Livestock building: main switch and buttons, three fan contactors with "
                    "their fault contacts, lamps, inside and outside temperature "
                    "(textbook Fig. 118-119)", [
        _di("%IX0.0", "MS", "main switch: TRUE = on"),
        _di("%IX0.1", "START", "start push button, NO", **_BUTTON),
        _di("%IX0.2", "STOP", "stop push button, NC: TRUE while not pressed", **_BUTTON),
        _di("%IX0.3", "FAULT1", "fan 1 motor protection: TRUE = tripped"),
        _di("%IX0.4", "FAULT2", "fan 2 motor protection: TRUE = tripped"),
        _di("%IX0.5", "FAULT3", "fan 3 motor protection: TRUE = tripped"),
        _do("%QX0.0", "MAIN_POWER", "main power contactor of the fan circuit", **_RELAY),
        _do("%QX0.1", "FAN1", "fan 1 contactor (standby fan)", **_RELAY),
        _do("%QX0.2", "FAN2", "fan 2 contactor", **_RELAY),
        _do("%QX0.3", "FAN3", "fan 3 contactor", **_RELAY),
        _do("%QX0.4", "RUN_LAMP", "cycle running lamp"),
        _do("%QX0.5", "FAULT_LAMP", "fault lamp: steady = one fault, 5 Hz = two or more"),
        _do("%QX0.6", "FAN1_LAMP", "fan 1 running lamp"),
        _do("%QX0.7", "FAN2_LAMP", "fan 2 running lamp"),
        _do("%QX1.0", "FAN3_LAMP", "fan 3 running lamp"),
        _ai("%IW64", "TEMP_IN", -30.0, 60.0, "inside air temperature -30..60 degC"),
        _ai("%IW66", "TEMP_OUT", -30.0, 50.0, "outside air temperature -30..50 degC"),
    ]),
    "press": ("Plastic press: two-hand buttons, light curtain, E-stop, end switches, encoder, "
              "valve solenoids and heater (textbook Fig. 100)", [
        _di("%IX0.0", "HAND_L", "left two-hand button, NO", **_BUTTON),
        _di("%IX0.1", "HAND_R", "right two-hand button, NO", **_BUTTON),
        _di("%IX0.2", "LIGHT_CURTAIN", "light curtain: TRUE = field clear"),
        _di("%IX0.3", "E_STOP", "emergency stop, NC: TRUE while not pressed"),
        _di("%IX0.4", "TOP", "top end switch"),
        _di("%IX0.5", "BOTTOM", "bottom end switch"),
        _di("%IX0.6", "ENCODER_PULSE", "encoder pulse train (fast input, 0.2 ms filter)",
            filter_ms=0.2),
        _do("%QX0.0", "DOWN", "valve solenoid: piston down"),
        _do("%QX0.1", "UP", "valve solenoid: piston up"),
        _do("%QX0.2", "HEATER", "container heater contactor", **_RELAY),
        _ai("%IW64", "POSITION", 0.0, 200.0, "piston position transmitter 0..200 mm"),
        _ai("%IW66", "TEMP", 0.0, 400.0, "plastic temperature transmitter 0..400 degC"),
    ]),
    "washer": ("Washing machine: buttons, mode selector, valves, heater, drum motor, level "
               "switches and transmitters (textbook Fig. 32)", [
        _di("%IX0.0", "START", "start push button, NO", **_BUTTON),
        _di("%IX0.1", "STOP", "stop push button, NC: TRUE while not pressed", **_BUTTON),
        _di("%IX0.2", "COTTON", "mode selector contact COTTON"),
        _di("%IX0.3", "SILK", "mode selector contact SILK"),
        _di("%IX0.4", "LEVEL_SW", "level pressure switch: TRUE when full"),
        _di("%IX0.5", "EMPTY", "TRUE when the tub is empty"),
        _di("%IX0.6", "DOOR", "door switch, NC: TRUE while the door is closed"),
        _do("%QX0.0", "FILL_VALVE", "cold water inlet valve"),
        _do("%QX0.1", "DRAIN_VALVE", "drain valve / pump"),
        _do("%QX0.2", "HEATER", "heating element contactor", **_RELAY),
        _do("%QX0.3", "MOTOR", "drum motor contactor", **_RELAY),
        _ai("%IW64", "LEVEL", 0.0, 30.0, "water level transmitter 0..30 l"),
        _ai("%IW66", "TEMP", 0.0, 100.0, "water temperature transmitter 0..100 degC"),
    ]),
    # -- drives lab (labs/drive-homing): encoders as REAL millimetres through module direct
    "axes": ("Three axes (belt, piston, pump): reversing contactors, home switches, drive "
             "fault contacts, encoders in mm, START/RESET buttons and two lamps", [
        _di("%IX0.0", "START", "start push button, NO", **_BUTTON),
        _di("%IX0.1", "RESET", "alarm reset push button, NO", **_BUTTON),
        *[row for i, axis in enumerate(("BELT", "PISTON", "PUMP")) for row in (
            _di(f"%IX0.{2 + 2 * i}", f"{axis}_HOME", f"{axis.lower()} home switch"),
            _di(f"%IX0.{3 + 2 * i}", f"{axis}_FAULT", f"{axis.lower()} drive fault contact"),
            _do(f"%QX0.{2 * i}", f"{axis}_FWD", f"{axis.lower()} forward contactor", **_RELAY),
            _do(f"%QX0.{1 + 2 * i}", f"{axis}_REV", f"{axis.lower()} reverse contactor",
                **_RELAY),
            {"plc": f"%ID{100 + 4 * i}", "signal": f"{axis}_POS", "module": "direct",
             "description": f"{axis.lower()} encoder position, mm (REAL)"})],
        _do("%QX0.6", "READY_LAMP", "READY lamp"),
        _do("%QX0.7", "ALARM_LAMP", "ALARM lamp"),
    ]),
    # -- traffic-light lab (labs/pedestrian-crossing)
    "crossing": ("Pedestrian crossing: request button, kerb and crossing sensors, car and "
                 "pedestrian lamps", [
        _di("%IX0.0", "REQUEST", "pedestrian request button, NO", **_BUTTON),
        _di("%IX0.1", "PED_WAITING", "kerb sensor"),
        _di("%IX0.2", "ON_CROSSING", "crossing sensor"),
        _do("%QX0.0", "CAR_RED", "car red lamp"),
        _do("%QX0.1", "CAR_YELLOW", "car yellow lamp"),
        _do("%QX0.2", "CAR_GREEN", "car green lamp"),
        _do("%QX0.3", "PED_RED", "pedestrian red lamp"),
        _do("%QX0.4", "PED_GREEN", "pedestrian green lamp"),
        _do("%QX0.5", "WAIT_LAMP", "'signal comes' lamp"),
    ]),
}
"""plant -> (description, rows) of the default wiring tables."""


def default_wiring(plant_name: str) -> Wiring:
    """The default wiring table of a plant (the same as ``plclab/sim/wirings/<plant>.toml``).

    Raises
    ------
    PlcError
        PLC4020 when there is no default for that plant.
    """
    name = getattr(plant_name, "name", plant_name)
    entry = DEFAULTS.get(name)
    if entry is None:
        raise sim_error("PLC4020", f"no default wiring for plant {name!r}.{did_you_mean(name, DEFAULTS)}"
                        f" Plants with one: {', '.join(DEFAULTS)}; or give a wiring table")
    desc, rows = entry
    return Wiring.from_rows([dict(r) for r in rows], plant=name, description=desc)


def as_wiring(wiring: Any, plant_name: str) -> Wiring:
    """Accept None (the plant's default), a path, a Wiring or a list of rows."""
    if wiring is None:
        return default_wiring(plant_name)
    if isinstance(wiring, Wiring):
        return wiring
    if isinstance(wiring, str | os.PathLike):
        return Wiring.load(wiring)
    return Wiring.from_rows(wiring)
