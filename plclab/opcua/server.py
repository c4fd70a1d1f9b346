"""The OPC UA server around a PLC running in real time (``plclab opcua``, ADR 0055).

One asyncio loop serves OPC UA (asyncua); the operator panel's thread steps the PLC (and its
plant) paced to the wall clock. A sync task copies every tag into its node after each
``period`` of wall time, under the runner's lock: the value, the StatusCode
(:mod:`.quality`) and a source timestamp from the PLC's clock (the server's start time plus
the PLC's virtual time). asyncua's subscriptions then report changes, honouring each monitored
item's DataChangeFilter (absolute deadband). A client's write passes three gates: the session's
role (:class:`.access.Access`), the node's AccessLevel (only tags an access rule names are
writable) and the value's range for the IEC type; it reaches the PLC between two scans.
"""

from __future__ import annotations

import asyncio
import datetime as _dt
import logging
from collections.abc import Callable
from typing import Any

from plclab.errors import PlcError

from .quality import GOOD, bad_keys, tag_status
from .tags import Tag, Tree
from .typemap import data_type_id, from_ua, to_ua, variant_type

NAMESPACE = "urn:plclab:plc"
ROOT = "PLC"  # other nodes than tags have "PLC:" ids: no IEC name holds a colon


def need_asyncua():
    """Return asyncua or raise PLC7050."""
    try:
        import asyncua
    except ModuleNotFoundError:
        raise PlcError("PLC7050", "OPC UA needs asyncua: pip install 'plclab[opcua]' (or pip "
                       "install 'asyncua>=1.1')") from None
    for name in ("asyncua", "asyncua.server", "asyncua.uaprotocol"):
        lg = logging.getLogger(name)
        lg.setLevel(logging.CRITICAL + 1)
        lg.propagate = False
    return asyncua


