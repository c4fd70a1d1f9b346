"""Every value of every lab.toml, wiring file and scenario file, mutated: wrong types, negative,
zero, NaN/inf, huge numbers, empty strings, lists for scalars, deleted keys and unknown keys.
Loading (and, where loading succeeds, a short run of the first scenario with its criteria) either
works or raises a PlcError with a catalogued code naming the file and the key; never another
Python exception.

The suite runs one mutation per value (rotating through the kinds, so every kind reaches every
file); ``PLCLAB_FULL_MUTATIONS=1`` runs all of them (about 25,000 for the labs, a few minutes).
"""

from __future__ import annotations

import copy
import json
import math
import os
import re
import shutil
import tomllib
import zlib
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.grade.lab import ScenarioSpec, list_labs, load_lab, repo_labs_dir, stub_program
from plclab.problems import PROBLEMS
from plclab.sim.wirings import FOLDER

LABS = sorted(p for p in list_labs() if p.parent == repo_labs_dir())
FULL = bool(os.environ.get("PLCLAB_FULL_MUTATIONS"))
DELETE = object()
UNKNOWN = "zz_unknown_key"
KINDS = ["x", "", -1, 0, math.nan, math.inf, 1e300, 10 ** 30, DELETE, "LIST"]


# -- TOML out ---------------------------------------------------------------------------------
def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) \
            else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + "}"


def dumps(data: dict) -> str:
    """TOML text in the shape of the lab files: keys first, then [[tables]]."""
    head, blocks = [], []
    for k, v in data.items():
        if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for row in v:
                blocks.append(f"\n[[{k}]]\n" + "".join(f"{_key(a)} = {_value(b)}\n"
                                                       for a, b in row.items()))
        else:
            head.append(f"{_key(k)} = {_value(v)}\n")
    return "".join(head) + "".join(blocks)


# -- mutations --------------------------------------------------------------------------------
def _values(obj, path=()):
    if isinstance(obj, dict):
        yield path, obj
        for k, v in obj.items():
            yield from _values(v, path + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _values(v, path + (i,))
        yield path, obj
    else:
        yield path, obj


def mutations(data: dict) -> list[tuple[tuple, object]]:
    """(path, new value) pairs; a path ending in UNKNOWN adds a key to that table."""
    out = []
    for path, v in _values(data):
        if isinstance(v, dict):
            out.append((path + (UNKNOWN,), 1))
            continue
        if not path:
            continue
        kinds = [k for k in KINDS if not (k == v and type(k) is type(v))]
        if not FULL:
            kinds = [kinds[zlib.crc32(repr(path).encode()) % len(kinds)]]
        for k in kinds:
            out.append((path, [v, v] if k == "LIST" and not isinstance(v, list) else
                        7 if k == "LIST" else k))
    return out


def mutate(data: dict, path: tuple, new) -> dict:
    d = copy.deepcopy(data)
    cur = d
    for p in path[:-1]:
        cur = cur[p]
    if new is DELETE:
        del cur[path[-1]]
    else:
        cur[path[-1]] = new
    return d


def assert_teaches(e: PlcError, path: tuple, text: str, file: str) -> None:
    """A catalogued code, the file, and the key (in the message or on the line pointed at)."""
    assert e.code in PROBLEMS, e
    assert e.location is not None and Path(e.location.file).name == file, e
    lines = text.splitlines()
    line = lines[e.location.line - 1] if 0 < e.location.line <= len(lines) else ""
    keys = [p for p in path if isinstance(p, str)]
    assert any(k in e.message or k in line for k in keys), (path, str(e))


# -- running ----------------------------------------------------------------------------------
def run_first_scenario(lab) -> None:
    import plclab
    from plclab.sim import Simulation

    sc = lab.scenarios[0]
    plc = plclab.loads(stub_program(lab), "stub.st", cycle_time=lab.scan)
    acts = [a for a in sc.actions if not any(k in a for k in ("var", "force", "unforce"))]
    spec = ScenarioSpec(sc.name, min(sc.duration, 0.3), sc.description, sc.seed, sc.visible,
                        sc.plant_params, acts, sc.until, [])
    sim = Simulation(plc, lab.plant, lab.wiring, seed=sc.seed, scenario=spec.scenario(),
                     watch=[w for w in lab.all_watch(sc) if w.startswith("%")],
                     plant_params={**lab.plant_params, **sc.plant_params})
    trace = sim.run()
    for c in lab.criteria_for(sc.name):
        c.evaluate(trace)


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("labs")


@pytest.mark.parametrize("lab_dir", LABS, ids=[p.name for p in LABS])
def test_every_mutated_lab_toml_value_is_a_plc_error_or_works(lab_dir, workdir):
    dst = workdir / lab_dir.name
    shutil.copytree(lab_dir, dst)
    data = tomllib.loads((lab_dir / "lab.toml").read_text(encoding="utf-8"))
    muts = mutations(data)
    assert len(muts) > 50
    loaded = 0
    for path, new in muts:
        text = dumps(mutate(data, path, new))
        (dst / "lab.toml").write_text(text, encoding="utf-8")
        try:
            lab = load_lab(dst)
            loaded += 1
            run_first_scenario(lab)
        except PlcError as e:
            assert_teaches(e, path, text, "lab.toml")
    assert loaded  # some mutations are harmless (descriptions, extra goals...)


PROG = "PROGRAM P VAR x : BOOL; END_VAR x := NOT x; END_PROGRAM"
WIRING_FILES = sorted(FOLDER.glob("*.toml"))  # the wiring tables (plclab/sim/wirings)
SCENARIO_FILES = sorted(repo_labs_dir().glob("*/*_scenario.toml"))  # a lab's scenario files


@pytest.mark.parametrize("file", WIRING_FILES + SCENARIO_FILES,
                         ids=[p.stem for p in WIRING_FILES + SCENARIO_FILES])
def test_every_mutated_wiring_and_scenario_value_is_a_plc_error_or_works(file, tmp_path):
    import plclab
    from plclab.sim import Simulation, load_scenario, load_wiring

    data = tomllib.loads(file.read_text(encoding="utf-8"))
    plant = data.get("plant") or "tank"
    is_scenario = "scenario" in file.name
    target = tmp_path / file.name
    for path, new in mutations(data):
        text = dumps(mutate(data, path, new))
        target.write_text(text, encoding="utf-8")
        try:
            if is_scenario:
                sc = load_scenario(target)
                plc = plclab.loads(PROG, cycle_time=sc.scan or "10ms")
                sim = Simulation(plc, plant, scenario=sc)
            else:
                sim = Simulation(plclab.loads(PROG), plant, load_wiring(target))
            sim.run(duration=0.2)
        except PlcError as e:
            assert_teaches(e, path, text, file.name)
