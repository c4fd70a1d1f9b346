"""Ladder Diagram as text: tricky layouts, edge contacts and coils, boxes, scan semantics, and
every LD diagnostic (PLC0160-PLC0166) at its line and column."""

import pytest

import plclab
from plclab.lang.frontends.ld import parse_ld_collect
from plclab.project import check_sources

DECLS = ("a, b, c, d, e, x, y, z : BOOL; t1 : TON; c1 : CTU; n, m : INT; level : REAL; "
         "et : TIME; inp AT %IX0.0 : BOOL;")


def src(net: str, decls: str = DECLS) -> str:
    return f"PROGRAM P\nVAR {decls} END_VAR\n{net.strip(chr(10))}\nEND_PROGRAM\n"


def load(net: str, decls: str = DECLS):
    return plclab.loads(src(net, decls), "p.ld")


def truth(plc, inputs, out, fn):
    import itertools

    for vals in itertools.product((False, True), repeat=len(inputs)):
        for k, v in zip(inputs, vals, strict=True):
            plc[k] = v
        plc.scan()
        assert plc[out] == fn(*vals), (vals, plc[out])


def test_series_and_parallel():
    plc = load("""
|   a      b       c        x  |
|---[ ]----[/]--+--[ ]--+---( )|
|               |  d    |      |
|               +--[ ]--+      |
""")
    truth(plc, "abcd", "x", lambda a, b, c, d: a and not b and (c or d))


def test_nested_branches():
    plc = load("""
|   a        b             c        x  |
|---[ ]--+---[ ]---+--+----[ ]------( )|
|        |   d     |  |                |
|        +---[ ]---+  |                |
|   e                 |                |
|---[ ]---------------+                |
""")
    truth(plc, "abcde", "x", lambda a, b, c, d, e: ((a and (b or d)) or e) and c)


def test_branch_around_a_coil_and_several_coils_on_one_rung():
    plc = load("""
|   a       b        x   |
|---[ ]--+--[ ]--+--( )--|
|        |  c    |  y    |
|        +--[/]--+--(/)--|
|        |          z    |
|        +----------(S)--|
|   d               z    |
|---[ ]-------------(R)--|
""")
    for a, b, c in ((1, 1, 1), (1, 0, 0), (1, 0, 1), (0, 1, 0)):
        plc["a"], plc["b"], plc["c"], plc["d"] = bool(a), bool(b), bool(c), False
        plc.scan()
        pf = bool(a and (b or not c))
        assert plc["x"] is pf and plc["y"] is (not pf)
    assert plc["z"] is True  # set on an earlier scan, kept
    plc["d"] = True
    plc.scan()
    assert plc["z"] is False


def test_later_rungs_see_earlier_results_in_the_same_scan():
    plc = load("""
|   a       x  |
|---[ ]-----( )|

|   x       y  |
|---[ ]-----( )|
|   y       z  |
|---[ ]-----( )|
""")
    plc["a"] = True
    plc.scan()
    assert (plc["x"], plc["y"], plc["z"]) == (True, True, True)


def test_coils_write_every_scan():
    plc = load("""
|   a       x  |
|---[ ]-----( )|
""")
    plc["a"] = True
    plc.scan()
    plc["x"] = True
    plc["a"] = False
    plc.scan()
    assert plc["x"] is False


def test_edge_contacts_fire_exactly_one_scan():
    plc = load("""
|   a       x  |
|---[P]-----( )|
|   a       y  |
|---[N]-----( )|
""")
    seq = [False, True, True, True, False, False, True, False]
    xs, ys = [], []
    for v in seq:
        plc["a"] = v
        plc.scan()
        xs.append(plc["x"])
        ys.append(plc["y"])
    assert xs == [False, True, False, False, False, False, True, False]
    assert ys == [False, False, False, False, True, False, False, True]


def test_edge_coils_and_edge_contact_behind_a_contact():
    plc = load("""
|   a      b       x  |
|---[ ]----[P]-----( )|
|   a              y  |
|---[ ]------------(P)|
""")
    rows = []
    for a, b in ((False, True), (True, True), (True, True), (False, False), (True, True)):
        plc["a"], plc["b"] = a, b
        plc.scan()
        rows.append((plc["x"], plc["y"]))
    # b rose on scan 1 while a was FALSE: no pulse for x (edge seen, no power); y pulses on a
    assert rows == [(False, False), (False, True), (False, False), (False, False),
                    (True, True)]


