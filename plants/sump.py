"""Mine dewatering station: a sump, a priming pump and three main pumps (textbook Fig. 120-121).

The signal names are the variables of the textbook's ST program, so that program drives the
plant unchanged::

    if NY then
        ZAL := not(DAWL);
        if WY and not(NS1) then NS1 := true; END_IF;
        if (PWY or TNS1) and not(NS2) then NS2 := true; END_IF;
        if (AWY or TNS2) and not(NS3) then NS3 := true; END_IF;
    end_if;
    if not(NY) then NS1 := false; NS2 := false; NS3 := false; ZAL := false; END_IF;

========  ==========================================================  ===========
Signal    Meaning (Russian abbreviation)                              Kind
========  ==========================================================  ===========
NY        low level switch (НУ, нижний уровень)                       sensor
WY        high level switch (ВУ, верхний уровень)                     sensor
PWY       raised high level switch (ПВУ, повышенный верхний)          sensor
AWY       emergency high level switch (АВУ, аварийный верхний)        sensor
DAWL      pressure switch: water in the pump system (давление)        sensor
ZAL       priming (vacuum) pump (заливочный насос)                    actuator
NS1..NS3  main pumps 1..3 (насос)                                     actuator
========  ==========================================================  ===========

All level switches are ``True`` when the water is at or above them.

Physics
-------
Sump volume balance ``A dh/dt = q_in - sum(q_i)``. Centrifugal pumps cannot lift water until
their suction line and casing are full: the priming pump ``ZAL`` fills them in
``priming_time`` seconds of running (only while the intake is submerged, i.e. the level is above
``intake_height``). Then ``DAWL`` becomes ``True``. The system stays primed while a main pump runs
and for ``prime_hold`` seconds of standstill (the foot valve leaks), and loses its prime at once
if a running pump sucks air (level below the intake).

A primed pump ``i`` delivers ``q_i = s_i * q_nom * sqrt((h0 - H) / (h0 - h_nom))`` where the
static head is ``H = lift - level`` and ``s_i`` is the motor speed (first-order lag
``pump_tau``); this is the crossing of a quadratic pump curve ``H = h0 - c q^2`` with a flat
system curve. Each pump has its own rising main.

The inflow is a profile (constant, table or function) times a slowly wandering seeded factor
``1 + inflow_noise * x`` where ``x`` is an Ornstein-Uhlenbeck process (one-minute correlation
time), updated once a second.

Events: ``pump_dry_run`` (a main pump started without prime), ``lost_prime``, ``primed``,
``emergency_level`` (water reached AWY), ``flooded`` (water over the sump rim, counted as
overflow volume).
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, ProfileSpec, StepProfile, bool_signal, real_signal

__all__ = ["Sump"]


class Sump(Plant):
    """Mine sump with priming pump ZAL, pressure switch DAWL and main pumps NS1..NS3.

    Parameters
    ----------
    area : float
        Sump cross-section, m2.
    depth : float
        Depth to the rim, m.
    level0 : float
        Level after reset, m.
    intake_height : float
        Height of the pumps' suction intake, m (below ``ny_height``).
    ny_height, wy_height, pwy_height, awy_height : float
        Heights of the level switches NY < WY < PWY < AWY, m.
    inflow : float, list of (time_s, m3/s) or callable
        Mean water inflow.
    inflow_noise : float
        Relative amplitude of the random inflow variation (0 = none).
    lift : float
        Height from the sump bottom to the discharge, m.
    pump_q_nom, pump_h_nom : float
        Nominal point of a main pump: flow m3/s at head m.
    pump_h0 : float
        Shut-off head of a main pump, m.
    pump_tau : float
        Spin-up/spin-down time constant of a main pump, s.
    priming_time : float
        Running time of ZAL needed to prime the system, s.
    prime_hold : float
        How long an idle primed system keeps its prime, s.
    max_dt : float
        Largest integration step, s.
    """

    name = "sump"
    title = "Mine dewatering station: sump, priming pump and three main pumps"
    EVENTS = {
        "primed": "the priming pump filled the system: DAWL closes",
        "lost_prime": "the system lost its prime (air sucked in or idle too long)",
        "pump_dry_run": "a main pump was started without prime",
        "emergency_level": "the water reached the emergency level AWY",
        "flooded": "the sump overflowed into the mine workings",
    }
    FAULTS = {
        "pump1_fail": "main pump 1 runs but delivers nothing (broken impeller)",
        "pump2_fail": "main pump 2 runs but delivers nothing (broken impeller)",
        "pump3_fail": "main pump 3 runs but delivers nothing (broken impeller)",
        "priming_fail": "the priming pump ZAL does not prime the system",
        "pressure_switch_stuck": "DAWL is stuck (param value: bool, default FALSE)",
        "inflow_surge": "inflow multiplied by param factor (default 3.0)",
    }

    def __init__(
        self,
        *,
        area: float = 12.0,
        depth: float = 5.0,
        level0: float = 0.2,
        intake_height: float = 0.3,
        ny_height: float = 0.6,
        wy_height: float = 2.0,
        pwy_height: float = 3.0,
        awy_height: float = 4.0,
        inflow: ProfileSpec = 0.02,
        inflow_noise: float = 0.15,
        lift: float = 100.0,
        pump_q_nom: float = 0.03,
        pump_h_nom: float = 100.0,
        pump_h0: float = 125.0,
        pump_tau: float = 3.0,
        priming_time: float = 20.0,
        prime_hold: float = 1800.0,
        max_dt: float = 0.5,
    ) -> None:
        if not 0 <= intake_height < ny_height < wy_height < pwy_height < awy_height <= depth:
            raise PlantError(
                "sump: need 0 <= intake_height < ny_height < wy_height < pwy_height < "
                "awy_height <= depth"
            )
        if area <= 0 or pump_h0 <= pump_h_nom or pump_q_nom <= 0 or priming_time <= 0:
            raise PlantError("sump: need area > 0, pump_h0 > pump_h_nom, pump_q_nom > 0")
        self.area = float(area)
        self.depth = float(depth)
        self.level0 = float(level0)
        self.intake_height = float(intake_height)
        self.heights = (float(ny_height), float(wy_height), float(pwy_height), float(awy_height))
        self.inflow = StepProfile(inflow, "sump inflow")
        self.inflow_noise = float(inflow_noise)
        self.lift = float(lift)
        self.pump_q_nom = float(pump_q_nom)
        self.pump_h_nom = float(pump_h_nom)
        self.pump_h0 = float(pump_h0)
        self.pump_tau = float(pump_tau)
        self.priming_time = float(priming_time)
        self.prime_hold = float(prime_hold)
        self.max_dt = float(max_dt)
        self._vmax = self.area * self.depth
        self._c = 1.0 / (self.pump_h0 - self.pump_h_nom)
        super().__init__(
            [
                bool_signal("NY", "sensor", "low level switch (НУ)"),
                bool_signal("WY", "sensor", "high level switch (ВУ)"),
                bool_signal("PWY", "sensor", "raised high level switch (ПВУ)"),
                bool_signal("AWY", "sensor", "emergency high level switch (АВУ)"),
                bool_signal("DAWL", "sensor", "pressure switch: pump system primed with water"),
                real_signal("LEVEL", "sensor", "m", 0, self.depth, "sump level (for recording)"),
                bool_signal("ZAL", "actuator", "priming (vacuum) pump"),
                bool_signal("NS1", "actuator", "main pump 1"),
                bool_signal("NS2", "actuator", "main pump 2"),
                bool_signal("NS3", "actuator", "main pump 3"),
            ]
        )

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.volume = self.level0 * self.area
        self.volume0 = self.volume
        self.speeds = [0.0, 0.0, 0.0]
        self.flows = [0.0, 0.0, 0.0]
        self.q_in = 0.0
        self.prime = 0.0  # priming progress 0..1
        self.primed = False
        self._idle = 0.0
        self._dry_flag = [False, False, False]
        self._noise = 0.0
        self._noise_next = 0.0
        self._awy_flag = False
        self._flood_flag = False
        self.volume_in = 0.0
        self.volume_out = 0.0
        self.volume_overflow = 0.0
        self.pump_seconds = [0.0, 0.0, 0.0]
        self.inflow.reset()

    def _faults_changed(self) -> None:
        f = self._faults
        self._pump_ok = ["pump1_fail" not in f, "pump2_fail" not in f, "pump3_fail" not in f]
        surge = f.get("inflow_surge")
        self._surge = 1.0 if surge is None else float(surge.get("factor", 3.0))
        stuck = f.get("pressure_switch_stuck")
        self._dawl_stuck: bool | None = None if stuck is None else bool(stuck.get("value", False))

    def _pump_flow(self, level: float) -> float:
        head = self.lift - level
        x = (self.pump_h0 - head) * self._c
        return self.pump_q_nom * math.sqrt(x) if x > 0.0 else 0.0

    def _advance(self, h: float) -> None:
        io = self._io
        t = self.time
        lvl = self.volume / self.area
        # inflow with seeded slow variation (Ornstein-Uhlenbeck, updated every second)
        if self.inflow_noise and t >= self._noise_next:
            self._noise_next = t + 1.0
            a = 1.0 / 60.0
            self._noise += -a * self._noise + math.sqrt(2.0 * a) * self.rng.gauss(0.0, 1.0)
        q_in = self.inflow(t) * self._surge * (1.0 + self.inflow_noise * self._noise)
        if q_in < 0.0:
            q_in = 0.0
        self.q_in = q_in
        # priming
        submerged = lvl > self.intake_height
        if io["ZAL"] and submerged and "priming_fail" not in self._faults and not self.primed:
            self.prime += h / self.priming_time
            if self.prime >= 1.0:
                self.prime = 1.0
                self.primed = True
                self._emit("primed", "the pump system is primed: DAWL closes")
        cmds = (io["NS1"], io["NS2"], io["NS3"])
        running = cmds[0] or cmds[1] or cmds[2]
        if self.primed:
            if running and not submerged:
                self._lose_prime("a running pump sucked air: the system lost its prime")
            elif not running and not io["ZAL"]:
                self._idle += h
                if self._idle >= self.prime_hold:
                    self._lose_prime("the idle system drained through the foot valve")
            else:
                self._idle = 0.0
        q_base = self._pump_flow(lvl) if self.primed else 0.0
        q_out = 0.0
        speeds = self.speeds
        flows = self.flows
        for i in range(3):
            s = speeds[i]
            on = cmds[i]
            if on:
                self.pump_seconds[i] += h
                if not self.primed and not self._dry_flag[i]:
                    self._dry_flag[i] = True
                    self._emit(
                        "pump_dry_run",
                        f"main pump {i + 1} runs without prime (DAWL is FALSE): no delivery",
                        pump=i + 1,
                    )
            elif self._dry_flag[i]:
                self._dry_flag[i] = False
            target = 1.0 if on else 0.0
            if s != target:
                s += (target - s) * (h / self.pump_tau if h < self.pump_tau else 1.0)
                if -1e-6 < s - target < 1e-6:
                    s = target
                speeds[i] = s
            q = s * q_base if self._pump_ok[i] else 0.0
            flows[i] = q
            q_out += q
        vin = q_in * h
        vout = q_out * h
        v = self.volume + vin
        if vout > v:
            vout = v
        v -= vout
        self.volume_in += vin
        self.volume_out += vout
        if v > self._vmax:
            self.volume_overflow += v - self._vmax
            v = self._vmax
            if not self._flood_flag:
                self._flood_flag = True
                self._emit("flooded", "the sump overflowed into the mine workings")
        elif self._flood_flag and v < self._vmax - 0.05 * self.area:
            self._flood_flag = False
        self.volume = v
        lvl = v / self.area
        if lvl >= self.heights[3]:
            if not self._awy_flag:
                self._awy_flag = True
                self._emit(
                    "emergency_level", "the water reached the emergency level AWY", level=lvl
                )
        elif self._awy_flag and lvl < self.heights[3] - 0.05:
            self._awy_flag = False

    def _lose_prime(self, why: str) -> None:
        self.primed = False
        self.prime = 0.0
        self._idle = 0.0
        self._emit("lost_prime", why)

    def _outputs(self) -> None:
        io = self._io
        lvl = self.volume / self.area
        hs = self.heights
        io["NY"] = lvl >= hs[0]
        io["WY"] = lvl >= hs[1]
        io["PWY"] = lvl >= hs[2]
        io["AWY"] = lvl >= hs[3]
        io["DAWL"] = self.primed if self._dawl_stuck is None else self._dawl_stuck
        io["LEVEL"] = lvl

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Volumes (mass balance), flows, priming progress and pump running hours."""
        out = {
            "volume": self.volume,
            "volume0": self.volume0,
            "volume_in": self.volume_in,
            "volume_out": self.volume_out,
            "volume_overflow": self.volume_overflow,
            "q_in": self.q_in,
            "prime": self.prime,
        }
        for i in range(3):
            out[f"q_pump{i + 1}"] = self.flows[i]
            out[f"speed{i + 1}"] = self.speeds[i]
            out[f"pump{i + 1}_seconds"] = self.pump_seconds[i]
        return out

    def geometry(self) -> dict[str, Any]:
        w = math.sqrt(self.area)
        names = ("NY", "WY", "PWY", "AWY")
        shapes: list[dict[str, Any]] = [
            {"type": "rect", "name": "sump", "x": 0.0, "y": 0.0, "w": w, "h": self.depth}
        ]
        shapes += [
            {"type": "mark", "name": n, "x": w, "y": y}
            for n, y in zip(names, self.heights, strict=True)
        ]
        shapes.append({"type": "mark", "name": "intake", "x": 0.0, "y": self.intake_height})
        return {"shapes": shapes, "fill": {"signal": "LEVEL", "x": 0.0, "y": 0.0, "w": w}}
