"""The object-oriented extensions of ST (CODESYS V3, IEC 61131-3 ed.3), read by the ST parser.

``FUNCTION_BLOCK [ABSTRACT|FINAL] Name [EXTENDS Base] [IMPLEMENTS I1, I2]``, ``METHOD``
... ``END_METHOD`` inside a FUNCTION_BLOCK (before or after its body), and ``INTERFACE`` ...
``END_INTERFACE``. The words are not reserved by the lexer (older code may use them as names):
they are recognised here by position. What they mean is ADR 0021; the checks are
:mod:`plclab.lang.check.oop`.

The host parser (:class:`plclab.lang.frontends.st.Parser`) is passed in: this module does not
import it.

>>> from plclab.lang.frontends.st import parse_st
>>> f = parse_st("FUNCTION_BLOCK B EXTENDS A METHOD M : INT M := 1; END_METHOD END_FUNCTION_BLOCK"
...              " FUNCTION_BLOCK A END_FUNCTION_BLOCK", "b.st")
>>> b = f.pous[0]
>>> b.extends, [m.name for m in b.methods], b.methods[0].owner is b
(['A'], ['M'], True)
"""

from __future__ import annotations

from ...errors import Diagnostic
from ...suggest import suggest
from .. import ast as A
from ..lexer import Token, add_capped
from ..parsing import ParseAbort

MODIFIERS = ("ABSTRACT", "FINAL", "PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL", "OVERRIDE")
HEADER_WORDS = ("EXTENDS", "IMPLEMENTS")
ACCESS = ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL")
# words after which a statement list of a method or an FB body ends
BODY_STOPS = {"END_METHOD", "END_INTERFACE", "END_PROPERTY", "END_GET", "END_SET",
              "END_ACTION", "END_ACTIONS"}
MEMBER_STARTS = {"METHOD", "PROPERTY"}
_SECTIONS = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP")


def word(p, *words: str) -> bool:
    """The current token is the (unreserved) word ``words``."""
    return p.tok.kind == "IDENT" and p.tok.value in words


def ends_body(p) -> bool:
    """True where an ST statement list inside a FUNCTION_BLOCK, METHOD or INTERFACE ends:
    ``END_METHOD`` and friends, or ``METHOD name`` (a method after the FB body)."""
    if p.tok.kind != "IDENT":
        return False
    v = p.tok.value
    return v in BODY_STOPS or (v in MEMBER_STARTS and p.peek().kind == "IDENT")


def modifiers(p) -> list[str]:
    """``ABSTRACT``, ``FINAL`` and the access specifiers before a name (each followed by a
    name, so a block called ``Final`` still parses)."""
    out: list[str] = []
    while word(p, *MODIFIERS) and p.peek().kind == "IDENT":
        out.append(p.advance().value)
    return out


def header(p, pou_kind: str) -> tuple[list[str], list[str]]:
    """``EXTENDS Base`` and ``IMPLEMENTS I1, I2`` after a FUNCTION_BLOCK's (or, ``EXTENDS`` with
    several names, an INTERFACE's) name; a misspelling (the article's EXTENTS and IMPLEMETS) is
    reported with the right word and read as that word."""
    extends: list[str] = []
    implements: list[str] = []
    while p.tok.kind == "IDENT":
        t = p.tok
        w = t.value
        if w not in HEADER_WORDS:
            close = suggest(w, HEADER_WORDS, n=1, cutoff=0.7)
            if not close:
                break
            p.error("PLC0011", f"'{t.text}' is not a keyword; did you mean {close[0]}? "
                    f"(write {pou_kind} Name {close[0]} Other)")
            w = close[0]
        p.advance()
        names = [p.expect("IDENT", f"a name after {w}").value]
        while p.accept(","):
            names.append(p.expect("IDENT", f"a name after {w}").value)
        (extends if w == "EXTENDS" else implements).extend(names)
    return extends, implements


