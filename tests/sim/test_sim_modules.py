"""The wirings and the simulation read the module kinds from their one specification
(plclab.io.modules.KINDS): every kind the course wires is specified, every specified kind is
wired and moved, and one entry is all a new kind needs."""

from __future__ import annotations

import os
import tomllib
from pathlib import Path

import pytest

import plclab
from plants import list_plants
from plclab.errors import PlcError
from plclab.grade.courseware import courseware_root
from plclab.grade.lab import list_labs, load_lab
from plclab.io.modules import KINDS, ModuleKind, Param
from plclab.sim import Scenario, Simulation, Wiring, default_wiring
from plclab.sim.wirings import DEFAULTS

_SKIP_DIRS = {"tests", "node_modules", "build", "dist", "site", "_site", "__pycache__"}


def course_wirings() -> list[tuple[str, Wiring]]:
    """Every wiring of the course, read by its loaders: the labs' (load_lab), the plants'
    defaults, and every TOML file of the courseware with a wiring array (wherever it lives)."""
    out = [(f"default wiring of {p}", default_wiring(p)) for p in list_plants() if p in DEFAULTS]
    out += [(lab.name, load_lab(lab).wiring) for lab in list_labs()]
    root = courseware_root()
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if not d.startswith(".") and d not in _SKIP_DIRS]
        for f in files:
            if not f.endswith(".toml"):
                continue
            path = Path(folder) / f
            try:
                data = tomllib.loads(path.read_text(encoding="utf-8"))
            except (tomllib.TOMLDecodeError, UnicodeDecodeError):
                continue
            rows = data.get("wiring")
            if isinstance(rows, list) and rows and all(isinstance(r, dict) for r in rows):
                out.append((str(path.relative_to(root)), Wiring.from_rows(rows, source=str(path))))
    return out


@pytest.fixture(scope="module")
def wirings():
    return course_wirings()


def unwired(wirings: list[tuple[str, Wiring]]) -> list[str]:
    """The specified module kinds no wiring uses; every row's kind must be specified."""
    used = set()
    for where, w in wirings:
        for row in w:
            assert row.module in KINDS, f"{where}: module {row.module!r} is not specified"
            used.add(row.module)
    return [k for k in KINDS if k not in used]


def test_every_wired_kind_is_specified_and_every_kind_is_wired(wirings):
    files = [w for w, _ in wirings if w.endswith(".toml")]
    assert any("lab.toml" in f for f in files) and len(files) > len(list_labs())  # found them
    assert unwired(wirings) == [], "module kinds that no wiring of the course uses"


def test_a_kind_nobody_wires_is_found(wirings, fake_kinds, monkeypatch):
    assert unwired(wirings) == ["xin", "xout"]
    monkeypatch.delitem(KINDS, "di")
    with pytest.raises(AssertionError, match="module 'di' is not specified"):
        unwired(wirings)


# --------------------------------------------------------------------------- every kind moves
TANK = """PROGRAM Main
VAR
  LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; lvl AT %IW64 : INT;
  speed AT %QW64 : INT;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
speed := 13824;
END_PROGRAM"""
BASE = [{"plc": "%IX0.0", "signal": "LS1", "module": "direct"},
        {"plc": "%IX0.1", "signal": "LS2", "module": "direct"},
        {"plc": "%QX0.0", "signal": "PUMP", "module": "direct"}]


def _follows(plc_side: str, plant_side: str):
    def check(tr):
        plc_v, plant_v = tr[plc_side], tr[plant_side]
        assert plant_v.any() and not plant_v.all(), f"{plant_side} never changed"
        assert (plc_v == plant_v).mean() > 0.95, f"{plc_side} does not follow {plant_side}"
    return check


def _counts(tr):
    for t in (1.0, 30.0, 90.0):
        assert tr.value_at("%IW64", t) == round(tr.value_at("LEVEL", t) / 2 * 27648), t


def _speed(tr):  # 13824 counts of 27648: 50 % of 0..100
    assert tr.value_at("PUMP_SPEED", 1.0) == pytest.approx(50.0, abs=0.01)


# one row per module kind on the tank: the row, its PLC side, and what it must do
ROWS = {
    "di": ({"plc": "%IX0.0", "signal": "LS1"}, "%IX0.0", _follows("%IX0.0", "LS1")),
    "ai": ({"plc": "%IW64", "signal": "LEVEL", "lo": 0, "hi": 2}, "%IW64", _counts),
    "do": ({"plc": "%QX0.0", "signal": "PUMP", "kind": "relay"}, "%QX0.0",
           _follows("%QX0.0", "PUMP")),
    "ao": ({"plc": "%QW64", "signal": "PUMP_SPEED", "lo": 0, "hi": 100}, "%QW64", _speed),
    "direct": ({"plc": "%IX0.0", "signal": "LS1"}, "%IX0.0", _follows("%IX0.0", "LS1")),
}


def rows_with(name: str) -> list[dict]:
    row = {**ROWS[name][0], "module": name}
    return [r for r in BASE if r["plc"] != row["plc"]] + [row]


def test_every_kind_has_a_row_here():
    assert set(ROWS) == set(KINDS), "add a tank row for the new module kind to ROWS"


@pytest.mark.parametrize("name", list(ROWS))
def test_every_kind_moves_its_signal(name):
    tr = Simulation(plclab.loads(TANK), "tank", rows_with(name)).run("2min")
    ROWS[name][2](tr)


