"""Ladder Diagram front end: a plain-text ladder format (``.ld``) -> the shared AST.

A ``.ld`` file is an ST file whose POU bodies are drawn as rungs (full description with
examples in ``docs/languages.md``)::

    PROGRAM Motor
    VAR START, STOP, MOTOR : BOOL; END_VAR
    (* start/stop with seal-in *)
    |   START      STOP        MOTOR  |
    |---[ ]--+----[/]----------( )----|
    |  MOTOR |                        |
    |---[ ]--+                        |
    END_PROGRAM

* Every line of a network starts with the left rail ``|``; the right rail ``|`` is optional but,
  when drawn, in one column. Lines that do not start with ``|`` (blank lines, comments) separate
  networks; inside a network, rungs are the groups of wires joined by branches.
* Contacts ``[ ]`` ``[/]`` ``[P]`` ``[N]``, coils ``( )`` ``(/)`` ``(S)`` ``(R)`` ``(P)``
  ``(N)``, wire ``-``, branch junctions ``+`` joined by vertical ``|`` lines.
* The variable of a contact or coil is written on the line just above it, overlapping the
  element's columns (start it at the ``[``/``(`` or centre it over the element).
* Boxes sit inline in the wire: ``[TON T1 PT:=T#5s]`` (power flow into IN, Q continues the
  wire; outputs with ``ET=>elapsed``), ``[CTU C1 PV:=3]``, comparisons ``[GT level 50.0]``
  (power continues when the comparison holds), functions ``[MOVE 5 -> x]``,
  ``[ADD a, b -> c]`` (executed while power flows, EN/ENO).

The 2-D text becomes a small graph (:class:`~plclab.lang.lower.network.Elem`, shared with the
PLCopen XML importer), kept on the POU as a pending ``"NETWORK"`` body; the lowering stage
(:mod:`plclab.lang.lower.network`) turns the graph into statements: coils are assignments
(``S=``/``R=`` for set/reset coils), power flow is a BOOL expression, boxes are calls. Rungs run
top to bottom, elements left to right.

>>> f, diags = parse_ld_collect('''PROGRAM P VAR a, b, q : BOOL; END_VAR
... |   a       b      q  |
... |---[ ]-----[/]---( )-|
... END_PROGRAM''', "p.ld")
>>> diags, f.pous[0].language, type(f.pous[0].body[0]).__name__
([], 'LD', 'Assign')
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from ...errors import Diagnostic, Location
from .. import ast as A
from ..lexer import Lexer, Token
from ..lower.network import COMPARE, Elem, Ref
from ..parsing import ParseAbort
from .st import Parser, lower_alone

CONTACTS = {" ": "", "/": "/", "P": "P", "N": "N"}
COILS = {" ": "", "/": "/", "S": "S", "R": "R", "P": "P", "N": "N"}


# ---------------------------------------------------------------------------------------------
# The text format


@dataclass(eq=False)
class Network:
    """A block of consecutive rail lines of one POU, parsed."""

    first_line: int  # 1-based file line of lines[0]
    lines: list[str]
    left: int  # 0-based column of the left rail
    right: int | None  # 0-based column of the right rail, if drawn
    wire: list[bool]  # per line: a wire line (else names and vertical links)
    elems: list[Elem] = field(default_factory=list)
    names: list[tuple[int, int, int, str]] = field(default_factory=list)  # (row, c0, c1, text)
    grid: list[str] = field(default_factory=list)  # lines padded, decoration rails removed


_WIRE_RE = re.compile(r"[-+]|\[[^\]]*\]|\([ /SRPN]\)")
_NAME_RE = re.compile(r"[^\s|]+")


def _strip_comment(line: str) -> str:
    k = line.find("//")
    return (line[:k] if k >= 0 else line).rstrip()


def rail_lines(text: str) -> list[int]:
    """0-based indexes of the lines that belong to ladder networks: they start with '|' (not
    inside a comment: a drawing in a comment stays a comment)."""
    out = []
    depth = 0  # nesting of (* *) comments
    block = False  # inside /* */
    for i, line in enumerate(text.split("\n")):
        if depth == 0 and not block and line.lstrip().startswith("|"):
            out.append(i)
            continue
        k, n = 0, len(line)
        while k < n:
            two = line[k:k + 2]
            if block:
                if two == "*/":
                    block = False
                    k += 1
            elif two == "(*":
                depth += 1
                k += 1
            elif two == "*)" and depth:
                depth -= 1
                k += 1
            elif depth == 0:
                if two == "//":
                    break
                if two == "/*":
                    block = True
                    k += 1
                elif line[k] in "'\"":  # skip a string on this line
                    end = line.find(line[k], k + 1)
                    k = n if end < 0 else end
            k += 1
    return out


class _TextLadder:
    """Parses the rail lines of one POU into networks of :class:`Elem` (diagnostics on the way)."""

    def __init__(self, file: str, diags: list[Diagnostic]) -> None:
        self.file = file
        self.diags = diags
        self.elems: list[Elem] = []
        self.rung = 0
        self.networks: list[Network] = []

    def err(self, code: str, msg: str, line: int, col0: int) -> None:
        self.diags.append(Diagnostic(code, msg, Location(self.file, line, col0 + 1)))

    def loc(self, line: int, col0: int) -> Location:
        return Location(self.file, line, col0 + 1)

    def parse(self, numbered: list[tuple[int, str]]) -> list[Elem]:
        """``numbered``: (1-based line number, text) of the POU's rail lines, in order."""
        block: list[tuple[int, str]] = []
        for n, text in numbered:
            if block and n != block[-1][0] + 1:
                self.network(block)
                block = []
            block.append((n, text))
        if block:
            self.network(block)
        return self.elems

    # -- one network ------------------------------------------------------------------------
    def network(self, block: list[tuple[int, str]]) -> None:
        first = block[0][0]
        lines = [_strip_comment(t) for _, t in block]
        for k, t in enumerate(lines):
            if "\t" in t:
                self.err("PLC0166", "a rung must not contain tabs: columns decide what is "
                         "connected, so indent with spaces", first + k, t.index("\t"))
                return
        left = lines[0].index("|")
        for k, t in enumerate(lines):
            if t.index("|") != left:
                self.err("PLC0166", f"the left rail '|' must be in the same column on every "
                         f"line of a network (column {left + 1} on line {first})", first + k,
                         t.index("|"))
                return
        wire = [bool(_WIRE_RE.search(t[left + 1:])) for t in lines]
        rail_at = [len(t) - 1 if wire[k] and len(t) > left + 2 and t.endswith("|") else None
                   for k, t in enumerate(lines)]
        ends = [c for c in rail_at if c is not None]
        right = max(set(ends), key=lambda c: (ends.count(c), c)) if ends else None
        for k, c in enumerate(rail_at):
            if c is not None and c != right:
                self.err("PLC0166", f"the right rail '|' must be in the same column on every "
                         f"line (column {right + 1})", first + k, c)
        width = max(len(t) for t in lines) + 1
        grid = [t.ljust(width) for t in lines]
        # the right rail drawn on a name line is decoration, wherever it is
        for k, t in enumerate(lines):
            c = len(t) - 1
            if wire[k] or c <= left or t[c] != "|" or c == right:
                continue
            near = [grid[j][c] == ("+" if wire[j] else "|") for j in (k - 1, k + 1)
                    if 0 <= j < len(grid)]
            if not any(near):
                grid[k] = grid[k][:c] + " " + grid[k][c + 1:]
        # a '|' on a wire line with no wire on either side is a branch line passing by
        self.passing = {(k, c) for k, t in enumerate(grid) if wire[k]
                        for c in range(left + 1, len(t) - 1)
                        if t[c] == "|" and c != rail_at[k] and t[c - 1] == " " and
                        t[c + 1] == " "}
        net = Network(first, lines, left, right, wire, grid=grid)
        self.networks.append(net)
        self.grid, self.first, self.left, self.right, self.isw = grid, first, left, right, wire
        self.find = self.junctions()
        start = len(self.elems)
        self.nodes: dict[int, dict[str, Any]] = {}
        self.node_ids: dict[tuple[int, int], int] = {}
        for r, t in enumerate(grid):
            if wire[r]:
                self.wire_line(r, t, rail_at[r] if rail_at[r] is not None else right)
        self.resolve(start)
        self.assign_names(net, start)
        net.elems = self.elems[start:]

    def junctions(self):
        """Union the '+' junctions joined by vertical '|' lines; report open branches."""
        grid, left, right = self.grid, self.left, self.right
        parent: dict[tuple[int, int], tuple[int, int]] = {}

        def find(a):
            while parent.setdefault(a, a) != a:
                a = parent[a]
            return a

        h = len(grid)
        w = len(grid[0])
        def vertical(r: int, c: int) -> bool:
            ch = grid[r][c]
            if self.isw[r]:
                return ch == "+" or (r, c) in self.passing
            return ch == "|"

        for c in range(left + 1, w):
            if right is not None and c == right:
                continue
            r = 0
            while r < h:
                if not vertical(r, c):
                    r += 1
                    continue
                run = []
                while r < h and vertical(r, c):
                    run.append(r)
                    r += 1
                top, bottom = run[0], run[-1]
                if grid[top][c] == "|":
                    self.err("PLC0162", f"the branch line '|' at column {c + 1} has no '+' "
                             "junction at its top: start a branch with '+' on the wire above",
                             self.first + top, c)
                if grid[bottom][c] == "|":
                    self.err("PLC0162", f"the branch does not close: the vertical line at column "
                             f"{c + 1} ends without a '+' on a wire below; join it with '+'",
                             self.first + bottom, c)
                pluses = [(x, c) for x in run if grid[x][c] == "+"]
                for p in pluses:
                    find(p)
                for a, b in zip(pluses, pluses[1:], strict=False):
                    parent[find(b)] = find(a)
        return find

    def node(self, r: int, c: int) -> dict[str, Any]:
        key = self.find((r, c))
        nid = self.node_ids.setdefault(key, len(self.node_ids))
        n = self.nodes.get(nid)
        if n is None:
            n = self.nodes[nid] = {"inputs": [], "out": False, "at": (r, c), "id": nid}
        return n

    def new_elem(self, kind: str, r: int, c0: int, c1: int, text: str) -> Elem:
        e = Elem(len(self.elems), kind, self.loc(self.first + r, c0), text=text,
                 geom=(self.first + r, c0, c1))
        e.order = (self.first + r, c0)  # fixed up to (rung, column, line) in resolve()
        self.elems.append(e)
        return e

    def wire_line(self, r: int, t: str, rail: int | None) -> None:
        line = self.first + r
        end = rail if rail is not None else len(t.rstrip())
        c = self.left + 1
        cur: list | None = [("E", -1)] if t[c:c + 1] not in (" ", "") else None  # -1: rail
        broken_reported = False

        def need_left(col: int) -> list:
            nonlocal broken_reported
            if cur is None:
                if not broken_reported:
                    self.err("PLC0160", "broken wire: nothing connects this part of the rung "
                             "on its left; draw '-' to the left rail or join a branch with '+'",
                             line, col)
                    broken_reported = True
                return []
            return cur

        while c < end:
            ch = t[c]
            if ch == "-":
                cur = need_left(c)
                c += 1
            elif ch == "+":
                n = self.node(r, c)
                if cur is not None and t[c - 1] != " ":
                    n["inputs"].extend(cur)
                nxt = t[c + 1:c + 2]
                if nxt not in (" ", ""):
                    n["out"] = True
                    cur = [("N", n["id"])]
                else:
                    cur = None
                c += 1
            elif ch in "[(":
                close = "]" if ch == "[" else ")"
                k = t.find(close, c + 1)
                if k < 0 or k >= end:
                    self.err("PLC0164", f"'{ch}' at column {c + 1} is never closed with "
                             f"'{close}' on this line", line, c)
                    return
                inner = t[c + 1:k]
                ins = need_left(c)
                e = self.element(r, c, k, ch, inner)
                if e is not None:
                    e.inputs[""] = list(ins)
                    cur = [("E", e.id)]
                else:
                    cur = []
                c = k + 1
            elif ch == " " or (r, c) in self.passing:
                k = c
                while k < end and (t[k] == " " or (r, k) in self.passing):
                    k += 1
                if cur:
                    self.dangling(cur, line, c, at_rail=False)
                cur = None
                c = k
            elif ch == "|":
                self.err("PLC0162", "a vertical line crosses the wire here; join branches with "
                         "'+' on the wire (and '|' only between wires)", line, c)
                cur = []
                c += 1
            else:
                self.err("PLC0164", f"unexpected '{ch}' on the wire; variable names go on the "
                         "line above their element", line, c)
                cur = []
                c += 1
        if cur:
            self.dangling(cur, line, min(c, len(t)), at_rail=rail is not None)

    def dangling(self, cur: list, line: int, col: int, at_rail: bool) -> None:
        """The wire ends (at the right rail, or in the open): it must end in a coil or box."""
        kinds = self.producer_kinds(cur)
        if kinds and all(k in ("coil", "fb", "func") for k in kinds):
            if not at_rail and self.right is not None and "coil" in kinds:
                self.err("PLC0161", f"the coil is not connected to the right rail; continue the "
                         f"wire with '-' up to the rail in column {self.right + 1}", line, col)
            return
        if at_rail:
            self.err("PLC0160", "this branch reaches the right rail without a coil; put a coil "
                     "such as ( ) before the rail", line, col)
        else:
            self.err("PLC0160", "broken wire: the rung stops here without reaching a coil; "
                     "continue it with '-' or join it to a branch with '+'", line, col)

    def producer_kinds(self, refs: list, seen: set | None = None) -> list[str]:
        seen = set() if seen is None else seen
        out = []
        for kind, i in refs:
            if kind == "E":
                out.append("left" if i < 0 else self.elems[i].kind)
            elif i not in seen:
                seen.add(i)
                out.extend(self.producer_kinds(self.nodes[i]["inputs"], seen))
        return out

    def element(self, r: int, c0: int, c1: int, ch: str, inner: str) -> Elem | None:
        line = self.first + r
        text = ch + inner + ("]" if ch == "[" else ")")
        if ch == "(":
            kind, modes, forms = "coil", COILS, "coils are ( ) (/) (S) (R) (P) (N)"
        elif len(inner) <= 1:
            kind, modes, forms = "contact", CONTACTS, "contacts are [ ] [/] [P] [N]"
        else:
            return self.box(r, c0, c1, inner, text)
        mode = modes.get(inner.upper()) if len(inner) == 1 else None
        if mode is None:
            self.err("PLC0164", f"unknown {kind} '{text}'; {forms}", line, c0)
            return None
        e = self.new_elem(kind, r, c0, c1, text)
        e.mode = mode
        return e

    # -- boxes ------------------------------------------------------------------------------
    def box(self, r: int, c0: int, c1: int, inner: str, text: str) -> Elem | None:
        line = self.first + r
        lex = Lexer(" " * (c0 + 1) + inner, self.file)
        toks = lex.tokens()
        for t in toks:
            t.line = line
        for d in lex.diagnostics:
            self.diags.append(Diagnostic(d.code, d.message, Location(self.file, line,
                                                                     d.location.col)))
        if lex.diagnostics:
            return None
        if not toks or toks[0].kind != "IDENT":
            self.err("PLC0165", f"a box starts with its type, e.g. [TON T1 PT:=T#5s], "
                     f"[GT level 50], [MOVE 5 -> x]; found '{text}'", line, c0)
            return None
        tname = str(toks[0].value)
        arrow = next((k for k, t in enumerate(toks) if t.kind == "-" and toks[k + 1].kind == ">"
                      and toks[k + 1].col == t.col + 1), None)
        eof = toks[-1]

        def sub(ts: list[Token]) -> Parser:
            # EOF where the box's last token starts (an arrow or a name may follow nothing)
            return Parser.over_tokens(ts + [Token("EOF", None, "", eof.line, eof.col)],
                                      self.file, self.diags)

        try:
            if tname in COMPARE:
                q = sub(toks[1:])
                a = q.expr()
                q.accept(",")
                b = q.expr()
                if not q.at("EOF"):
                    q.fail_expected(f"the end of the {tname} box (two operands)")
                e = self.new_elem("cmp", r, c0, c1, text)
                e.type_name, e.args = tname, [A.Arg(a.loc, None, a), A.Arg(b.loc, None, b)]
                return e
            method = None
            if arrow is not None and len(toks) > 2 and toks[1].kind == ".":
                # [inst.Method args -> result]: a METHOD called like a function (ADR 0021)
                q = sub(toks[:arrow])
                method = q.postfix(q.primary())
                toks = [toks[0]] + toks[q.i:]
                arrow = next(k for k, t in enumerate(toks) if t.kind == "-" and
                             toks[k + 1].kind == ">")
            if arrow is not None:
                q = sub(toks[1:arrow])
                args = []
                while not q.at("EOF"):
                    x = q.expr()
                    args.append(A.Arg(x.loc, None, x))
                    q.accept(",")
                q = sub(toks[arrow + 2:])
                targets = [q.postfix(q.primary())]
                while q.accept(","):
                    targets.append(q.postfix(q.primary()))
                if not q.at("EOF"):
                    q.fail_expected("the end of the box after the result variable")
                e = self.new_elem("func", r, c0, c1, text)
                e.type_name, e.args, e.targets = tname, args, targets
                if method is not None:
                    e.type_name, e.instance = "", method
                return e
            q = sub(toks[1:])
            if q.at("EOF"):
                self.err("PLC0165", f"the {tname} box needs an instance name, e.g. "
                         f"[{tname} {tname[:1]}1 ...]; a function box needs '-> result'",
                         line, c0)
                return None
            inst = q.postfix(q.primary())
            params: list[A.Arg] = []
            while not q.at("EOF"):
                q.accept(",")
                if q.at("EOF"):
                    break
                nt = q.expect("IDENT", "a parameter such as PT:=T#5s or ET=>elapsed")
                ploc = Location(self.file, nt.line, nt.col)
                if q.accept("=>"):
                    params.append(A.Arg(ploc, str(nt.value), q.postfix(q.primary()), True))
                else:
                    q.expect(":=", f"':=' after {nt.text}")
                    params.append(A.Arg(ploc, str(nt.value), q.expr()))
            e = self.new_elem("fb", r, c0, c1, text)
            e.type_name, e.instance, e.args = tname, inst, params
            return e
        except ParseAbort:
            return None

    # -- after all lines ----------------------------------------------------------------------
    def resolve(self, start: int) -> None:
        """Replace junction references by what feeds them; check junctions; number rungs."""
        elems = self.elems[start:]
        for n in self.nodes.values():
            r, c = n["at"]
            if n["out"] and not n["inputs"]:
                self.err("PLC0160", "broken wire: nothing feeds this branch junction '+' from "
                         "the left", self.first + r, c)
            elif n["inputs"] and not n["out"]:
                kinds = self.producer_kinds(n["inputs"])
                if not all(k in ("coil", "fb", "func") for k in kinds):
                    self.err("PLC0160", "broken wire: the branch ends at this junction '+' "
                             "without reaching a coil", self.first + r, c)

        def flat(refs: list, seen: frozenset = frozenset()) -> list[Ref]:
            out: list[Ref] = []
            for kind, i in refs:
                if kind == "E":
                    out.append((i, ""))
                elif i not in seen:
                    out.extend(flat(self.nodes[i]["inputs"], seen | {i}))
            return out

        for e in elems:
            raw = e.inputs.get("", [])
            e.inputs[""] = [(-1 if i < 0 else i, pin) for i, pin in flat(raw)]
            for i, _ in e.inputs[""]:
                if i >= 0 and self.elems[i].kind == "coil":
                    self.err("PLC0161", f"{e.text} comes after a coil: a coil must be the last "
                             "element of its branch, at the right rail; put several coils on "
                             "parallel branches instead", e.loc.line, e.loc.col - 1)
                    break
        # rungs: connected groups of elements, numbered top to bottom
        parent = {e.id: e.id for e in elems}

        def find(a: int) -> int:
            while parent[a] != a:
                a = parent[a]
            return a

        for e in elems:
            for i, _ in e.inputs[""]:
                if i >= 0:
                    parent[find(i)] = find(e.id)
        groups: dict[int, list[Elem]] = {}
        for e in elems:
            groups.setdefault(find(e.id), []).append(e)
        for g in sorted(groups.values(), key=lambda g: min(x.order for x in g)):
            self.rung += 1
            for e in g:
                e.rung = self.rung
                e.order = (self.rung, e.geom[1], e.geom[0])

    def assign_names(self, net: Network, start: int) -> None:
        """Give each contact and coil the name written over it on the line above."""
        by_row: dict[int, list[Elem]] = {}
        for e in self.elems[start:]:
            by_row.setdefault(e.geom[0] - self.first, []).append(e)
        taken: dict[int, tuple[int, int, str]] = {}
        for r, t in enumerate(self.grid):
            if self.isw[r]:
                continue
            below = by_row.get(r + 1, []) if r + 1 < len(self.grid) and self.isw[r + 1] else []
            lo = self.left + 1
            hi = self.right if self.right is not None else len(t)
            for m in _NAME_RE.finditer(t, lo, hi):
                s, f = m.start(), m.end() - 1
                net.names.append((self.first + r, s, f, m.group()))
                best, overlap = None, 0
                for e in below:
                    ov = min(f, e.geom[2]) - max(s, e.geom[1]) + 1
                    if ov > overlap:
                        best, overlap = e, ov
                if best is None:
                    self.err("PLC0163", f"the name '{m.group()}' is not over a contact or coil of "
                             "the wire below; write it directly above its element", self.first + r,
                             s)
                    continue
                if best.kind not in ("contact", "coil"):
                    self.err("PLC0163", f"'{m.group()}' is over the box {best.text}; a box takes "
                             "its operands inside its brackets", self.first + r, s)
                    continue
                if best.id in taken:
                    self.err("PLC0163", f"two names over {best.text} at column "
                             f"{best.geom[1] + 1}: '{taken[best.id][2]}' and '{m.group()}'; "
                             "leave one", self.first + r, s)
                    continue
                taken[best.id] = (r, s, m.group())
        for e in self.elems[start:]:
            if e.kind not in ("contact", "coil"):
                continue
            got = taken.get(e.id)
            if got is None:
                what = "contact" if e.kind == "contact" else "coil"
                self.err("PLC0163", f"the {what} {e.text} has no variable name; write the name on "
                         "the line just above it, over its columns", e.loc.line, e.loc.col - 1)
                continue
            r, s, word = got
            line = self.first + r
            lex = Lexer(" " * s + word, self.file)
            toks = lex.tokens()
            for tk in toks:
                tk.line = line
            for d in lex.diagnostics:
                self.diags.append(Diagnostic(d.code, d.message, Location(self.file, line,
                                                                         d.location.col)))
            p = Parser.over_tokens(toks, self.file, self.diags)
            try:
                x = p.postfix(p.primary())
                if not p.at("EOF"):
                    p.fail_expected(f"the end of the name '{word}'")
                e.var = x
            except ParseAbort:
                pass