class OpcUaServer:
    """Expose a running PLC over OPC UA.

    Parameters
    ----------
    runner : plclab.scada.panel.Panel
        The real-time runner (:func:`.runner.make_runner`): ``sim``, ``lock``, ``start``,
        ``stop``, ``alarms``.
    tree : Tree
        The tags (:func:`.tags.build_tree`), writable ones marked (:func:`.tags.apply_rules`).
    access : Access
        Anonymous role and users.
    host, port : str, int
    period : float
        Wall seconds between two copies of the PLC into the nodes (default 0.05).
    on_message : callable, optional
        Receives a line of text for each notable event (writes, acknowledgements).
    """

    def __init__(self, runner: Any, tree: Tree, access: Any, *, host: str = "127.0.0.1",
                 port: int = 4840, period: float = 0.05,
                 on_message: Callable[[str], None] | None = None) -> None:
        self.runner = runner
        self.sim = runner.sim
        self.plc = runner.sim.plc
        self.tree = tree
        self.access = access
        self.host, self.port, self.period = host, port, float(period)
        self.on_message = on_message or (lambda text: None)
        self.server: Any = None
        self.idx = 0
        self.nodes: dict[str, Tag] = {}  # NodeId string -> tag
        self._last: dict[str, tuple[Any, str]] = {}
        # client writes per tag: a sync whose snapshot is older than a write skips the tag, so
        # a subscriber never sees the old value come back for a moment
        self._written: dict[str, int] = {}
        self._state: str | None = None
        self._t0 = _dt.datetime.now(_dt.UTC)
        self._stop: asyncio.Event | None = None
        self.alarms: Any = None
        self.writes = 0
        self.refused = 0
        self.syncs = 0

    @property
    def url(self) -> str:
        return f"opc.tcp://{self.host}:{self.port}"

    def stamp(self, t: float) -> _dt.datetime:
        """The source timestamp of PLC time ``t`` (s): the server's start plus ``t``."""
        return self._t0 + _dt.timedelta(seconds=t)

    # ------------------------------------------------------------------ life cycle
    async def start(self) -> None:
        need_asyncua()
        from asyncua import Server, ua
        from asyncua.common.callback import CallbackType

        from .users import PlcRuleset, PlcUserManager

        srv = Server(user_manager=PlcUserManager(self.access))
        await srv.init()
        srv.set_endpoint(f"opc.tcp://{self.host}:{self.port}/")
        srv.set_server_name("plclab virtual PLC")
        srv.set_security_policy([ua.SecurityPolicyType.NoSecurity],
                                permission_ruleset=PlcRuleset(self.access))
        if self.access.anonymous == "none":
            srv.iserver.supported_tokens = (ua.UserNameIdentityToken,)
        self.idx = await srv.register_namespace(NAMESPACE)
        self.server = srv
        await self._build()
        if self.runner.alarms is not None:
            from .alarms import AlarmNodes

            self.alarms = AlarmNodes(self, self.runner.alarms)
            await self.alarms.build()
        srv.subscribe_server_callback(CallbackType.PreWrite, self._pre_write)
        srv.subscribe_server_callback(CallbackType.PostWrite, self._post_write)
        await self.sync()
        try:
            await srv.start()
        except OSError as exc:
            self.server = None
            raise PlcError("PLC7051", f"cannot listen on {self.host}:{self.port} "
                           f"({exc.strerror or exc}); is another server running there? choose "
                           "another --port") from None
        self._stop = asyncio.Event()
        with self.runner.lock:  # source timestamps: PLC time 0 is now minus what has run
            self._t0 = _dt.datetime.now(_dt.UTC) - _dt.timedelta(seconds=self.plc.time)
        self.runner.start()

    def request_stop(self) -> None:
        if self._stop is not None:
            self._stop.set()

    async def run(self, duration: float | None = None) -> None:
        """Serve (start first if needed) until ``duration`` wall seconds or a stop."""
        if self.server is None:
            await self.start()
        assert self._stop is not None
        loop = asyncio.get_running_loop()
        end = None if duration is None else loop.time() + duration
        try:
            while not self._stop.is_set() and (end is None or loop.time() < end):
                await self.sync()
                try:
                    await asyncio.wait_for(self._stop.wait(), self.period)
                except TimeoutError:
                    pass
        finally:
            await self.close()

    async def close(self) -> None:
        self.runner.stop()
        if self.server is not None:
            srv, self.server = self.server, None
            await srv.stop()

    # ------------------------------------------------------------------ the address space
    def nodeid(self, key: str):
        from asyncua import ua

        return ua.NodeId(key, self.idx)

    async def _build(self) -> None:
        from asyncua import ua

        srv, idx = self.server, self.idx
        root = await srv.nodes.objects.add_folder(self.nodeid(f"{ROOT}:"), f"{idx}:{ROOT}")
        folders: dict[tuple[str, ...], Any] = {(): root}
        status = await root.add_folder(self.nodeid(f"{ROOT}:Status"), f"{idx}:Status")
        self.status_nodes = {
            "State": await status.add_variable(self.nodeid(f"{ROOT}:Status.State"), f"{idx}:State",
                                               self.plc.state, ua.VariantType.String),
            "Time": await status.add_variable(self.nodeid(f"{ROOT}:Status.Time"), f"{idx}:Time", 0.0,
                                              ua.VariantType.Double,
                                              datatype=ua.NodeId(ua.ObjectIds.Duration)),
            "ScanCount": await status.add_variable(self.nodeid(f"{ROOT}:Status.ScanCount"),
                                                   f"{idx}:ScanCount", 0,
                                                   ua.VariantType.UInt64),
        }
        for browse in self.tree.folders:
            parent = folders[browse[:-1]]
            folders[browse] = await parent.add_folder(self.nodeid(f"{ROOT}:" + ".".join(browse)),
                                                      f"{idx}:{browse[-1]}")
        for tag in self.tree.tags:
            parent = folders[tag.browse[:-1]]
            vt = variant_type(tag.kind)
            init = self._ua_value(tag, tag.var.get())
            node = await parent.add_variable(
                self.nodeid(tag.path), f"{idx}:{tag.browse[-1]}",
                ua.Variant(init, vt), datatype=data_type_id(tag.kind))
            if tag.dims is not None:
                n = 1
                for d in tag.dims:
                    n *= d
                await node.write_value_rank(1)
                await node.write_array_dimensions([n])
            desc = f"{self.plc.var(tag.path).type}" + (f" AT {tag.address}" if tag.address else "")
            await node.write_attribute(ua.AttributeIds.Description,
                                       ua.DataValue(ua.Variant(ua.LocalizedText(desc))))
            if tag.writable:
                await node.set_writable(True)
            self.nodes[node.nodeid.to_string()] = tag

    def _ua_value(self, tag: Tag, v: Any) -> Any:
        if tag.dims is not None:
            return [to_ua(e, T_elem(tag.ty)) for e in v]
        return to_ua(v, tag.ty)

    # ------------------------------------------------------------------ PLC -> nodes
    def snapshot(self) -> tuple[list[tuple[Tag, Any, str]], dict[str, Any]]:
        """Every tag's value and status, and the PLC's state, taken under the runner's lock."""
        thread = getattr(self.runner, "_thread", None)
        alive = thread is None or thread.is_alive()  # a dead runner: its values are stale
        with self.runner.lock:
            plc = self.plc
            running = plc.state == "RUN" and alive
            bad = bad_keys(self.sim) if running else set()
            rows = []
            for tag in self.tree.tags:
                v = tag.var.get()
                if tag.dims is not None:
                    v = list(v)
                rows.append((tag, v, tag_status(tag, running, bad)))
            fault = getattr(plc, "fault", None)
            info = {"state": plc.state if alive else "STOP", "time": plc.time,
                    "scans": plc.scan_count, "fault": str(fault) if fault is not None else "",
                    "alarms": self.alarms.take() if self.alarms is not None else []}
        return rows, info

    async def sync(self) -> None:
        """Copy the PLC into the nodes: changed values and status codes, PLC-clock stamps."""
        from asyncua import ua

        written = dict(self._written)
        rows, info = self.snapshot()
        stamp = self.stamp(info["time"])
        now = _dt.datetime.now(_dt.UTC)
        srv = self.server
        for tag, v, status in rows:
            key = tag.path
            if self._written.get(key) != written.get(key):
                continue  # written by a client since the snapshot: the next sync sends it
            last = self._last.get(key)
            if last is not None and last[0] == v and last[1] == status:
                continue
            self._last[key] = (v, status)
            dv = ua.DataValue(ua.Variant(self._ua_value(tag, v), variant_type(tag.kind)),
                              StatusCode=ua.StatusCode(getattr(ua.StatusCodes, status)),
                              SourceTimestamp=stamp, ServerTimestamp=now)
            await srv.write_attribute_value(self.nodeid(tag.path), dv)
        for name, value in (("State", info["state"]), ("Time", info["time"] * 1000.0),
                            ("ScanCount", info["scans"])):
            node = self.status_nodes[name]
            vt = {"State": ua.VariantType.String, "Time": ua.VariantType.Double,
                  "ScanCount": ua.VariantType.UInt64}[name]
            await srv.write_attribute_value(node.nodeid, ua.DataValue(
                ua.Variant(value, vt), SourceTimestamp=stamp, ServerTimestamp=now))
        if self.alarms is not None and info["alarms"]:
            await self.alarms.publish(info["alarms"])
        if info["state"] != self._state:
            if self._state is not None:
                why = f": {info['fault']}" if info["fault"] else ""
                self.on_message(f"the PLC is in {info['state']}{why}; every tag is "
                                + ("Good again" if info["state"] == "RUN" else
                                   "BadOutOfService"))
            self._state = info["state"]
        self.syncs += 1

    # ------------------------------------------------------------------ client writes
    async def _pre_write(self, event: Any, _dispatcher: Any) -> None:
        """Refuse a write before it is stored: no right, not writable, out of range."""
        from asyncua import ua

        if not event.is_external:
            return
        for wv in event.request_params.NodesToWrite:
            tag = self.nodes.get(wv.NodeId.to_string())
            if tag is None or wv.AttributeId != ua.AttributeIds.Value:
                continue  # the address space refuses (AccessLevel) or it is not ours
            if not tag.writable:
                self.refused += 1
                raise ua.uaerrors.BadNotWritable
            value = wv.Value.Value.Value if wv.Value and wv.Value.Value else None
            try:
                from_ua(value, _scalar(tag))if tag.dims is None else [
                    from_ua(e, _scalar(tag)) for e in (value or [])]
            except ValueError as exc:
                self.refused += 1
                self.on_message(f"write refused: {tag.path} = {value!r} (needs {exc})")
                raise ua.uaerrors.BadOutOfRange from None

    async def _post_write(self, event: Any, _dispatcher: Any) -> None:
        """Apply the writes the address space accepted to the PLC, between two scans."""
        if not event.is_external:
            return
        for wv, res in zip(event.request_params.NodesToWrite, event.response_params or [],
                           strict=False):
            tag = self.nodes.get(wv.NodeId.to_string())
            if tag is None or not tag.writable or not res.is_good():
                continue
            value = wv.Value.Value.Value
            if tag.dims is None:
                plc_value = from_ua(value, _scalar(tag))
            else:
                plc_value = [from_ua(e, _scalar(tag)) for e in value]
            with self.runner.lock:
                tag.var.set(plc_value)
            self._written[tag.path] = self._written.get(tag.path, 0) + 1
            self._last.pop(tag.path, None)  # re-send what the PLC holds now
            self.writes += 1
            who = getattr(event.user, "name", None) or "anonymous"
            self.on_message(f"{who} wrote {tag.path} = {value!r}")


def _scalar(tag: Tag) -> Any:
    return T_elem(tag.ty) if tag.dims is not None else tag.ty


def T_elem(ty: Any) -> Any:  # noqa: N802 - the element type of an array type
    from plclab.lang import types as T

    r = T.resolve(ty)
    return r.elem if isinstance(r, T.ArrayType) else r


__all__ = ["GOOD", "NAMESPACE", "OpcUaServer", "need_asyncua"]