def members(p, owner: A.Pou, end_kw: str) -> None:
    """The METHODs and PROPERTYs at the current position of a FUNCTION_BLOCK (or INTERFACE),
    into ``owner.methods`` (a property is its accessor methods ``NAME__GET``, ``NAME__SET``)."""
    while word(p, *MEMBER_STARTS) and p.peek().kind in ("IDENT",):
        start = p.i
        try:
            if word(p, "PROPERTY"):
                new = prop(p, owner.kind == "INTERFACE")
            else:
                new = [method(p, owner.kind == "INTERFACE")]
            for m in new:
                m.owner = owner
                owner.methods.append(m)
                owner.decls.extend(  # VAR_INST: instance data of the block, hidden name
                    A.VarDecl(d.loc, A.method_inst_name(owner.name, m.name, d.name), d.type, d.init,
                              section="VAR", spelling=f"{owner.spelling}__{m.spelling}__{d.spelling}")
                    for d in m.decls if d.section == "VAR_INST")
        except ParseAbort:
            while not p.at("EOF", end_kw) and not word(p, "END_METHOD", "END_PROPERTY"):
                p.advance()
            p.advance() if not p.at("EOF", end_kw) else None
            p.ensure_progress(start)


def method(p, in_interface: bool) -> A.Pou:
    """``METHOD [mods] Name [: TYPE][;] sections body END_METHOD``."""
    head = p.advance()
    mods = modifiers(p)
    name = p.expect("IDENT", "a method name")
    ret = None
    if p.accept(":"):
        ret = p.type_ref()
    p.accept(";")  # the article writes METHOD HasError : BOOL;
    decls: list[A.VarDecl] = []
    while p.tok.kind in _SECTIONS or word(p, "VAR_INST"):
        inst = word(p, "VAR_INST")
        sec = p.var_section()
        for d in sec:
            d.section = "VAR_INST" if inst else d.section
        decls.extend(sec)
    body = p.stmt_list({"END_METHOD"})
    if in_interface and body:
        add_capped(p.diagnostics, Diagnostic(
            "PLC0234", f"a method of an interface has no body; move the statements of "
            f"{name.text} into the FUNCTION_BLOCKs that implement the interface",
            body[0].loc), p.file)
        body = []
    end_loc = p.loc()
    if not word(p, "END_METHOD"):
        p.fail_expected(f"END_METHOD to close METHOD {name.text}")
    p.advance()
    p.accept(";")
    return A.Pou(p.loc(head), "METHOD", name.value, decls, body, ret, name.text,
                 end_loc=end_loc, modifiers=mods)


def actions_block(p) -> list[tuple[Token | None, A.Pou]]:
    """``ACTIONS [Pou] ACTION A [:] ... END_ACTION ... END_ACTIONS`` (RuSTy's container for
    the actions of a PROGRAM or FUNCTION_BLOCK): (the POU's name token, or None for the POU
    just before, and the action) for each action."""
    p.advance()
    owner = None
    if p.tok.kind == "IDENT" and not word(p, "ACTION", "END_ACTIONS"):
        owner = p.advance()
    p.accept(";")
    out: list[tuple[Token | None, A.Pou]] = []
    while word(p, "ACTION"):
        qual, act = action(p)
        out.append((qual or owner, act))
    if not word(p, "END_ACTIONS"):
        p.fail_expected("ACTION or END_ACTIONS to close ACTIONS")
    p.advance()
    p.accept(";")
    return out


def action(p) -> tuple[Token | None, A.Pou]:
    """``ACTION [Pou.]Name [:] statements END_ACTION`` -> (the POU's name token if written,
    the action as a METHOD without declarations, ``action`` set)."""
    head = p.advance()
    name = p.expect("IDENT", "an action name after ACTION")
    qual = None
    if p.accept("."):
        qual, name = name, p.expect("IDENT", f"an action name after {name.text}.")
    p.accept(":")
    body = p.stmt_list(set())
    end_loc = p.loc()
    if not word(p, "END_ACTION"):
        p.fail_expected(f"END_ACTION to close ACTION {name.text}")
    p.advance()
    p.accept(";")
    return qual, A.Pou(p.loc(head), "METHOD", name.value, [], body, None, name.text,
                       end_loc=end_loc, action=True)