def test_timer_and_counter_boxes():
    plc = load("""
|   a                                        x  |
|---[ ]---[TON t1 PT:=T#50ms, ET=>et]--------( )|
|   b                                        y  |
|---[ ]---[CTU c1 PV:=3, CV=>n]--------------( )|
""")
    plc["a"] = True
    plc.scan(5)
    assert plc["x"] is False and plc.format("et") == "T#40ms"
    plc.scan()
    assert plc["x"] is True
    for _ in range(3):
        plc["b"] = True
        plc.scan()
        plc["b"] = False
        plc.scan()
    assert plc["y"] is True and plc["n"] == 3


def test_compare_and_move_boxes():
    plc = load("""
|   a                                        |
|---[ ]---[GT level, 50.0]---[MOVE 7 -> n]---|
|   a                                        |
|---[ ]---[ADD n, 1 -> m]--------------------|
|             x                              |
|---[LE n 0]--( )----------------------------|
""")
    plc["a"], plc["level"] = True, 20.0
    plc.scan()
    assert (plc["n"], plc["m"], plc["x"]) == (0, 1, True)
    plc["level"] = 60.5
    plc.scan()
    assert (plc["n"], plc["m"], plc["x"]) == (7, 8, False)


def test_names_may_be_centred_and_may_be_members_or_addresses():
    plc = load("""
|    a        t1.Q     %QX0.0   |
|---[ ]--------[ ]------( )-----|
|  START                        |
|---[ ]---[TON t1 PT:=T#20ms]---|
""", DECLS + " START : BOOL;")
    plc["START"], plc["a"] = True, True
    plc.scan(3)  # t1.Q rises in rung 2 of scan 3, after rung 1 has read it
    assert plc["%QX0.0"] is False
    plc.scan()
    assert plc["%QX0.0"] is True


def test_right_rail_may_be_left_out():
    plc = load("""
|   a       x
|---[ ]-----( )
""")
    plc["a"] = True
    plc.scan()
    assert plc["x"] is True


def test_parse_keeps_the_network_for_drawing():
    f, d = parse_ld_collect(src("""
|   a       x  |
|---[ ]-----( )|
"""), "k.ld")
    assert not d and f.pous[0].language == "LD"
    net = f.pous[0].networks[0]
    assert [e.kind for e in net.elems] == ["contact", "coil"] and net.right == 15


def test_ld_and_st_pous_mix_in_one_file():
    text = """
FUNCTION_BLOCK Twice
VAR_INPUT i : BOOL; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
q := i;
END_FUNCTION_BLOCK
PROGRAM P
VAR a, x : BOOL; tw : Twice; END_VAR
|   a                      x  |
|---[ ]---[Twice tw]-------( )|
END_PROGRAM
"""
    plc = plclab.loads(text, "mix.ld")
    plc["a"] = True
    plc.scan()
    assert plc["x"] is True


