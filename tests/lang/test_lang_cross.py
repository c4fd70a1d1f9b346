"""One program, several languages: ST, IL, text LD and PLCopen XML (LD, FBD) compile to the same
behaviour. Each program is driven with the same random inputs, scan by scan (timers included),
and every output is compared after every scan."""

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.runtime.plc import Plc

EXAMPLES = Path(__file__).parent.parent.parent / "examples"


def _compile(text: str, filename: str):
    return plclab.compile_sources([(text, filename)])


def _file(name: str):
    return _compile((EXAMPLES / name).read_text(encoding="utf-8"), name)


# --- motor start/stop with seal-in (001 L1588-1660) ------------------------------------------
MOTOR_DECL = "PROGRAM Motor\nVAR START, STOP, MOTOR : BOOL; END_VAR\n"
MOTOR = {
    "st": (MOTOR_DECL + "MOTOR := (START OR MOTOR) AND NOT STOP;\nEND_PROGRAM\n", "m.st"),
    "il": (MOTOR_DECL + "    LD START\n    OR MOTOR\n    ANDN STOP\n    ST MOTOR\nEND_PROGRAM\n",
           "m.il"),
    "il_deferred": (MOTOR_DECL + "    LDN STOP\n    AND( START\n    OR MOTOR\n    )\n"
                    "    ST MOTOR\nEND_PROGRAM\n", "m2.st"),
    "ld": ((EXAMPLES / "motor.ld").read_text(encoding="utf-8"), "motor.ld"),
    "xml": ((EXAMPLES / "motor.xml").read_text(encoding="utf-8"), "motor.xml"),
}

# --- two-position tank level (001 L2914-2923) ----------------------------------------------------
TANK_DECL = "PROGRAM TankLevel\nVAR LS1, LS2, M : BOOL; END_VAR\n"
TANK_LD = TANK_DECL + """
|   LS1         LS2          M  |
|---[/]--+------[/]--------( )--|
|   M    |                      |
|---[ ]--+                      |
END_PROGRAM
"""
TANK = {
    "st": (TANK_DECL + "M := ((NOT LS1) OR M) AND (NOT LS2);\nEND_PROGRAM\n", "t.st"),
    "il": ((EXAMPLES / "tank.il").read_text(encoding="utf-8"), "tank.il"),
    "ld": (TANK_LD, "t.ld"),
    "fbd_xml": ((EXAMPLES / "tank_fbd.xml").read_text(encoding="utf-8"), "tank_fbd.xml"),
}

# --- fallen-bottle rejection with a TON holding the cylinder (001 L7645-7696) ------------------
BOTTLE_DECL = ("PROGRAM Bottle\nVAR X1, X2, CYL, REJECT : BOOL; T1 : TON; END_VAR\n")
BOTTLE = {
    "st": (BOTTLE_DECL + """
REJECT := X2 AND NOT X1;
CYL := (REJECT OR CYL) AND NOT T1.Q;
T1(IN := CYL, PT := T#300ms);
END_PROGRAM
""", "b.st"),
    "il_formal": (BOTTLE_DECL + """
    LD   X2
    ANDN X1
    ST   REJECT
    OR   CYL
    ANDN T1.Q
    ST   CYL
    CAL  T1(IN := CYL, PT := T#300ms)
END_PROGRAM
""", "b.il"),
    "il_informal": (BOTTLE_DECL + """
    LD   X2
    ANDN X1
    ST   REJECT
    LD   REJECT
    OR   CYL
    ANDN T1.Q
    ST   CYL
    ST   T1.IN
    LD   T#300ms
    ST   T1.PT
    CAL  T1
END_PROGRAM
""", "b2.il"),
    "ld": ((EXAMPLES / "bottle.ld").read_text(encoding="utf-8"), "bottle.ld"),
    "xml": ((EXAMPLES / "bottle.xml").read_text(encoding="utf-8"), "bottle.xml"),
}


def _build(forms):
    return {k: _compile(text, name) for k, (text, name) in forms.items()}


_MOTOR, _TANK, _BOTTLE = _build(MOTOR), _build(TANK), _build(BOTTLE)


def _trace(compiled, prog, inputs, seq, outputs):
    plc = Plc(compiled)
    rows = []
    for values in seq:
        for name, v in zip(inputs, values, strict=True):
            plc[f"{prog}.{name}"] = v
        plc.scan()
        rows.append(tuple(plc[f"{prog}.{o}"] for o in outputs))
    return rows


def _agree(built, prog, inputs, seq, outputs):
    traces = {k: _trace(c, prog, inputs, seq, outputs) for k, c in built.items()}
    ref = traces["st"]
    for k, tr in traces.items():
        assert tr == ref, f"{k} differs from ST"
    return ref


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.booleans()), min_size=1, max_size=40))
def test_motor_same_in_st_il_ld_xml(seq):
    _agree(_MOTOR, "Motor", ("START", "STOP"), seq, ("MOTOR",))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.booleans()), min_size=1, max_size=40))
def test_tank_same_in_st_il_ld_fbd(seq):
    _agree(_TANK, "TankLevel", ("LS1", "LS2"), seq, ("M",))


# a fallen bottle stays in front of the sensors for a few scans: runs of equal inputs
_runs = st.lists(st.tuples(st.booleans(), st.booleans(), st.integers(1, 40)), min_size=1,
                 max_size=12).map(lambda rs: [(a, b) for a, b, n in rs for _ in range(n)])


@settings(max_examples=60, deadline=None)
@given(_runs)
def test_bottle_rejection_same_with_timer(seq):
    ref = _agree(_BOTTLE, "Bottle", ("X1", "X2"), seq,
                 ("REJECT", "CYL", "T1.Q", "T1.ET"))
    assert len(ref) == len(seq)


def test_bottle_cylinder_holds_300ms():
    """The reference behaviour itself: a fallen bottle (X2 and not X1) pushes for 300 ms."""
    seq = [(False, True)] + [(False, False)] * 40
    ref = _agree(_BOTTLE, "Bottle", ("X1", "X2"), seq, ("CYL",))
    held = [c for (c,) in ref]
    assert held[:30] == [True] * 30 and not any(held[31:])


def test_examples_ship_their_forms():
    for name in ("motor.ld", "tank.il", "bottle.ld", "motor.xml", "bottle.xml", "tank_fbd.xml",
                 "project.xml"):
        assert _file(name).project.programs
