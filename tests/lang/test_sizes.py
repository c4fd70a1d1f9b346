"""Programs of any size: they check, compile, run and give the right results; beyond the
documented nesting limits a PLC0190 error at the place, never a Python error (issue 11 item 5).

Expected values come from small Python models of the generated programs, not from plclab."""

from __future__ import annotations

import pytest

import plclab
from plclab.errors import PlcError, PlcRuntimeFault
from plclab.lang import ast as A
from plclab.lang.check import Checker
from plclab.lang.limits import MAX_BLOCK_NESTING, MAX_EXPR_NESTING
from plclab.project import check_sources, parse_sources


def load(src: str):
    """``plclab check`` finds no error, and then the program compiles."""
    _, diags = check_sources([(src, "size.st")])
    errors = [str(d) for d in diags if d.severity == "error"]
    assert not errors, errors[:3]
    return plclab.loads(src, "size.st")


def errors_of(src: str) -> list:
    _, diags = check_sources([(src, "size.st")])
    return [d for d in diags if d.severity == "error"]


VALS = [(i * 37) % 101 - 50 for i in range(100)]
ARRAY = f"a : ARRAY[0..99] OF DINT := [{', '.join(map(str, VALS))}];"


# -- long chains ------------------------------------------------------------------------------
def test_a_10000_term_sum():
    terms = [f"a[{i % 100}]" for i in range(10_000)]
    src = f"PROGRAM P VAR {ARRAY} s : DINT; END_VAR\ns := {' + '.join(terms)};\nEND_PROGRAM\n"
    plc = load(src)
    plc.scan()
    assert plc["s"] == sum(VALS[i % 100] for i in range(10_000))


def test_a_long_mixed_chain_keeps_left_to_right_order():
    ops = ["+", "-", "*", "-", "+"]
    expr = "x" + "".join(f" {ops[i % 5]} a[{i % 100}]" for i in range(1, 3000))
    # the model: '*' binds tighter than '+' and '-', which go left to right
    terms: list[list] = [[3]]
    signs = [1]
    for i in range(1, 3000):
        op, v = ops[i % 5], VALS[i % 100]
        if op == "*":
            terms[-1].append(v)
        else:
            terms.append([v])
            signs.append(1 if op == "+" else -1)
    total = 0
    for sign, factors in zip(signs, terms, strict=True):
        p = 1
        for f in factors:
            p *= f
        total += sign * p
    src = (f"PROGRAM P VAR {ARRAY} s : LINT; x : LINT := 3; END_VAR\ns := {expr};\n"
           "END_PROGRAM\n")
    plc = load(src)
    plc.scan()
    assert plc["s"] == (total + 2**63) % 2**64 - 2**63


@pytest.mark.parametrize("op", ["AND", "OR", "XOR"])
def test_long_boolean_chains(op):
    n = 5000
    src = (f"PROGRAM P VAR bs : ARRAY[0..63] OF BOOL; r : BOOL; END_VAR\n"
           f"r := {f' {op} '.join(f'bs[{i % 64}]' for i in range(n))};\nEND_PROGRAM\n")
    plc = load(src)
    for pattern in ([True] * 64, [False] * 64, [i % 9 == 4 for i in range(64)]):
        for i, v in enumerate(pattern):
            plc[f"bs[{i}]"] = v
        plc.scan()
        vals = [pattern[i % 64] for i in range(n)]
        want = all(vals) if op == "AND" else any(vals) if op == "OR" else sum(vals) % 2 == 1
        assert plc["r"] is want


def test_and_or_chain_of_comparisons_in_a_condition():
    n = 2000
    cond = " OR ".join(f"(a[{i % 100}] = x AND y > {i})" for i in range(n))
    src = (f"PROGRAM P VAR {ARRAY} x, y, hits : DINT; END_VAR\n"
           f"IF {cond} THEN hits := hits + 1; END_IF;\nEND_PROGRAM\n")
    plc = load(src)
    for x, y in ((VALS[5], 10), (VALS[5], 4), (VALS[99], 200), (1000, 5000)):
        plc["x"], plc["y"], plc["hits"] = x, y, 0
        plc.scan()
        want = any(VALS[i % 100] == x and y > i for i in range(n))
        assert plc["hits"] == int(want)


