"""Alarms as WinCC keeps them: discrete and analog alarms, classes, states, acknowledgement.

The model (``001_c648febd3bbd6efb.txt``, lines 5838-6075; ADR 0025):

* a **discrete alarm** comes when its trigger bit is TRUE (a BOOL tag, or bit ``bit`` of a
  WORD/INT tag, as WinCC's *Trigger -> Tag / Bit*);
* an **analog alarm** comes when its tag crosses a limit: ``HH``/``H`` above, ``L``/``LL``
  below; it goes only when the value is back by ``deadband`` (hysteresis), so a value that
  hovers at the limit does not make a stream of alarms;
* ``delay``: the condition must hold that long before the alarm comes (a short spike raises
  nothing);
* the **class** says whether the operator must acknowledge it: ``warning`` (no), ``error``
  (yes), ``system`` (no), or a custom class;
* the **states** are WinCC's (Tables 18 and 19): ``I`` incoming, ``IO`` outgoing not
  acknowledged, ``IA`` incoming acknowledged, ``IAO`` outgoing acknowledged first, ``IOA``
  outgoing subsequently acknowledged; an alarm without acknowledgement goes ``I`` -> ``IO``.
  ``IAO``, ``IOA`` and a warning's ``IO`` end the alarm: it leaves the list of pending alarms.

Every change is a :class:`LogEntry` stamped with the virtual clock.

>>> srv = AlarmServer([Alarm("LOW", "water level low", tag="LEVEL", limit=0.5, kind="L",
...                          deadband=0.05, alarm_class="error")])
>>> for t, level in [(0, 0.8), (1, 0.45), (2, 0.52), (3, 0.6)]:
...     srv.evaluate(t, {"LEVEL": level}.__getitem__)
>>> srv.acknowledge("LOW", t=4)
True
>>> [(e.time, e.state) for e in srv.log]
[(1.0, 'I'), (3.0, 'IO'), (4.0, 'IOA')]
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError
from plclab.process.files import read_toml


@dataclass(frozen=True)
class AlarmClass:
    """How alarms of a class are shown and whether they must be acknowledged."""

    name: str
    ack: bool
    color: str = "#ffffff"


CLASSES = {
    "warning": AlarmClass("warning", False, "#fff4c2"),
    "error": AlarmClass("error", True, "#ff4d4d"),
    "system": AlarmClass("system", False, "#c8d8ff"),
}
KINDS = ("discrete", "HH", "H", "L", "LL")
DEADBAND_MODES = ("outgoing", "incoming", "both")
STATE_TEXT = {
    "I": "incoming", "IO": "outgoing, not acknowledged", "IA": "incoming, acknowledged",
    "IAO": "outgoing, acknowledged first", "IOA": "outgoing, subsequently acknowledged",
}


@dataclass
class Alarm:
    """One alarm: its text, trigger (tag, kind, limit or bit), class, deadband and delay (s)."""

    id: str
    text: str
    tag: str
    kind: str = "discrete"
    limit: float | None = None
    bit: int | None = None
    deadband: float = 0.0
    delay: float = 0.0
    alarm_class: str = "warning"
    ack_tag: str | None = None  # a BOOL whose rising edge acknowledges (PLC or button)
    ack_bit: str | None = None  # a PLC BOOL the server sets TRUE while acknowledged
    deadband_mode: str = "outgoing"  # WinCC's Deadband -> Mode: outgoing, incoming or both

    def __post_init__(self) -> None:
        where = f"alarm {self.id}"
        if self.kind not in KINDS:
            raise PlcError("PLC6020", f"{where}: kind {self.kind!r} is unknown; use one of "
                           f"{', '.join(KINDS)}")
        if self.kind != "discrete" and not isinstance(self.limit, int | float):
            raise PlcError("PLC6020", f"{where}: an analog alarm ({self.kind}) needs a numeric "
                           "limit, e.g. limit = 0.5")
        if self.kind == "discrete" and self.limit is not None:
            raise PlcError("PLC6020", f"{where}: a discrete alarm has no limit; give kind = "
                           "\"H\" (or HH, L, LL) for an analog limit alarm")
        if self.bit is not None and not (isinstance(self.bit, int) and 0 <= self.bit < 32):
            raise PlcError("PLC6020", f"{where}: bit is a bit number 0..31, not {self.bit!r}")
        if self.deadband_mode not in DEADBAND_MODES:
            raise PlcError("PLC6020", f"{where}: deadband_mode is one of "
                           f"{', '.join(DEADBAND_MODES)}, not {self.deadband_mode!r}")
        if self.deadband < 0 or self.delay < 0:
            raise PlcError("PLC6020", f"{where}: deadband and delay are 0 or more")
        self._limits = self._thresholds()

    def _thresholds(self) -> tuple[float, float, bool] | None:
        """(comes beyond, goes back beyond, high?) of an analog alarm; None for a discrete one."""
        if self.kind == "discrete":
            return None
        assert self.limit is not None
        d_in = self.deadband if self.deadband_mode in ("incoming", "both") else 0.0
        d_out = self.deadband if self.deadband_mode in ("outgoing", "both") else 0.0
        if self.high:
            return self.limit + d_in, self.limit - d_out, True
        return self.limit - d_in, self.limit + d_out, False

    @property
    def high(self) -> bool:
        return self.kind in ("HH", "H")

    def violated(self, value: Any, active: bool) -> bool:
        """Whether the alarm condition holds for ``value``; ``active``: the alarm is on now
        (then an analog alarm holds until the value is back by the deadband)."""
        if self.kind == "discrete":
            if self.bit is not None:
                return bool(int(value) >> self.bit & 1)
            return bool(value)
        come, go, high = self._thresholds()  # type: ignore[misc]
        v = float(value)
        if high:
            return v >= go if active else v > come
        return v <= go if active else v < come


@dataclass
class LogEntry:
    """A change of an alarm's state at a virtual time."""

    time: float
    id: str
    text: str
    alarm_class: str
    state: str
    value: Any = None
    user: str = ""

    def __str__(self) -> str:
        return f"{self.time:10.3f} s  {self.id:<12} {self.state:<4} {self.alarm_class:<8} " \
               f"{self.text}"


