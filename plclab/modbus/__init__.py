"""Modbus TCP for plclab: serve a PLC's process image, remote I/O, a notebook client.

Layer ``modbus`` (``docs/adr/0013-layers-and-lazy-cli.md``): above the PLC core, beside ``viz``;
the ``plclab serve`` commands are in the ``cli`` layer (:mod:`plclab.modbus.commands`).

* ``plclab serve PROGRAM...`` -- the PLC scans in real time behind a Modbus TCP server
  (:class:`~plclab.modbus.server.PlcServer`; address map in :mod:`plclab.modbus.addressing`);
* ``plclab plant-serve PLANT`` -- a plant as a Modbus server, for ``serve --io modbus://...``
  (:mod:`plclab.modbus.plant_server`, :mod:`plclab.modbus.remote_io`);
* :func:`connect` -- a small synchronous client for notebooks.

pymodbus (``pip install 'plclab[modbus]'``) is imported only when one of these runs; importing
this package imports nothing outside the standard library. See ``docs/modbus.md``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["BackgroundServer", "ModbusClient", "PlcServer", "connect"]


def connect(host: str = "127.0.0.1", port: int = 5020, device_id: int = 1,
            timeout: float = 2.0):
    """Connect to ``plclab serve`` (or any Modbus TCP server); returns a client.

    The client has ``read_coils``, ``read_inputs``, ``read_registers``, ``write_register``,
    ``write_coil``, ``status()`` and ``client["%QX0.0"]`` / ``client["%MW0"] = 5`` access.
    """
    from .client import connect as _connect

    return _connect(host, port, device_id, timeout)


def __getattr__(name: str) -> Any:
    if name == "ModbusClient":
        from .client import ModbusClient

        return ModbusClient
    if name in ("PlcServer", "BackgroundServer"):
        from . import server

        return getattr(server, name)
    raise AttributeError(f"module 'plclab.modbus' has no attribute {name!r}")
