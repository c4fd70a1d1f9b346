"""``plclab opcua``: an OPC UA server around a PLC running in real time (docs/opcua.md, ADR 0055).

Layer ``opcua``: above ``scada`` (it reuses the operator panel's real-time runner and turns
the alarms of :mod:`plclab.scada` into OPC UA conditions); nothing below imports it. asyncua
(the ``opcua`` extra) is imported lazily, when a server starts. One module a concept:

* :mod:`.typemap`  IEC 61131-3 types -> OPC UA built-in types and the value conversions;
* :mod:`.access`   who may connect and which variables a client may write (config file, CLI);
* :mod:`.tags`     the browse tree: every global and program variable as a tag, by POU and
  instance, structures and block instances as folders;
* :mod:`.quality`  the StatusCode of each tag (PLC stopped, wire break on its input);
* :mod:`.alarms`   the alarms of :mod:`plclab.scada` as AlarmConditionType conditions;
* :mod:`.runner`   the real-time runner (the panel's), also for a PLC without a plant;
* :mod:`.server`   the server: the sync task, writes through the access rules;
* :mod:`.users`    asyncua's user manager and permission ruleset (imports asyncua).

>>> from plclab.opcua.typemap import kind_of
>>> kind_of("DINT"), kind_of("LREAL"), kind_of("STRING")
('Int32', 'Double', 'String')
"""

from __future__ import annotations

__all__ = ["access", "alarms", "quality", "runner", "server", "tags", "typemap"]
