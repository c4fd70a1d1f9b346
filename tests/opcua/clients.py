"""Independent OPC UA clients for the tests, each run as its own process (asyncua's client API).

``python clients.py deadband URL NODE DEADBAND`` ... every command prints one JSON line with
what it saw, or ``READY`` first when the test must act after the client is subscribed. None of
this imports plclab: the server is judged from outside, as UaExpert or Node-RED would.
"""

from __future__ import annotations

import asyncio
import json
import sys

from asyncua import Client, ua

TIMEOUT = 120.0  # generous: the tests wait for conditions, never for a speed


def say(obj) -> None:
    print(obj if isinstance(obj, str) else json.dumps(obj), flush=True)


class Collect:
    def __init__(self) -> None:
        self.values: dict[int, list] = {}
        self.events: list = []
        self.changed = asyncio.Event()

    def datachange_notification(self, node, val, data) -> None:
        self.values.setdefault(data.monitored_item.ClientHandle, []).append(val)
        self.changed.set()

    def event_notification(self, event) -> None:
        self.events.append(event)
        self.changed.set()

    async def until(self, cond) -> None:
        async def loop():
            while not cond():
                self.changed.clear()
                await self.changed.wait()
        await asyncio.wait_for(loop(), TIMEOUT)


async def deadband(url: str, node_id: str, band: float, last: float) -> None:
    """Two subscriptions on one node, one with an absolute deadband ``band``, one without;
    stop when both have seen ``last``."""
    async with Client(url) as c:
        plain, filtered = Collect(), Collect()
        node = c.get_node(node_id)
        await (await c.create_subscription(50, plain)).subscribe_data_change(node, queuesize=100)
        flt = ua.DataChangeFilter(Trigger=ua.DataChangeTrigger.StatusValue,
                                  DeadbandType=ua.DeadbandType.Absolute, DeadbandValue=band)
        sub = await c.create_subscription(50, filtered)
        await sub._subscribe(node, ua.AttributeIds.Value, flt, queuesize=100)  # no public API
        await plain.until(lambda: plain.values)
        await filtered.until(lambda: filtered.values)
        say("READY")
        for h in (plain, filtered):
            await h.until(lambda h=h: list(h.values.values())[0][-1] == last)
        say({"plain": list(plain.values.values())[0],
             "deadband": list(filtered.values.values())[0]})


async def alarm(url: str, user: str, password: str, node_id: str, trigger: str) -> None:
    """As ``user``: raise the alarm by writing ``trigger``, acknowledge it, report the events;
    then try the same as an anonymous client and report how the server refused."""
    out: dict = {}
    async with Client(url) as anon:  # anonymous first: read-only
        try:
            await anon.get_node(trigger).write_value(ua.DataValue(ua.Variant(True, ua.VariantType.Boolean)))
            out["anonymous_write"] = "accepted"
        except ua.UaStatusCodeError as e:
            out["anonymous_write"] = type(e).__name__
    c = Client(url)
    c.set_user(user)
    c.set_password(password)
    async with c:
        h = Collect()
        sub = await c.create_subscription(50, h)
        await sub.subscribe_events(c.nodes.server, ua.ObjectIds.AlarmConditionType)
        await c.get_node(trigger).write_value(ua.DataValue(ua.Variant(True, ua.VariantType.Boolean)))

        def texts():
            return [e.Message.Text for e in h.events if e.SourceNode == ua.NodeId.from_string(node_id)]

        await h.until(lambda: any(t.startswith("I:") for t in texts()))
        came = [e for e in h.events if e.Message.Text.startswith("I:")][-1]
        out["came"] = {"message": came.Message.Text, "severity": came.Severity}
        cond = c.get_node(node_id)
        acked = await cond.get_child("0:AckedState")
        out["acked_before"] = (await acked.read_value()).Text
        async with Client(url) as anon:
            try:
                await anon.get_node(node_id).call_method(
                    ua.NodeId(ua.ObjectIds.AcknowledgeableConditionType_Acknowledge),
                    ua.Variant(came.EventId, ua.VariantType.ByteString),
                    ua.Variant(ua.LocalizedText("anonymous"), ua.VariantType.LocalizedText))
                out["anonymous_ack"] = "accepted"
            except ua.UaStatusCodeError as e:
                out["anonymous_ack"] = type(e).__name__
        await cond.call_method(ua.NodeId(ua.ObjectIds.AcknowledgeableConditionType_Acknowledge),
                               ua.Variant(came.EventId, ua.VariantType.ByteString),
                               ua.Variant(ua.LocalizedText("seen"), ua.VariantType.LocalizedText))
        await h.until(lambda: any(t.startswith("IA:") for t in texts()))
        out["events"] = texts()
        out["acked_after"] = (await acked.read_value()).Text
        try:
            await cond.call_method(ua.NodeId(ua.ObjectIds.AcknowledgeableConditionType_Acknowledge),
                                   ua.Variant(came.EventId, ua.VariantType.ByteString),
                                   ua.Variant(ua.LocalizedText("again"), ua.VariantType.LocalizedText))
            out["second_ack"] = "accepted"
        except ua.UaStatusCodeError as e:
            out["second_ack"] = type(e).__name__
    say(out)


async def load(url: str, user: str, password: str, clients: int, nodes: list[str],
               steps: int) -> None:
    """``clients`` sessions, each with one subscription per node; a writer writes 1001..1000 +
    steps to every node, each step only after every subscription has seen the previous one."""
    sessions = []
    collectors = []
    try:
        for _ in range(clients):
            c = Client(url)
            await c.connect()
            sessions.append(c)
            for n in nodes:
                h = Collect()
                sub = await c.create_subscription(50, h)
                await sub.subscribe_data_change(c.get_node(n))
                collectors.append(h)

        def seen(k):
            return all(h.values and list(h.values.values())[0][-1] == k for h in collectors)

        async def wait_all(k):
            await asyncio.wait_for(_poll(lambda: seen(k)), TIMEOUT)

        await asyncio.wait_for(_poll(lambda: all(h.values for h in collectors)), TIMEOUT)
        w = Client(url)
        w.set_user(user)
        w.set_password(password)
        async with w:
            for k in range(1001, 1001 + steps):
                for n in nodes:
                    await w.get_node(n).write_value(ua.DataValue(ua.Variant(float(k), ua.VariantType.Double)))
                await wait_all(float(k))
        say({"subscriptions": len(collectors), "sessions": len(sessions),
             "values": [list(h.values.values())[0] for h in collectors]})
    finally:
        for c in sessions:
            await c.disconnect()


async def _poll(cond) -> None:
    while not cond():
        await asyncio.sleep(0.02)


def main(argv: list[str]) -> None:
    cmd, url = argv[0], argv[1]
    if cmd == "deadband":
        asyncio.run(deadband(url, argv[2], float(argv[3]), float(argv[4])))
    elif cmd == "alarm":
        asyncio.run(alarm(url, argv[2], argv[3], argv[4], argv[5]))
    elif cmd == "load":
        asyncio.run(load(url, argv[2], argv[3], int(argv[4]), argv[5].split(","),
                         int(argv[6])))
    else:
        raise SystemExit(f"unknown command {cmd}")


if __name__ == "__main__":
    main(sys.argv[1:])