# -- nesting ----------------------------------------------------------------------------------
def test_500_nested_parentheses():
    d = 500
    right = "a[0]"
    for i in range(1, d):
        right = f"a[{i % 100}] - ({right})"
    want = VALS[0]
    for i in range(1, d):
        want = VALS[i % 100] - want
    src = (f"PROGRAM P VAR {ARRAY} s, t, x : DINT; END_VAR\ns := {right};\n"
           f"t := {'(' * d}x + 1{')' * d};\nEND_PROGRAM\n")
    plc = load(src)
    plc["x"] = 41
    plc.scan()
    assert (plc["s"], plc["t"]) == (want, 42)


def test_deep_index_and_member_chains():
    d = 300
    idx = [(i * 7 + 3) % 100 for i in range(100)]
    nested = "0"
    want = 0
    for _ in range(d):
        nested = f"a[{nested}]"
        want = idx[want]
    types = "TYPE S0 : STRUCT v : DINT; END_STRUCT; END_TYPE\n" + "".join(
        f"TYPE S{i} : STRUCT n : S{i - 1}; END_STRUCT; END_TYPE\n" for i in range(1, 30))  # data nests at most 32 levels (PLC0124)
    path = "z" + ".n" * 29 + ".v"
    deep_42 = "42"
    for _ in range(200):
        deep_42 = f"1 * ({deep_42})"
    src = (types + f"PROGRAM P VAR a : ARRAY[0..99] OF DINT := [{', '.join(map(str, idx))}];\n"
           f"b : ARRAY[0..99] OF DINT; z : S29; s, m : DINT; END_VAR\n"
           f"s := {nested};\n{path} := s + 7;\nm := {path} * 2;\nb[{deep_42}] := m;\n"
           "END_PROGRAM\n")
    plc = load(src)
    plc.scan()
    assert plc["s"] == want
    assert plc["m"] == (want + 7) * 2
    assert plc["b[42]"] == (want + 7) * 2  # a deep target index: the element itself is written


def nested_ifs(depth: int, function: bool) -> str:
    """IF x >= i THEN ... at every level; ELSIF at levels ending in 3, ELSE at levels ending in
    7; a FOR loop opened at level 50; EXIT at level 900 (j = 3); RETURN at level 960."""
    out = []
    for i in range(depth):
        out.append(f"IF x >= {i} THEN\nn := n + 1;")
        if i == 900:
            out.append("IF j = 3 THEN EXIT; END_IF;")
        if i == 960:
            out.append("IF y = -1 THEN res := -1; RETURN; END_IF;")
        if i == 50:
            out.append("FOR j := 1 TO 4 DO\nm := m + 1;")
    for i in reversed(range(depth)):
        if i == 50:
            out.append("END_FOR;")
        out.append(f"k := k + {i};")
        if i % 10 == 3:
            out.append(f"ELSIF y = {i} THEN e := e + {i};")
        if i % 10 == 7:
            out.append(f"ELSE f := f + {i};")
        out.append("END_IF;")
    body = "\n".join(out).replace("res :=", "Deep :=" if function else "res :=")
    if function:
        return ("FUNCTION Deep : DINT\nVAR_INPUT x, y : DINT; END_VAR\n"
                "VAR_OUTPUT n, m, k, e, f : DINT; END_VAR\nVAR j : DINT; END_VAR\n"
                f"{body}\nDeep := 1;\nEND_FUNCTION\n"
                "PROGRAM P VAR x, y, n, m, k, e, f, res : DINT; END_VAR\n"
                "res := Deep(x := x, y := y, n => n, m => m, k => k, e => e, f => f);\n"
                "END_PROGRAM\n")
    return ("PROGRAM P VAR x, y, n, m, k, e, f, res, j : DINT; END_VAR\n"
            "n := 0; m := 0; k := 0; e := 0; f := 0; res := 1;\n"
            f"{body}\nEND_PROGRAM\n")


def nested_ifs_model(x: int, y: int, depth: int) -> dict[str, int]:
    """What the program of :func:`nested_ifs` computes, written as loops."""
    v = {"n": 0, "m": 0, "k": 0, "e": 0, "f": 0, "res": 1}
    top = min(x, depth - 1)  # levels 0..top are taken

    def not_taken(level: int) -> None:
        if level < depth:
            if level % 10 == 3 and y == level:
                v["e"] += level
            elif level % 10 == 7:
                v["f"] += level

    v["n"] += min(top, 50) + 1
    if top < 50:
        not_taken(top + 1)
        v["k"] += sum(range(top + 1))
        return v
    for j in range(1, 5):
        v["m"] += 1
        if top >= 960 and y == -1 and (top < 900 or j != 3):
            v["n"] += 960 - 50
            v["res"] = -1
            return v
        if top >= 900 and j == 3:
            v["n"] += 900 - 50
            break
        v["n"] += top - 50
        not_taken(top + 1)
        v["k"] += sum(range(51, top + 1))
    v["k"] += sum(range(51))
    return v