def attach_actions(p, out: A.SourceFile, found: list[tuple[Token | None, A.Pou, A.Pou | None]]
                   ) -> None:
    """Give each action to its PROGRAM or FUNCTION_BLOCK of the same file (named, or the POU
    before the ACTIONS block); PLC0198 when there is none."""
    pous = {q.name: q for q in out.pous if q.kind in ("PROGRAM", "FUNCTION_BLOCK")}
    for tok, act, before in found:
        owner = pous.get(tok.value) if tok is not None else before
        if owner is None or owner.kind not in ("PROGRAM", "FUNCTION_BLOCK"):
            what = f"{tok.text}, which is no PROGRAM or FUNCTION_BLOCK of this file" if tok \
                else "no PROGRAM or FUNCTION_BLOCK before it"
            add_capped(p.diagnostics, Diagnostic(
                "PLC0198", f"ACTION {act.spelling} belongs to {what}; write the actions after "
                "their POU (ACTIONS Name ... END_ACTIONS)", act.loc, "error"), p.file)
            continue
        act.owner = owner
        owner.methods.append(act)


def prop(p, in_interface: bool) -> list[A.Pou]:
    """``PROPERTY [mods] Name : TYPE  GET ... END_GET  SET ... END_SET  END_PROPERTY`` -> the
    accessor methods ``NAME__GET`` (its result is called Name) and ``NAME__SET`` (its input
    Name is the value assigned). In an interface, a property without accessors has both."""
    head = p.advance()
    mods = modifiers(p)
    name = p.expect("IDENT", "a property name")
    p.expect(":", "':' and the property's type")
    tref = p.type_ref()
    p.accept(";")
    out: list[A.Pou] = []
    while word(p, "GET", "SET"):
        acc = p.advance()
        decls: list[A.VarDecl] = []
        while p.tok.kind in ("VAR", "VAR_TEMP"):
            decls.extend(p.var_section())
        body = p.stmt_list(set())
        end = f"END_{acc.value}"
        if not word(p, end):
            p.fail_expected(f"{end} to close {acc.value} of PROPERTY {name.text}")
        p.advance()
        p.accept(";")
        if in_interface and body:
            p.error("PLC0234", "a property of an interface has no body; implement it in the "
                    "FUNCTION_BLOCKs", acc)
            body = []
        out.append(_accessor(p, head, name, acc.value, tref, decls, body, mods))
    if in_interface and not out:
        out = [_accessor(p, head, name, a, tref, [], [], mods) for a in ("GET", "SET")]
    if not word(p, "END_PROPERTY"):
        p.fail_expected(f"GET, SET or END_PROPERTY to close PROPERTY {name.text}")
    p.advance()
    p.accept(";")
    return out


def _accessor(p, head, name, acc: str, tref: A.TypeRef, decls: list[A.VarDecl],
              body: list[A.Stmt], mods: list[str]) -> A.Pou:
    loc = p.loc(head)
    if acc == "SET":
        value = A.VarDecl(loc, name.value, tref, section="VAR_INPUT", spelling=name.text)
        value.used = True
        return A.Pou(loc, "METHOD", f"{name.value}__SET", [value, *decls], body, None,
                     f"{name.text}.SET", modifiers=mods)
    return A.Pou(loc, "METHOD", f"{name.value}__GET", decls, body, tref, f"{name.text}.GET",
                 modifiers=mods)