def parse_networks(numbered: list[tuple[int, str]], file: str = "<input>"):
    """Parse rail lines into networks; return (networks, elements, diagnostics)."""
    diags: list[Diagnostic] = []
    tl = _TextLadder(file, diags)
    elems = tl.parse(numbered)
    return tl.networks, elems, diags


def parse(text: str, file: str = "<input>.ld") -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse a ``.ld`` file: declarations as in ST, bodies as ladder networks (or ST/IL); the
    networks stay pending (``Pou.pending``) and drawn (``Pou.networks``)."""
    lines = text.split("\n")
    rails = rail_lines(text)
    rail_set = set(rails)
    blanked = "\n".join("" if i in rail_set else line for i, line in enumerate(lines))
    p = Parser(blanked, file)
    out = p.parse_file()
    diags = list(p.diagnostics)
    owner: dict[int, A.Pou] = {}
    for pou in out.pous:
        hi = pou.end_loc.line if pou.end_loc is not None else 10 ** 9
        for i in rails:
            if pou.loc.line < i + 1 < hi:
                owner[i] = pou
    for i in rails:
        if i not in owner:
            diags.append(Diagnostic("PLC0166", "a rung must be inside the body of a PROGRAM, "
                                    "FUNCTION_BLOCK or FUNCTION (after its declarations)",
                                    Location(file, i + 1, lines[i].index("|") + 1)))
    for pou in out.pous:
        mine = [(i + 1, lines[i]) for i in rails if owner.get(i) is pou]
        if not mine:
            continue
        stray = [s for s in pou.body if not isinstance(s, A.Empty)]
        if stray or pou.language != "ST":
            where = stray[0].loc if stray else pou.loc
            diags.append(Diagnostic("PLC0166", "a ladder body holds only rungs (lines starting "
                                    "with '|') and comments; write ST or IL in a POU of its own",
                                    where))
        pou.body = []
        pou.language = "LD"
        tl = _TextLadder(file, diags)
        elems = tl.parse(mine)
        pou.networks = tl.networks
        # the rungs replace whatever body the ST parser saw (an IL body was reported above)
        pou.pending = [A.PendingBody("NETWORK", elems, Location(file, mine[0][0], 1))]
    return out, diags


def parse_ld_collect(text: str, file: str = "<input>.ld") -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse a ``.ld`` file and lower its networks (the file alone)."""
    out, diags = parse(text, file)
    return out, diags + lower_alone(out)


__all__ = ["Network", "parse", "parse_ld_collect", "parse_networks", "rail_lines", "CONTACTS",
           "COILS"]