@pytest.mark.parametrize("function", [False, True], ids=["PROGRAM", "FUNCTION"])
def test_1000_nested_ifs(function):
    plc = load(nested_ifs(1000, function))
    for x, y in ((-1, 0), (12, 13), (16, 0), (23, 23), (500, 0), (502, 503), (507, 0),
                 (950, 0), (999, -1), (5000, 0), (5000, -1)):
        plc["x"], plc["y"] = x, y
        plc.scan()
        got = {name: plc[name] for name in ("n", "m", "k", "e", "f", "res")}
        assert got == nested_ifs_model(x, y, 1000), (x, y)


def test_a_fault_deep_inside_nested_blocks_points_at_its_st_line():
    depth = 1000
    lines = ["PROGRAM P VAR x, z, q : DINT; END_VAR"]
    lines += [f"IF x >= {i} THEN" for i in range(depth)]
    lines.append("q := 100 / z;")
    fault_line = len(lines)
    lines += ["END_IF;"] * depth + ["END_PROGRAM"]
    plc = load("\n".join(lines))
    plc["x"], plc["z"] = depth, 4
    plc.scan()
    assert plc["q"] == 25
    plc["z"] = 0
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    assert ei.value.code == "PLC2001"
    assert (ei.value.location.file, ei.value.location.line) == ("size.st", fault_line)


def test_a_long_elsif_chain():
    n = 3000
    src = ["PROGRAM P VAR x, s : DINT; END_VAR", "IF x = 0 THEN s := 5;"]
    src += [f"ELSIF x = {i} THEN s := {i * 3 + 5};" for i in range(1, n)]
    src += ["ELSE s := -1;", "END_IF;", "END_PROGRAM"]
    plc = load("\n".join(src))
    for x in (0, 1, 1500, n - 1, n, -7):
        plc["x"] = x
        plc.scan()
        assert plc["s"] == (x * 3 + 5 if 0 <= x < n else -1)


# -- CASE -------------------------------------------------------------------------------------
def case_program(n: int) -> tuple[str, list[list]]:
    """Branch i: label 2 * i; every 1000th branch also a range; branch 0 also the range 2..3,
    which overlaps the label of branch 1 (the first branch wins, as in an IF chain)."""
    branches: list[list] = []
    lines = ["PROGRAM P VAR x, s : DINT; END_VAR", "CASE x OF"]
    for i in range(n):
        labels: list = [2 * i]
        if i % 1000 == 0:
            labels.append((1_000_000 + 10 * i, 1_000_000 + 10 * i + 4))
        if i == 0:
            labels.append((2, 3))
        branches.append(labels)
        text = ", ".join(str(x) if isinstance(x, int) else f"{x[0]}..{x[1]}" for x in labels)
        lines.append(f"{text}: s := {i * 3 + 1};")
    lines += ["ELSE s := -1;", "END_CASE;", "END_PROGRAM"]
    return "\n".join(lines), branches


def case_model(x: int, branches: list[list]) -> int:
    for i, labels in enumerate(branches):
        for lab in labels:
            if lab == x if isinstance(lab, int) else lab[0] <= x <= lab[1]:
                return i * 3 + 1
    return -1