def interface(p) -> A.Pou:
    """``INTERFACE Name [EXTENDS I1, I2] METHOD ... END_METHOD ... END_INTERFACE``."""
    head = p.advance()
    name = p.expect("IDENT", "a name for the INTERFACE")
    extends, implements = header(p, "INTERFACE")
    pou = A.Pou(p.loc(head), "INTERFACE", name.value, [], [], None, name.text,
                extends=extends + implements)
    if implements:
        p.error("PLC0011", "an INTERFACE extends other interfaces: write EXTENDS, not "
                "IMPLEMENTS", head)
    members(p, pou, "END_INTERFACE")
    if p.tok.kind in _SECTIONS:
        p.error("PLC0234", f"an INTERFACE declares methods only, no variables; move them into "
                f"the FUNCTION_BLOCKs that implement {name.text}")
        raise ParseAbort
    pou.end_loc = p.loc()
    if not word(p, "END_INTERFACE"):
        p.fail_expected(f"METHOD or END_INTERFACE to close INTERFACE {name.text}")
    p.advance()
    return pou


def ref_type(p) -> A.RefTypeRef | None:
    """``REF_TO T``, ``POINTER TO T``, ``REFERENCE TO T`` at the parser's position, or None."""
    t = p.tok
    if word(p, "REF_TO"):
        p.advance()
        return A.RefTypeRef(p.loc(t), "REF_TO", p.type_ref())
    if word(p, "POINTER", "REFERENCE") and p.peek().kind == "TO":
        p.advance()
        p.advance()
        return A.RefTypeRef(p.loc(t), t.value, p.type_ref())
    return None


def class_pou(p) -> A.Pou:
    """ed.3 ``CLASS [FINAL|ABSTRACT] Name [EXTENDS B] [IMPLEMENTS I] VAR ... METHOD ...
    END_CLASS`` (6.6.5.2): a FUNCTION_BLOCK without a body (``is_class``); a CLASS has no
    VAR_INPUT, VAR_OUTPUT or VAR_IN_OUT (PLC0341), its methods take the inputs."""
    head = p.advance()
    mods = modifiers(p)
    name = p.expect("IDENT", "a name for the CLASS")
    extends, implements = header(p, "FUNCTION_BLOCK")
    decls: list[A.VarDecl] = []
    while p.tok.kind in _SECTIONS or p.at("VAR_EXTERNAL"):
        section = p.tok
        got = p.var_section()
        if section.kind in ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT"):
            p.error("PLC0341", f"a CLASS has no {section.text} (IEC 61131-3 ed.3 6.6.5.2: "
                    f"only VAR and VAR_EXTERNAL); give the values to a METHOD of "
                    f"{name.text} as its VAR_INPUT, or write FUNCTION_BLOCK {name.text}",
                    section)
        decls.extend(got)
    pou = A.Pou(p.loc(head), "FUNCTION_BLOCK", name.value, decls, [], None, name.text,
                extends=extends, implements=implements, modifiers=mods, is_class=True)
    members(p, pou, "END_CLASS")
    pou.end_loc = p.loc()
    if not word(p, "END_CLASS"):
        p.fail_expected(f"METHOD or END_CLASS to close CLASS {name.text} (a CLASS has no "
                        "body: its statements go into METHODs)")
    p.advance()
    return pou


def this_or_super(p) -> A.Name | None:
    """``THIS^`` or ``SUPER^`` (the instance itself, its base part) as a name the checker
    knows (:mod:`plclab.lang.check.oop`); None when the current token starts neither. The
    ed.3 spellings (IEC 61131-3 ed.3 Annex A: ``THIS.x``, ``THIS.M()``, ``SUPER.M()``,
    ``SUPER()``) are the same names: the ``.`` or ``(`` is left for the caller (ADR 0059)."""
    if not word(p, "THIS", "SUPER"):
        return None
    after = p.peek().kind
    if after == "^":
        t = p.advance()
        p.advance()
    elif after == "." or (after == "(" and word(p, "SUPER")):
        t = p.advance()
    else:
        return None
    return A.Name(p.loc(t), t.value, t.text + "^")
