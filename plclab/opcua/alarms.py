"""The alarms of :mod:`plclab.scada` as OPC UA AlarmConditionType conditions (Part 9).

Each alarm is a condition object ``PLC/Alarms/<id>`` (NodeId ``ns=2;s=PLC:Alarms.<id>``); every
entry of the alarm log (WinCC's states I, IA, IO, IAO, IOA) becomes an event from the Server
object with the condition's ActiveState, AckedState, Retain, Severity and the message, stamped
with the PLC's clock. Acknowledge (the method of AcknowledgeableConditionType, called on the
condition) acknowledges the alarm in the AlarmServer, as the panel's button does; it needs
the ``write`` role. The EventId argument is not checked against the last event: any event of
the condition acknowledges it (Part 9 allows a server to be this lenient).

State mapping (ADR 0055): I = active, unacknowledged; IA = active, acknowledged; IO =
inactive, unacknowledged (still retained for the operator); IAO, IOA and a warning's IO =
inactive, acknowledged, Retain false (the condition leaves the alarm list).
"""

from __future__ import annotations

from typing import Any

SEVERITY = {"error": 800, "warning": 500, "system": 300}


class AlarmNodes:
    """Condition nodes and events for an :class:`~plclab.process.alarms.AlarmServer`."""

    def __init__(self, server: Any, alarms: Any) -> None:
        self.server = server
        self.alarms = alarms
        self._seen = len(alarms.log)
        self.nodes: dict[str, Any] = {}  # alarm id -> condition node
        self.by_node: dict[str, str] = {}  # NodeId string -> alarm id
        self.gens: dict[str, Any] = {}
        self.acked = 0

    def take(self) -> list[Any]:
        """New log entries since the last call (the caller holds the runner's lock)."""
        new = self.alarms.log[self._seen:]
        self._seen = len(self.alarms.log)
        return list(new)

    async def build(self) -> None:
        from asyncua import ua

        srv, idx = self.server.server, self.server.idx
        root = await srv.nodes.objects.get_child([f"{idx}:PLC"])
        folder = await root.add_folder(self.server.nodeid("PLC:Alarms"), f"{idx}:Alarms")
        for a in self.alarms.alarms:
            node = await folder.add_object(self.server.nodeid(f"PLC:Alarms.{a.id}"), f"{idx}:{a.id}",
                                           objecttype=ua.ObjectIds.AlarmConditionType)
            self.nodes[a.id] = node
            self.by_node[node.nodeid.to_string()] = a.id
            gen = await srv.get_event_generator(ua.ObjectIds.AlarmConditionType,
                                                ua.ObjectIds.Server)
            ev = gen.event
            ev.SourceNode = node.nodeid
            ev.SourceName = a.tag
            ev.NodeId = node.nodeid
            ev.ConditionName = a.id
            ev.Severity = self._severity(a)
            ev.Message = ua.LocalizedText(a.text)
            self.gens[a.id] = gen
            for child in await node.get_children():
                if (await child.read_browse_name()).Name == "Acknowledge":
                    srv.link_method(child, self._acknowledge)
            await self._set_state(a.id, active=False, acked=True)
        srv.link_method(srv.get_node(ua.NodeId(ua.ObjectIds.AcknowledgeableConditionType_Acknowledge)),
                        self._acknowledge)

    def _severity(self, a: Any) -> int:
        cls = self.alarms.classes[a.alarm_class]
        return SEVERITY.get(a.alarm_class, 800 if cls.ack else 500)

    async def _set_state(self, alarm_id: str, *, active: bool, acked: bool) -> None:
        from asyncua import ua

        node = self.nodes[alarm_id]
        for name, value, true_text, false_text in (
                ("ActiveState", active, "Active", "Inactive"),
                ("AckedState", acked, "Acknowledged", "Unacknowledged")):
            state = await node.get_child(f"0:{name}")
            await state.write_value(ua.LocalizedText(true_text if value else false_text))
            await (await state.get_child("0:Id")).write_value(value)
        await (await node.get_child("0:Retain")).write_value(active or not acked)

    async def publish(self, entries: list[Any]) -> None:
        """One event per new log entry, and the condition's state."""
        from asyncua import ua

        for e in entries:
            a = self.alarms.by_id(e.id)
            needs_ack = self.alarms.classes[a.alarm_class].ack
            active = e.state in ("I", "IA")
            acked = e.state in ("IA", "IAO", "IOA") or not needs_ack
            await self._set_state(e.id, active=active, acked=acked)
            gen = self.gens[e.id]
            ev = gen.event
            ev.ActiveState = ua.LocalizedText("Active" if active else "Inactive")
            setattr(ev, "ActiveState/Id", active)
            ev.AckedState = ua.LocalizedText("Acknowledged" if acked else "Unacknowledged")
            setattr(ev, "AckedState/Id", acked)
            ev.Retain = active or not acked
            ev.ClientUserId = e.user or ""
            await gen.trigger(self.server.stamp(e.time), f"{e.state}: {e.text}")

    async def _acknowledge(self, parent: Any, *args: Any) -> Any:
        from asyncua import ua

        alarm_id = self.by_node.get(parent.to_string())
        if alarm_id is None:
            return ua.StatusCode(ua.StatusCodes.BadNodeIdInvalid)
        runner = self.server.runner
        with runner.lock:
            done = self.alarms.acknowledge(alarm_id, t=runner.sim.time, user="opcua")
        if not done:  # acknowledged already, or a class that needs no acknowledgement
            return ua.StatusCode(ua.StatusCodes.BadConditionBranchAlreadyAcked)
        self.acked += 1
        self.server.on_message(f"alarm {alarm_id} acknowledged over OPC UA")
        return []