@dataclass
class _Status:
    state: str = ""  # "" = no alarm
    since: float | None = None  # the condition holds since (for the delay)
    came: float | None = None
    ack_in: bool = False  # last value of the ack tag (for its rising edge)


@dataclass
class AlarmServer:
    """Evaluates alarms on each scan, keeps their states and the alarm log.

    ``evaluate(t, read)`` takes the virtual time in seconds and a function reading a tag;
    as a simulation hook (:meth:`plclab.sim.Simulation.add_hook`) it reads plant signals
    and PLC variables by itself, and writes the log into the Trace as ``alarm`` events.
    """

    alarms: list[Alarm]
    classes: dict[str, AlarmClass] = field(default_factory=lambda: dict(CLASSES))
    log: list[LogEntry] = field(default_factory=list)

    def __post_init__(self) -> None:
        seen = set()
        for a in self.alarms:
            if a.id in seen:
                raise PlcError("PLC6020", f"alarm {a.id} is defined twice; give each alarm its "
                               "own id")
            seen.add(a.id)
            if a.alarm_class not in self.classes:
                raise PlcError("PLC6020", f"alarm {a.id}: class {a.alarm_class!r} is unknown; "
                               f"use one of {', '.join(self.classes)} or define it under "
                               "[class.NAME]")
        self.status = {a.id: _Status() for a in self.alarms}
        self.now = 0.0
        self._writers: dict[str, Callable[[bool], None]] = {}
        self._acks: list[tuple[float, str | None, str]] = []

    # ---------------------------------------------------------------- the state machine
    def evaluate(self, t: float, read: Callable[[str], Any]) -> None:
        """Update every alarm at time ``t`` (s) from the tag values ``read`` returns."""
        self._evaluate(float(t), [(a, self.status[a.id], lambda a=a: read(a.tag),
                                   (lambda a=a: read(a.ack_tag)) if a.ack_tag else None)
                                  for a in self.alarms])

    def _evaluate(self, t: float, rows: list[tuple[Alarm, _Status, Any, Any]]) -> None:
        """One evaluation: ``rows`` holds each alarm, its status and its tag readers."""
        self.now = t
        if self._acks:
            while self._acks and self._acks[0][0] <= t + 1e-12:
                _, which, user = self._acks.pop(0)
                self.acknowledge(which, user=user)
        for a, st, get, get_ack in rows:
            if get_ack is not None:
                edge = bool(get_ack())
                if edge and not st.ack_in:
                    self.acknowledge(a.id, user=a.ack_tag or "")
                st.ack_in = edge
            value = get()
            state = st.state
            active = state == "I" or state == "IA"
            lim = a._limits
            if lim is not None:
                come, go, high = lim
                v = float(value)
                if high:
                    cond = v >= go if active else v > come
                else:
                    cond = v <= go if active else v < come
            elif a.bit is None:
                cond = bool(value)
            else:
                cond = a.violated(value, active)
            if active:
                if not cond:
                    self._leave(a, st, value)
                continue
            if not cond:
                st.since = None
                continue
            if st.since is None:
                st.since = self.now
            if self.now - st.since >= a.delay - 1e-9:
                st.state = "I"
                st.came = self.now
                self._enter(a, "I", value)
                self._write_ack(a, False)

    def _leave(self, a: Alarm, st: _Status, value: Any) -> None:
        st.since = None
        needs_ack = self.classes[a.alarm_class].ack
        st.state = "IAO" if st.state == "IA" else "IO" if needs_ack else ""
        self._enter(a, "IO" if not needs_ack else st.state, value)
        if st.state == "IAO" or not needs_ack:
            st.state = ""

    def _enter(self, a: Alarm, state: str, value: Any, user: str = "") -> None:
        if not isinstance(value, bool | int | float):
            value = None
        self.log.append(LogEntry(self.now, a.id, a.text, a.alarm_class, state, value, user))

    def acknowledge(self, alarm_id: str | None = None, t: float | None = None,
                    user: str = "operator") -> bool:
        """Acknowledge one alarm (or every pending one): ``I`` -> ``IA``, ``IO`` -> ``IOA``.
        Returns whether anything was acknowledged (a warning needs none)."""
        if t is not None:
            self.now = float(t)
        if alarm_id is not None and alarm_id not in self.status:
            raise PlcError("PLC6021", f"no alarm {alarm_id!r}; the alarms are "
                           f"{', '.join(self.status) or '(none)'}")
        done = False
        for a in self.alarms:
            if alarm_id is not None and a.id != alarm_id:
                continue
            st = self.status[a.id]
            if not self.classes[a.alarm_class].ack or st.state not in ("I", "IO"):
                continue
            new = "IA" if st.state == "I" else "IOA"
            self._enter(a, new, None, user)
            st.state = "IA" if new == "IA" else ""
            self._write_ack(a, True)
            done = True
        return done

    def schedule_ack(self, t: float, alarm_id: str | None = None,
                     user: str = "operator") -> None:
        """Acknowledge at virtual time ``t`` (s) during a simulation (a scripted operator)."""
        self._acks.append((float(t), alarm_id, user))
        self._acks.sort(key=lambda x: x[0])

    def _write_ack(self, a: Alarm, value: bool) -> None:
        w = self._writers.get(a.id)
        if w is not None:
            w(value)

    # ---------------------------------------------------------------- views
    def pending(self) -> list[tuple[Alarm, str]]:
        """Alarms still shown: active ones and gone ones waiting for acknowledgement."""
        return [(a, self.status[a.id].state) for a in self.alarms if self.status[a.id].state]

    def state(self, alarm_id: str) -> str:
        """``""`` (no alarm), ``I``, ``IA`` or ``IO``."""
        return self.status[alarm_id].state

    def by_id(self, alarm_id: str) -> Alarm:
        for a in self.alarms:
            if a.id == alarm_id:
                return a
        raise PlcError("PLC6021", f"no alarm {alarm_id!r}; the alarms are "
                       f"{', '.join(self.status) or '(none)'}")

    # ---------------------------------------------------------------- files
    @classmethod
    def load(cls, path: str | Path) -> AlarmServer:
        """Read an alarm configuration (TOML: ``[[alarm]]`` rows, optional ``[class.NAME]``)."""
        return cls.from_dict(read_toml(path, "PLC6020", "alarm file"), str(path))

    @classmethod
    def from_dict(cls, data: dict[str, Any], source: str = "alarms") -> AlarmServer:
        classes = dict(CLASSES)
        for name, c in (data.get("class") or {}).items():
            if not isinstance(c, dict) or not isinstance(c.get("ack"), bool):
                raise PlcError("PLC6020", f"{source}: [class.{name}] needs ack = true or false")
            classes[name] = AlarmClass(name, c["ack"], str(c.get("color", "#ffffff")))
        fields = {"id", "text", "tag", "kind", "limit", "bit", "deadband", "deadband_mode",
                  "delay", "class", "ack_tag", "ack_bit"}
        alarms = []
        for i, row in enumerate(data.get("alarm", []), 1):
            if not isinstance(row, dict) or not {"id", "text", "tag"} <= set(row):
                raise PlcError("PLC6020", f"{source}: [[alarm]] {i} needs id, text and tag")
            bad = set(row) - fields
            if bad:
                raise PlcError("PLC6020", f"{source}: alarm {row['id']}: unknown key(s) "
                               f"{', '.join(sorted(bad))}; an alarm has "
                               f"{', '.join(sorted(fields))}")
            from plclab.durations import parse_duration

            delay = row.get("delay", 0)
            if isinstance(delay, str):
                ns = parse_duration(delay)
                if ns is None:
                    raise PlcError("PLC6020", f"{source}: alarm {row['id']}: delay {delay!r} is "
                                   "not a duration (e.g. \"2s\")")
                delay = ns / 1e9
            alarms.append(Alarm(str(row["id"]), str(row["text"]), str(row["tag"]),
                                str(row.get("kind", "discrete")), row.get("limit"),
                                row.get("bit"), _deadband(row, source), float(delay),
                                str(row.get("class", "warning")), row.get("ack_tag"),
                                row.get("ack_bit"), str(row.get("deadband_mode", "outgoing"))))
        if not alarms:
            raise PlcError("PLC6020", f"{source}: no [[alarm]] defined")
        return cls(alarms, classes)

    # ---------------------------------------------------------------- simulation hook
    def bind(self, sim: Any) -> None:
        """Simulation hook: read plant signals and PLC variables each scan."""
        self._readers: dict[str, Callable[[], Any]] = {}
        tags = {a.tag for a in self.alarms} | {a.ack_tag for a in self.alarms if a.ack_tag}
        for tag in tags:
            if tag in sim.plant.signals:
                self._readers[tag] = (lambda n=tag: sim.plant.read(n))
                continue
            try:
                self._readers[tag] = sim.plc.var(tag).get
            except PlcError as e:
                raise PlcError("PLC6020", f"alarm tag {tag}: neither a signal of "
                               f"'{sim.plant.name}' nor a PLC variable ({e.message})") from None
        self._rows = [(a, self.status[a.id], self._readers[a.tag],
                       self._readers[a.ack_tag] if a.ack_tag else None) for a in self.alarms]
        for a in self.alarms:
            if a.ack_bit:
                try:
                    v = sim.plc.var(a.ack_bit)
                except PlcError as e:
                    raise PlcError("PLC6020", f"alarm {a.id}: ack_bit {a.ack_bit}: "
                                   f"{e.message}") from None
                self._writers[a.id] = v.set

    def after_scan(self, sim: Any, t_ns: int, recorded: bool) -> None:
        self._evaluate(t_ns / 1e9, self._rows)

    def finish(self, sim: Any) -> tuple[list[Any], dict[str, Any]]:
        from plclab.trace.events import Event

        events = [Event(e.time, "alarm", e.id, f"{e.state} ({STATE_TEXT[e.state]}): {e.text}",
                        {"state": e.state, "class": e.alarm_class, "user": e.user,
                         **({"value": e.value} if e.value is not None else {})})
                  for e in self.log]
        meta = {"alarms": [{"id": a.id, "text": a.text, "tag": a.tag, "kind": a.kind,
                            "limit": a.limit, "class": a.alarm_class,
                            "ack": self.classes[a.alarm_class].ack} for a in self.alarms]}
        return events, meta