@pytest.mark.parametrize("n", [12, 50_000])
def test_case_with_many_labels_ranges_and_else(n):
    src, branches = case_program(n)
    plc = load(src)
    for x in (0, 2, 3, 4, n, 2 * (n // 2), 2 * (n - 1), 1, 2 * n + 1, -5, 1_000_002,
              1_000_000 + 10 * 1000 + 3, 1_000_000 + 10 * 1000 + 7, 10**7):
        plc["x"] = x
        plc.scan()
        assert plc["s"] == case_model(x, branches), x


def test_a_large_case_inside_a_loop_with_exit_and_continue():
    n = 600
    body = "\n".join(f"{i}: IF i = 7 THEN EXIT; END_IF; IF i = 3 THEN CONTINUE; END_IF; "
                     f"s := s + {i};" for i in range(n))
    src = (f"FUNCTION F : DINT VAR_INPUT x : DINT; END_VAR VAR i, s : DINT; END_VAR\n"
           f"FOR i := x TO x + 10 DO\nCASE i OF\n{body}\nEND_CASE;\ns := s + 1000;\nEND_FOR;\n"
           "F := s;\nEND_FUNCTION\nPROGRAM P VAR x, r : DINT; END_VAR r := F(x); END_PROGRAM\n")
    plc = load(src)
    for x in (0, 100, 595):
        plc["x"] = x
        plc.scan()
        s = 0
        for i in range(x, x + 11):
            if i == 7:
                break
            if i == 3:
                continue
            s += (i if i < n else 0) + 1000
        assert plc["r"] == s, x


# -- beyond the limits ------------------------------------------------------------------------
def test_parentheses_beyond_the_limit_are_plc0190_at_the_statement():
    d = MAX_EXPR_NESTING + 5
    src = f"PROGRAM P VAR s : DINT; END_VAR\ns := 1;\ns := {'(' * d}1{')' * d};\nEND_PROGRAM\n"
    errs = errors_of(src)
    assert [e.code for e in errs] == ["PLC0190"]
    assert errs[0].location.line == 3 and "split it" in errs[0].message
    with pytest.raises(PlcError) as ei:
        plclab.loads(src, "size.st")
    assert ei.value.code == "PLC0190"


def test_blocks_beyond_the_limit_are_plc0190_and_the_next_pou_is_still_checked():
    d = MAX_BLOCK_NESTING + 5
    src = ("PROGRAM P VAR x : DINT; END_VAR\n" + "IF x > 0 THEN\n" * d + "x := 1;\n" +
           "END_IF;\n" * d + "END_PROGRAM\nPROGRAM Q VAR y : INT; END_VAR y := nosuch; "
           "END_PROGRAM\n")
    errs = errors_of(src)
    assert [e.code for e in errs] == ["PLC0190", "PLC0100"]
    assert errs[0].location.line == MAX_BLOCK_NESTING + 3  # the first statement too deep


def test_unary_operators_count_as_nesting():
    src = f"PROGRAM P VAR b : BOOL; END_VAR\nb := {'NOT ' * (MAX_EXPR_NESTING + 1)}b;\nEND_PROGRAM"
    assert [e.code for e in errors_of(src)] == ["PLC0190"]
    ok = f"PROGRAM P VAR b, c : BOOL; END_VAR\nc := {'NOT ' * 1001}b;\nEND_PROGRAM"
    plc = load(ok)
    plc.scan()
    assert plc["c"] is True


def test_the_checker_limits_trees_from_any_front_end():
    """A tree too deep for the checker and compiler, made without the ST parser (as a graphical
    front end could), is a PLC0190 error too."""
    files, diags = parse_sources([("PROGRAM P VAR s : DINT; END_VAR\ns := 1;\nEND_PROGRAM",
                                   "tree.st")])
    assert not diags
    pou = files[-1].pous[0]
    stmt = pou.body[0]
    e: A.Expr = stmt.value
    for _ in range(MAX_EXPR_NESTING + 10):
        e = A.Binary(stmt.loc, "-", A.Literal(stmt.loc, 1, "INT", None, "1"), e)
    stmt.value = e
    ck = Checker(files)
    ck.run()
    assert [d.code for d in ck.diags if d.severity == "error"] == ["PLC0190"]


def test_a_long_il_accumulation():
    """IL keeps one current result across lines: 5,000 operators make one deep left chain."""
    n = 5000
    ops = [("ADD", lambda a, b: a + b), ("SUB", lambda a, b: a - b), ("MUL", lambda a, b: a * b)]
    lines, want = ["LD x"], 3
    for i in range(n):
        name, fn = ops[i % 3] if i % 7 else ops[0]
        v = i % 5 + 1 if name == "MUL" else i % 11
        lines.append(f"{name} {v}")
        want = (fn(want, v) + 2**63) % 2**64 - 2**63
    src = "PROGRAM P\nVAR x, s : LINT; END_VAR\n" + "\n".join(lines) + "\nST s\nEND_PROGRAM\n"
    plc = plclab.loads(src, "chain.il")
    plc["x"] = 3
    plc.scan()
    assert plc["s"] == want