# --- diagnostics ---------------------------------------------------------------------------
# the network starts on line 3 of the file; columns are those of the offending character
DIAG_CASES = {
    "gap in the wire": ("""
|   a        x  |
|---[ ]  ----( )|
""", "PLC0160", 4, 8, ["broken wire"]),
    "branch reaches no coil": ("""
|   a        x  |
|---[ ]--+---( )|
|   b    |      |
|---[ ]--+--[ ] |
""", "PLC0160", 6, 16, ["without reaching a coil"]),
    "contact at the right rail": ("""
|   a       b   |
|---[ ]-----[ ]-|
""", "PLC0160", 4, 17, ["without a coil"]),
    "nothing feeds a junction": ("""
|   a        x  |
|   +-[ ]----( )|
|   |           |
|   +           |
""", "PLC0160", 4, 5, ["nothing feeds"]),
    "element after a coil": ("""
|   a        x    b  |
|---[ ]------( )--[ ]|
""", "PLC0161", 4, 19, ["after a coil"]),
    "coil not at the rail": ("""
|   a        x      |
|---[ ]------( )    |
""", "PLC0161", 4, 17, ["right rail"]),
    "branch does not close": ("""
|   a        x  |
|---[ ]--+---( )|
|   b    |      |
|---[ ]---      |
""", "PLC0162", 5, 10, ["does not close"]),
    "vertical crosses a wire": ("""
|   a        x  |
|---[ ]--|---( )|
""", "PLC0162", 4, 10, ["crosses"]),
    "missing name": ("""
|   a           |
|---[ ]------( )|
""", "PLC0163", 4, 14, ["no variable name"]),
    "name over nothing": ("""
|   a     b     x  |
|---[ ]---------( )|
""", "PLC0163", 3, 11, ["'b'"]),
    "two names": ("""
|   a b     x  |
|---[ ]-----( )|
""", "PLC0163", 3, 7, ["two names"]),
    "unknown contact": ("""
|   a        x  |
|---[Q]------( )|
""", "PLC0164", 4, 5, ["[Q]"]),
    "unknown coil": ("""
|   a        x  |
|---[ ]------(Z)|
""", "PLC0164", 4, 14, ["(Z)"]),
    "stray character": ("""
|   a        x  |
|---[ ]--a---( )|
""", "PLC0164", 4, 10, ["unexpected 'a'"]),
    "unclosed bracket": ("""
|   a        x  |
|---[ ---------(|
""", "PLC0164", 4, 5, ["never closed"]),
    "box type mismatch": ("""
|   a                      x  |
|---[ ]---[TOF t1 PT:=T#1s]--( )|
""", "PLC0165", 4, 11, ["declared as TON"]),
    "box is not a block": ("""
|   a                      x  |
|---[ ]---[FOO t1 PT:=T#1s]--( )|
""", "PLC0165", 4, 11, ["FOO"]),
    "box without instance": ("""
|   a             x  |
|---[ ]---[TON]---( )|
""", "PLC0165", 4, 11, ["instance"]),
    "left rail misaligned": ("""
|   a        x  |
 |---[ ]-----( )|
""", "PLC0166", 4, 2, ["left rail"]),
    "right rail misaligned": ("""
|   a        x   |
|---[ ]-----( )--|
|   b        y  |
|---[ ]-----( )-|
""", "PLC0166", 6, 17, ["right rail"]),
    "unknown variable": ("""
|   a        xx  |
|---[ ]------( )-|
""", "PLC0100", 3, 14, ["xx is not declared"]),
}


@pytest.mark.parametrize("name", sorted(DIAG_CASES))
def test_each_ld_diagnostic(name):
    net, code, line, col, words = DIAG_CASES[name]
    _, ds = check_sources([(src(net), "d.ld")])
    errs = [d for d in ds if d.severity == "error"]
    found = [d for d in errs if d.code == code]
    assert found, f"{code} not reported: {[str(d) for d in errs]}"
    d = found[0]
    assert (d.location.file, d.location.line, d.location.col) == ("d.ld", line, col), str(d)
    for w in words:
        assert w in d.message, d.message


def test_rung_text_mixed_with_st_is_reported():
    text = "PROGRAM P\nVAR a, x : BOOL; END_VAR\nx := a;\n|   a    x  |\n|---[ ]--( )|\n" \
           "END_PROGRAM\n"
    _, ds = check_sources([(text, "m.ld")])
    assert [d.code for d in ds if d.severity == "error"] == ["PLC0166"]


def test_rung_outside_a_pou_is_reported():
    _, ds = check_sources([("|---[ ]--( )|\n", "o.ld")])
    assert ds and ds[0].code == "PLC0166" and ds[0].location.line == 1


def test_tabs_are_rejected():
    _, ds = check_sources([(src("|   a\tx  |\n|---[ ]--( )|"), "t.ld")])
    assert any(d.code == "PLC0166" and "tabs" in d.message for d in ds)


def test_a_drawing_inside_a_comment_stays_a_comment():
    plc = plclab.loads("""(* the old version:
|---[ ]-----(S)|
*)
PROGRAM P
VAR a, x : BOOL; END_VAR
|   a       x  |
|---[ ]-----( )|
END_PROGRAM
""", "c.ld")
    plc["a"] = True
    plc.scan()
    assert plc["x"] is True