def _deadband(row: dict[str, Any], source: str) -> float:
    """``deadband = 0.5`` (in the tag's unit) or ``"2%"`` of the limit, as WinCC gives it."""
    db = row.get("deadband", 0.0)
    if isinstance(db, str) and db.strip().endswith("%"):
        try:
            pct = float(db.strip()[:-1])
        except ValueError:
            pct = -1.0
        lim = row.get("limit")
        if pct < 0 or not isinstance(lim, int | float):
            raise PlcError("PLC6020", f"{source}: alarm {row['id']}: deadband {db!r}: give a "
                           "percentage of a numeric limit (\"2%\") or a value (0.5)")
        return abs(float(lim)) * pct / 100.0
    if isinstance(db, bool) or not isinstance(db, int | float):
        raise PlcError("PLC6020", f"{source}: alarm {row['id']}: deadband is a number (0.5) "
                       f"or a percentage of the limit (\"2%\"), not {db!r}")
    return float(db)


def alarm_log(trace: Any, alarm_id: str | None = None) -> list[LogEntry]:
    """The alarm log of a Trace (its ``alarm`` events) as :class:`LogEntry` rows."""
    out = []
    for e in trace.events:
        if e.kind != "alarm" or (alarm_id is not None and e.source != alarm_id):
            continue
        out.append(LogEntry(e.time, e.source, e.message.partition(": ")[2],
                            str(e.data.get("class", "")), str(e.data.get("state", "")),
                            e.data.get("value"), str(e.data.get("user", ""))))
    return out
