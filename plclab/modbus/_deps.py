"""Import pymodbus on demand, quietly, with a teaching error when it is missing."""

from __future__ import annotations

import logging

from ..errors import PlcError

#: error codes of the Modbus layer (see docs/modbus.md)
PROBLEMS = {
    "PLC9201": ("Modbus support not installed", "pip install 'plclab[modbus]' (pymodbus 3.16+)."),
    "PLC9202": ("cannot open the Modbus port", "Another program uses the port, or it needs "
                "privileges (ports below 1024); pick another with --port."),
    "PLC9203": ("bad Modbus option", "An --io URL, a host, a port or an address is malformed."),
    "PLC9204": ("Modbus exception response", "The server refused the request (illegal address, "
                "read-only area, illegal value)."),
    "PLC9205": ("no Modbus connection", "The server does not answer: is it running, on this "
                "host and port?"),
}

_quiet = False


def quiet_logging() -> None:
    """Keep pymodbus from writing to stderr (notebook graders fail on any stderr output)."""
    global _quiet
    if _quiet:
        return
    lg = logging.getLogger("pymodbus")
    lg.addHandler(logging.NullHandler())
    lg.propagate = False
    lg.setLevel(logging.CRITICAL + 1)
    _quiet = True


def need_pymodbus():
    """Return the pymodbus module or raise PLC9201."""
    try:
        import pymodbus
    except ModuleNotFoundError:
        raise PlcError("PLC9201", "Modbus needs pymodbus: pip install 'plclab[modbus]' "
                       "(or pip install 'pymodbus>=3.16,<4')") from None
    quiet_logging()
    return pymodbus
