"""``scan(n)``, ``scan()`` one at a time, the prebound ``scanner()`` and the plain one-scan
path (``_scan_once``) leave the PLC in the same state (ADR 0024): variables, clock, scan count,
images and terminals, faults included."""

from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcRuntimeFault
from plclab.runtime.plc import Plc

NO_IMAGES = """
PROGRAM Main
VAR t : TON; n : DINT; d : INT := 5; q : INT; first : BOOL := TRUE; END_VAR
t(IN := NOT t.Q, PT := T#30ms);
n := n + 1;
IF n MOD 7 = 0 THEN d := d - 1; END_IF
q := 100 / d;
END_PROGRAM
"""

WITH_IMAGES = """
PROGRAM Main
VAR start AT %IX0.0 : BOOL; level AT %IW2 : INT; pump AT %QX0.0 : BOOL; count : DINT;
    d : INT := 3; q : INT; END_VAR
pump := start AND level < 50;
count := count + 1;
IF level = 99 THEN d := 0; END_IF
q := 10 / d;
END_PROGRAM
"""

_COMPILED = {name: plclab.compile_sources([(src, "p.st")])
             for name, src in (("plain", NO_IMAGES), ("images", WITH_IMAGES))}


def members(v):
    """A block instance as a dict of its members (all of them, internal ones included)."""
    slots = [s for c in type(v).__mro__ for s in getattr(c, "__slots__", ())]
    if slots or hasattr(v, "__dict__"):
        d = {s: getattr(v, s) for s in slots if hasattr(v, s)}
        d.update(getattr(v, "__dict__", {}))
        return {k: members(x) for k, x in d.items() if not k.startswith("_ctx")}
    return v


def state(plc):
    return ({k: members(plc[k]) for k in plc.variables()}, plc.ctx.now_ns, plc.ctx.now,
            plc.ctx.scan_count, plc.ctx.first_scan, bytes(plc.image_in), bytes(plc.image_out),
            bytes(plc.outputs), plc.state, plc.fault and plc.fault.code)


def drive(plc, how: str, steps: list[tuple[int, int]]):
    """Run the steps (scans, an input byte) one way; a fault ends the run."""
    one = plc.scanner() if how == "scanner" else None
    for scans, level in steps:
        plc.inputs[0] = level & 1
        plc.inputs[2:4] = level.to_bytes(2, "big")
        try:
            if how == "batch":
                plc.scan(scans)
            elif how == "run":
                plc.run(cycles=scans)
            elif how == "plain":
                for _ in range(scans):
                    plc._scan_once()
            else:
                for _ in range(scans):
                    one() if one is not None else plc.scan()
        except PlcRuntimeFault:
            break
    return state(plc)


@settings(max_examples=60, deadline=None, database=None)
@given(program=st.sampled_from(sorted(_COMPILED)),
       steps=st.lists(st.tuples(st.integers(0, 12), st.sampled_from([0, 1, 40, 60, 99])),
                      min_size=1, max_size=6))
def test_every_way_of_scanning_ends_in_the_same_state(program, steps):
    results = {how: drive(Plc(_COMPILED[program]), how, steps)
               for how in ("plain", "batch", "run", "one", "scanner")}
    assert results["batch"] == results["plain"]
    assert results["run"] == results["plain"]
    assert results["one"] == results["plain"]
    assert results["scanner"] == results["plain"]


def test_the_scanner_follows_stop_force_and_restart():
    plc = Plc(_COMPILED["images"])
    one = plc.scanner()
    plc.inputs[0] = 1
    one()
    assert plc["Main.pump"] is True and plc.outputs[0] & 1
    plc.force("Main.pump", False)
    one()
    assert plc.outputs[0] & 1 == 0
    plc.unforce()
    plc.stop()
    before = plc.time
    one()  # a STOP cycle: the clock moves, the program does not run, outputs are off
    assert plc.time > before and plc.scan_count == 2 and plc.outputs[0] == 0
    plc.cold_restart()
    one()  # the old namespace is gone: the scanner falls back to scan()
    assert plc.scan_count == 1 and plc["Main.count"] == 1


def test_the_trigger_flag_follows_every_change_of_the_trigger_points():
    """scan() tests one flag, kept by the trigger lists, modify() and the scan that applies a
    modification (ADR 0034), instead of any() over every trigger point on each call."""
    plc = plclab.loads("PROGRAM P VAR n, m : INT; END_VAR n := n + 1; END_PROGRAM")
    seen: list[int] = []

    def cb(p, at):
        seen.append(p["P.n"])

    assert not plc._hooked
    plc.triggers["scan_end"].append(cb)
    assert plc._hooked
    plc.scan(2)
    scan_one = plc.scanner()
    scan_one()
    assert seen == [1, 2, 3]
    plc.triggers["scan_end"].remove(cb)
    assert not plc._hooked
    plc.triggers["stop"] += [cb]
    assert plc._hooked
    plc.triggers["stop"].clear()
    assert not plc._hooked
    plc.modify("P.m", 7)
    assert plc._hooked
    plc.scan()
    assert plc["P.m"] == 7 and not plc._hooked
    plc.triggers["scan_start"].insert(0, cb)
    del plc.triggers["scan_start"][0]
    plc.triggers["scan_start"].extend([cb, cb])
    plc.triggers["scan_start"].pop()
    assert plc._hooked == any(plc._watch_parts)
    plc.triggers["scan_start"][0:1] = []
    assert not plc._hooked
