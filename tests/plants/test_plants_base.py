"""The shared plant machinery: registry, signal validation, faults, events, determinism."""

from __future__ import annotations

import math

import pytest

import plants
from plants import PLANTS, Plant, PlantError, StepProfile, get_plant, list_plants

ALL = list_plants()


def test_registry_lists_all_plants() -> None:
    assert ALL == ["motor", "tank", "sump", "heater", "conveyor", "ventilation", "press", "washer",
                   "axes", "crossing"]
    for name, cls in PLANTS.items():
        assert cls.name == name
        assert issubclass(cls, Plant)
        assert cls.title


def test_plants_never_import_plclab() -> None:
    import pathlib

    for path in pathlib.Path(plants.__file__).parent.glob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "import plclab" not in text and "from plclab" not in text, path.name


def test_unknown_plant_suggests_a_name() -> None:
    with pytest.raises(ValueError, match=r"Did you mean 'tank'") as exc:
        get_plant("tnak")
    assert "Known plants" in str(exc.value)


def test_unknown_parameter_suggests_a_name() -> None:
    with pytest.raises(PlantError, match=r"'area'"):
        get_plant("tank", aera=2.0)


@pytest.mark.parametrize("name", ALL)
def test_signal_table_is_consistent(name: str) -> None:
    p = get_plant(name)
    sigs = p.signals
    assert sigs, name
    for s in sigs.values():
        assert s.kind in ("sensor", "actuator", "panel", "lamp")
        assert s.type in ("bool", "real")
        assert s.range[0] <= s.range[1]
        assert s.description
        v = p.read(s.name)
        if s.type == "bool":
            assert isinstance(v, bool), s.name
        else:
            assert isinstance(v, float), s.name
    assert p[next(iter(sigs))] == p.read(next(iter(sigs)))
    assert p.faults == type(p).FAULTS and p.faults
    assert isinstance(p.snapshot(), dict)
    assert all(isinstance(v, float) for v in p.snapshot().values())
    assert isinstance(p.geometry(), dict)


@pytest.mark.parametrize("name", ALL)
def test_writing_a_sensor_raises(name: str) -> None:
    p = get_plant(name)
    sensor = next(s.name for s in p.signals.values() if s.kind == "sensor")
    with pytest.raises(ValueError, match="can only be read"):
        p.write(sensor, True)
    with pytest.raises(ValueError, match="can only be read"):
        p[sensor] = 1.0


@pytest.mark.parametrize("name", ALL)
def test_unknown_signal_and_fault(name: str) -> None:
    p = get_plant(name)
    with pytest.raises(ValueError, match="has no signal 'NOPE'"):
        p.read("NOPE")
    with pytest.raises(ValueError, match="has no signal"):
        p.write("NOPE", True)
    with pytest.raises(ValueError, match="Valid faults: ") as exc:
        p.inject("no_such_fault")
    for f in p.faults:
        assert f in str(exc.value)
    with pytest.raises(ValueError, match="Valid faults"):
        p.clear("no_such_fault")


def test_did_you_mean_for_signals_and_faults() -> None:
    tank = get_plant("tank")
    with pytest.raises(ValueError, match="Did you mean 'LS1'"):
        tank.read("LS_1")
    with pytest.raises(ValueError, match="Did you mean 'pump_fail'"):
        tank.inject("pump_fial")


def test_write_validation_and_clipping() -> None:
    tank = get_plant("tank")
    tank.write("PUMP", 1)
    assert tank.read("PUMP") is True
    tank.write("PUMP", 0.0)
    assert tank.read("PUMP") is False
    with pytest.raises(ValueError, match="BOOL"):
        tank.write("PUMP", "yes")
    tank.write("PUMP_SPEED", 150)
    assert tank.read("PUMP_SPEED") == 100.0
    tank.write("PUMP_SPEED", -5)
    assert tank.read("PUMP_SPEED") == 0.0
    with pytest.raises(ValueError, match="REAL"):
        tank.write("PUMP_SPEED", "fast")
    with pytest.raises(ValueError, match="NaN"):
        tank.write("PUMP_SPEED", math.nan)


@pytest.mark.parametrize("name", ALL)
def test_every_fault_injects_and_clears(name: str) -> None:
    p = get_plant(name)
    for f in p.faults:
        p.inject(f)
        assert f in p.active_faults
        p.step(0.05)
        p.clear(f)
        assert f not in p.active_faults
        p.clear(f)  # clearing twice is harmless
    kinds = [e.kind for e in p.drain_events()]
    assert kinds.count("fault_injected") == len(p.faults)
    assert p.drain_events() == []