@pytest.mark.parametrize("name, fault", [(n, f) for n, k in KINDS.items() for f in k.faults])
def test_every_fault_of_every_kind_injects_from_a_scenario(name, fault):
    plc_side = ROWS[name][1]
    sc = Scenario().io_fault(plc_side, fault, at="2s").io_clear(plc_side, at="4s")
    sim = Simulation(plclab.loads(TANK), "tank", rows_with(name), scenario=sc)
    tr = sim.run("5s")
    events = [(e.kind, e.source) for e in tr.events if e.kind.startswith("io_")]
    assert events == [("io_fault", plc_side), ("io_clear", plc_side)]


def test_a_fault_the_kind_does_not_have_is_refused_with_its_own():
    sc = Scenario().io_fault(ROWS["ai"][1], "welded", at="1s")
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", rows_with("ai"), scenario=sc).run("2s")
    assert e.value.code == "PLC4014"
    assert all(f in e.value.message for f in KINDS["ai"].faults)


# --------------------------------------------------------------------------- a new kind
class _Scaled:
    """A fake input module: counts = gain * value, -1 while "dead"."""

    def __init__(self, gain: float) -> None:
        self.gain, self.fault = gain, None

    def sample(self, t: float, value: float) -> int:
        return -1 if self.fault else round(self.gain * value)

    def inject(self, fault: str, value: float | None = None) -> None:
        self.fault = fault

    def clear(self) -> None:
        self.fault = None


class _Follow:
    """A fake output module: the actuator follows the bit."""

    fault = None

    def apply(self, t: float, command: bool) -> bool:
        return bool(command)


FAKE_IN = ModuleKind("xin", "in", "fake input: counts = gain * value", "real", "counts",
                     {"gain": Param("number", "counts per engineering unit")},
                     {"dead": "reads -1"}, "sampled", lambda p, sig: _Scaled(p.get("gain", 1.0)))
FAKE_OUT = ModuleKind("xout", "out", "fake output: the bit as it is", "bool", "bit", {}, {},
                      "on_change", lambda p, sig: _Follow())
FAKE_ROWS = [{"plc": "%IW64", "signal": "LEVEL", "module": "xin", "gain": 10000},
             {"plc": "%QX0.0", "signal": "PUMP", "module": "xout"}]


@pytest.fixture
def fake_kinds(monkeypatch):
    monkeypatch.setitem(KINDS, "xin", FAKE_IN)
    monkeypatch.setitem(KINDS, "xout", FAKE_OUT)


def test_without_its_entry_a_kind_is_unknown():
    with pytest.raises(PlcError) as e:
        Wiring.from_rows(FAKE_ROWS)
    assert e.value.code == "PLC4005" and "unknown module 'xin'" in e.value.message


def test_one_entry_makes_a_new_kind_loadable_bindable_and_moving(fake_kinds):
    w = Wiring.from_rows(FAKE_ROWS, plant="tank")
    assert [r.module for r in w] == ["xin", "xout"] and w[0].params == {"gain": 10000.0}
    with pytest.raises(PlcError) as e:  # its parameters are checked like any other's
        Wiring.from_rows([{**FAKE_ROWS[0], "gian": 3}])
    assert e.value.code == "PLC4005" and "Did you mean 'gain'" in e.value.message
    sc = Scenario().io_fault("%IW64", "dead", at="20s")
    tr = Simulation(plclab.loads(TANK), "tank", [*BASE[:2], *w], scenario=sc).run("25s")
    for t in (1.0, 10.0, 19.9):
        assert tr.value_at("%IW64", t) == round(10000 * tr.value_at("LEVEL", t))
    assert tr.value_at("%IW64", 21.0) == -1  # its fault, from the scenario
    q, pump = tr["%QX0.0"], tr["PUMP"]
    assert pump.any() and (q[:-1] == pump[1:]).all()  # no delay: the next sample has it


def test_a_new_kind_is_checked_against_the_signal_and_address(fake_kinds):
    bad = [({**FAKE_ROWS[0], "signal": "LS1"}, "PLC4006"),  # a BOOL signal on a REAL kind
           ({**FAKE_ROWS[0], "plc": "%IB64"}, "PLC4004"),  # counts need a word
           ({**FAKE_ROWS[1], "signal": "PUMP_SPEED", "plc": "%QX0.1"}, "PLC4006")]
    for row, code in bad:
        with pytest.raises(PlcError) as e:
            Simulation(plclab.loads(TANK), "tank", [row])
        assert e.value.code == code, (row, e.value)


# --------------------------------------------------------------------------- the docs agree
def test_the_simulation_docs_name_every_kind_parameter_and_fault():
    text = (Path(__file__).resolve().parents[2] / "docs" / "simulation.md").read_text("utf-8")
    rows = {ln.split("`")[1]: ln for ln in text.splitlines() if ln.startswith("| `")}
    faults = next(ln for ln in text.splitlines() if ln.startswith("| `io_fault`"))
    for name, kind in KINDS.items():
        assert name in rows, f"docs/simulation.md: no row for module {name}"
        missing = [p for p in kind.params if f"`{p}`" not in rows[name]]
        assert not missing, f"docs/simulation.md, module {name}: parameters {missing} missing"
        missing = [f for f in kind.faults if f"`{f}`" not in faults]
        assert not missing, f"docs/simulation.md, io_fault: faults {missing} of {name} missing"