@pytest.mark.parametrize("name", ALL)
def test_reset_restores_initial_state(name: str) -> None:
    p = get_plant(name)
    first = p.values()
    snap = p.snapshot()
    for s in p.signals.values():
        if s.kind == "actuator" and s.type == "bool":
            p.write(s.name, True)
    p.inject(next(iter(p.faults)))
    for _ in range(50):
        p.step(0.02)
    p.reset(0)
    assert p.time == 0.0
    assert p.active_faults == {}
    assert p.drain_events() == []
    assert p.values() == first
    assert _same(p.snapshot(), snap)


def _same(a: dict[str, float], b: dict[str, float]) -> bool:
    if a.keys() != b.keys():
        return False
    return all((math.isnan(x) and math.isnan(b[k])) or x == b[k] for k, x in a.items())


def _drive(p: Plant, seconds: float, dt: float) -> list[tuple]:
    """Switch every bool actuator on and off in a fixed pattern, record all values."""
    acts = [s.name for s in p.signals.values() if s.kind == "actuator" and s.type == "bool"]
    rec = []
    n = int(round(seconds / dt))
    for k in range(n):
        for i, a in enumerate(acts):
            p.write(a, ((k // (37 + 11 * i)) % 2) == 0)
        p.step(dt)
        rec.append(tuple(p.values().values()) + tuple(sorted(p.snapshot().items())))
    return rec


@pytest.mark.parametrize("name", ALL)
def test_same_seed_same_run(name: str) -> None:
    a = get_plant(name)
    b = get_plant(name)
    a.reset(7)
    b.reset(7)
    ra = _drive(a, 6.0, 0.01)
    rb = _drive(b, 6.0, 0.01)
    assert repr(ra) == repr(rb)  # repr: NaN-safe comparison
    a.reset(7)
    assert repr(_drive(a, 6.0, 0.01)) == repr(ra)


@pytest.mark.parametrize("name", ["sump", "ventilation", "conveyor"])
def test_different_seed_differs_where_random(name: str) -> None:
    a = get_plant(name)
    b = get_plant(name)
    a.reset(1)
    b.reset(2)
    assert repr(_drive(a, 8.0, 0.01)) != repr(_drive(b, 8.0, 0.01))


@pytest.mark.parametrize("name", ALL)
def test_large_steps_are_substepped(name: str) -> None:
    p = get_plant(name)
    p.step(3 * p.max_dt + 1e-4)
    assert p.time == pytest.approx(3 * p.max_dt + 1e-4)
    with pytest.raises(ValueError, match="dt"):
        p.step(-1.0)
    p.step(0.0)


def test_step_profile() -> None:
    p = StepProfile([(0.0, 1.0), (10.0, 2.0), (20.0, 0.5)])
    assert [p(t) for t in (0.0, 5.0, 10.0, 15.0, 25.0)] == [1.0, 1.0, 2.0, 2.0, 0.5]
    assert p(3.0) == 1.0  # going back in time works too
    assert StepProfile(None).is_zero
    assert StepProfile(3)(100.0) == 3.0
    assert StepProfile(lambda t: 2 * t)(4.0) == 8.0
    assert StepProfile([(5.0, 1.0)])(1.0) == 0.0
    with pytest.raises(ValueError, match="increase"):
        StepProfile([(5.0, 1.0), (1.0, 2.0)])
    with pytest.raises(ValueError, match="pairs"):
        StepProfile(["x"])


def test_signal_table_markdown() -> None:
    md = plants.signal_table("tank")
    assert "| `LS1` | sensor | bool |" in md


@pytest.mark.parametrize("name", ALL)
def test_every_emitted_event_kind_is_declared(name: str) -> None:
    import inspect
    import re

    cls = PLANTS[name]
    src = inspect.getsource(inspect.getmodule(cls))
    emitted = set(re.findall(r'_emit\(\s*"([a-z_]+)"', src))
    declared = set(get_plant(name).events)
    assert emitted <= declared, emitted - declared
    assert set(cls.EVENTS) <= emitted  # nothing declared that never happens


def test_readme_tables_match_the_code() -> None:
    import pathlib

    readme = (pathlib.Path(plants.__file__).parent / "README.md").read_text(encoding="utf-8")
    for name in ALL:
        assert plants.signal_table(name) in readme, f"plants/README.md: {name} table is stale"
