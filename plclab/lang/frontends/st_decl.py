"""The declarations of the ST parser: configurations, resources and tasks, VAR sections,
initializers, TYPE blocks and type references (a mixin of
:class:`plclab.lang.frontends.st.Parser`).
"""

from __future__ import annotations

from contextlib import contextmanager

from ...errors import Diagnostic
from .. import ast as A
from ..addresses import canonical, hierarchical
from ..datasize import NESTING_LIMIT
from ..lexer import Token, add_capped
from ..parsing import ParseAbort
from . import oop
from .st_words import DECL_STOP, POU_START, found_token


class DeclParse:
    """Declarations (a mixin of Parser)."""

    def configuration(self) -> A.Configuration:
        head = self.advance()
        name = self.expect("IDENT", "a configuration name").value
        cfg = A.Configuration(self.loc(head), name, [], [], [])
        while not self.at("END_CONFIGURATION", "EOF"):
            if self.at("VAR_GLOBAL"):
                cfg.globals.extend(self.var_section())
            elif self.at("VAR_CONFIG"):
                cfg.config_vars.extend(self.config_section())
            elif self.at("VAR_ACCESS"):
                cfg.access_paths.extend(self.access_section())
            elif self.accept("RESOURCE"):
                res = str(self.expect("IDENT", "a resource name").value)
                cfg.resources.append(res)
                if self.accept("ON"):
                    self.expect("IDENT", "a processor type")
                while not self.at("END_RESOURCE", "EOF"):
                    if self.at("VAR_GLOBAL"):
                        cfg.resource_globals.setdefault(res, []).extend(self.var_section())
                    elif self.at("TASK"):
                        cfg.tasks.append(self.task_decl())
                        cfg.tasks[-1].resource = res
                    elif self.at("PROGRAM"):
                        cfg.instances.append(self.program_instance())
                        cfg.instances[-1].resource = res
                    else:
                        self.fail_expected("TASK, PROGRAM or END_RESOURCE")
                self.expect("END_RESOURCE")
                self.accept(";")
            elif self.at("TASK"):
                cfg.tasks.append(self.task_decl())
            elif self.at("PROGRAM"):
                cfg.instances.append(self.program_instance())
            else:
                self.fail_expected("RESOURCE, TASK, PROGRAM, VAR_GLOBAL, VAR_CONFIG, VAR_ACCESS "
                                   "or END_CONFIGURATION")
        self.expect("END_CONFIGURATION")
        cfg.settle_resources()
        return cfg

    def instance_path(self, what: str) -> tuple[list[Token], Token | None]:
        """``STATION_1.P1.FB1.C2`` (names) or ``STATION_1.%IX1.1`` (names, then an address)."""
        parts = [self.expect("IDENT", what)]
        while self.accept("."):
            if self.at("ADDR"):
                return parts, self.advance()
            parts.append(self.expect("IDENT", "a name after '.'"))
        return parts, None

    def config_section(self) -> list[A.ConfigVar]:
        """``VAR_CONFIG path [AT %addr] : type [:= value]; ... END_VAR``."""
        self.advance()
        out: list[A.ConfigVar] = []
        while not self.at("END_VAR", "EOF") and self.tok.kind not in DECL_STOP:
            start = self.i
            try:
                parts, _ = self.instance_path("an instance path such as Main.fb1.x")
                address = None
                if self.accept("AT"):
                    address = self.address(self.expect("ADDR", "a direct address such as "
                                                       "%IX0.0"))
                self.expect(":", "':' and the variable's type")
                tref = self.type_ref()
                init = self.initializer() if self.accept(":=") else None
                if not self.accept(";"):
                    self.fail_expected("';' after the VAR_CONFIG line")
                out.append(A.ConfigVar(self.loc(parts[0]), [p.value for p in parts],
                                       ".".join(p.text for p in parts), address, tref, init))
            except ParseAbort:
                self.sync({"END_VAR"} | DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def access_section(self) -> list[A.AccessPath]:
        """``VAR_ACCESS name : path : type [READ_ONLY | READ_WRITE]; ... END_VAR``."""
        self.advance()
        out: list[A.AccessPath] = []
        while not self.at("END_VAR", "EOF") and self.tok.kind not in DECL_STOP:
            start = self.i
            try:
                name = self.expect("IDENT", "the access path's name")
                self.expect(":", "':' and the path it names")
                parts, addr = self.instance_path("a variable path such as P1.x")
                path = [p.value for p in parts] + ([canonical(addr.value)] if addr else [])
                spelled = ".".join([p.text for p in parts] + ([addr.text] if addr else []))
                self.expect(":", "':' and the type")
                tref = self.type_ref()
                read_only = True
                if self.at("IDENT") and self.tok.value in ("READ_ONLY", "READ_WRITE"):
                    read_only = self.advance().value == "READ_ONLY"
                if not self.accept(";"):
                    self.fail_expected("';' after the VAR_ACCESS line")
                out.append(A.AccessPath(self.loc(name), name.value, name.text, path, spelled,
                                        tref, read_only))
            except ParseAbort:
                self.sync({"END_VAR"} | DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def task_decl(self) -> A.TaskDecl:
        head = self.advance()
        name = self.expect("IDENT", "a task name").value
        task = A.TaskDecl(self.loc(head), name, None, None)
        self.expect("(")
        while not self.at(")"):
            key = self.expect("IDENT", "INTERVAL, PRIORITY or SINGLE").value
            self.expect(":=")
            val = self.expr()
            if key == "INTERVAL":
                task.interval = val
            elif key == "PRIORITY":
                task.priority = val
            elif key == "SINGLE":
                task.single = val
            else:
                self.error("PLC0010", f"unknown task property {key}; use INTERVAL, PRIORITY "
                           "or SINGLE")
            if not self.accept(","):
                break
        self.expect(")")
        self.expect(";")
        return task

    def program_instance(self) -> A.ProgramInstance:
        head = self.advance()
        name = self.expect("IDENT", "a program instance name").value
        task = None
        if self.accept("WITH"):
            task = self.expect("IDENT", "a task name").value
        self.expect(":")
        prog_tok = self.expect("IDENT", "a program type name")
        call = None
        if self.at("("):  # connections (ed.3 Figure 21): inputs from, outputs to, the outside
            loc = self.loc()
            self.advance()
            args = self.call_args()
            call = A.Call(loc, A.Name(self.loc(prog_tok), prog_tok.value, prog_tok.text), args)
        self.expect(";")
        return A.ProgramInstance(self.loc(head), name, task, prog_tok.value, call)

    # -- declarations -------------------------------------------------------------------------
    def var_section(self) -> list[A.VarDecl]:
        sec_tok = self.advance()
        section = sec_tok.kind
        constant = retain = False
        while self.at("CONSTANT", "RETAIN", "NON_RETAIN", "PERSISTENT") or (
                oop.word(self, *oop.ACCESS) and self.peek().kind == "IDENT"):
            # ed.3 Annex A var_decls: VAR [CONSTANT] [PUBLIC|PRIVATE|PROTECTED|INTERNAL]; the
            # access specifier of a class's variables is read and not enforced (ADR 0059)
            k = self.advance().kind
            constant |= k == "CONSTANT"
            retain |= k in ("RETAIN", "PERSISTENT")
        out: list[A.VarDecl] = []
        while not self.at("END_VAR"):
            if self.tok.kind in DECL_STOP:
                # a section or POU starts before this one is closed: report it and let the
                # caller go on from here (never loop on the same token)
                self.error("PLC0010", f"expected END_VAR to close the {section} section opened "
                           f"at line {sec_tok.line}, found {found_token(self.tok)}; add END_VAR "
                           "before it")
                raise ParseAbort
            start = self.i
            try:
                out.extend(self.var_decl(section, constant, retain))
            except ParseAbort:
                self.sync({"END_VAR"} | DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def var_decl(self, section: str, constant: bool, retain: bool) -> list[A.VarDecl]:
        if self.at("AT"):  # unnamed: AT %IX1.1 : BOOL; (IEC 61131-3 ed.3 Table 16)
            at = self.tok
            names = [Token("IDENT", "", "", at.line, at.col)]
        else:
            names = [self.expect("IDENT", "a variable name")]
            while self.accept(","):
                names.append(self.expect("IDENT", "a variable name"))
        address = None
        if self.accept("AT"):
            address = self.address(self.expect("ADDR", "a direct address such as %IX0.0"))
            if not names[0].value:  # the unnamed variable is called by its address
                text = address.replace("%", "").replace(".", "_")
                names = [Token("IDENT", f"AT_{text}", address, names[0].line, names[0].col)]
        if self.at(":="):
            self.error("PLC0010", "a declaration needs a type before the initial value: "
                       "write  name : TYPE := value;")
            raise ParseAbort
        self.expect(":", "':' and a type")
        tref = self.type_ref()
        if self.at("IDENT") and self.tok.value in ("R_EDGE", "F_EDGE"):
            self.edge_qualifier(section, tref, names)
        init = None
        if self.accept(":="):
            init = self.initializer()
        if not self.accept(";"):
            self.fail_expected("';' after the declaration")
        return [
            A.VarDecl(self.loc(n), n.value, tref, init, address, section, constant, retain, n.text)
            for n in names
        ]

    def edge_qualifier(self, section: str, tref: A.TypeRef, names: list[Token]) -> None:
        """``x : BOOL R_EDGE;`` (IEC 61131-3 ed.3 6.5.2.2): recorded for the lowering stage
        (:mod:`plclab.lang.lower.edges`); only a BOOL VAR_INPUT may carry it (PLC0179)."""
        qualifier = self.advance()
        if section != "VAR_INPUT" or not (isinstance(tref, A.NamedTypeRef)
                                          and tref.name == "BOOL"):
            self.error("PLC0179", f"{qualifier.value} qualifies a BOOL input only: declare "
                       f"it as  name : BOOL {qualifier.value};  in VAR_INPUT", qualifier)
            return
        self.edge_inputs.extend((n.value, qualifier.value == "R_EDGE", self.loc(n))
                                for n in names)

    def address(self, t: Token) -> str:
        """A direct address in its canonical form (:mod:`plclab.lang.addresses`); a
        hierarchical one is read by its last field, with a warning."""
        words = self.dialect.hierarchical_words
        address = canonical(t.value, words)
        if t.value != address and hierarchical(t.value, words):
            add_capped(self.diagnostics, Diagnostic(
                "PLC0175", f"{t.text[:40]} is hierarchical; plclab's process image is flat, so "
                f"it is read as {address} (the leading fields name hardware a simulated PLC "
                "does not have); write the flat address to say so", self.loc(t), "warning"),
                self.file)
        return address

    def initializer(self) -> A.Expr:
        if self.at("["):
            with self.nested("initial value"):
                return self.array_init()
        if self.at("(") and self.peek().kind == "IDENT" and self.peek(2).kind == ":=":
            with self.nested("initial value"):
                return self.struct_init()
        return self.expr()

    def array_init(self) -> A.ArrayInit:
        start = self.advance()
        items: list[tuple[A.Expr | None, A.Expr]] = []
        while not self.at("]"):
            if self.at("INT") and self.peek().kind == "(":
                rep = A.Literal(self.loc(), self.advance().value, "INT")
                self.advance()
                val = self.initializer() if not self.at(")") else None
                self.expect(")")
                items.append((rep, val if val is not None else A.Literal(rep.loc, None, "DEFAULT")))
            else:
                items.append((None, self.initializer()))
            if not self.accept(","):
                break
        self.expect("]", "']' to close the array initial value")
        return A.ArrayInit(self.loc(start), items)

    def struct_init(self) -> A.StructInit:
        start = self.advance()
        fields = []
        while not self.at(")"):
            n = self.expect("IDENT", "a field name")
            self.expect(":=")
            fields.append((n.value, self.initializer(), self.loc(n)))
            if not self.accept(","):
                break
        self.expect(")")
        return A.StructInit(self.loc(start), fields)

    def type_block(self) -> list[A.TypeDecl]:
        self.advance()
        out = []
        while not self.at("END_TYPE"):
            if self.at("EOF") or self.tok.kind in POU_START:
                self.fail_expected("END_TYPE")
            start = self.i
            try:
                n = self.expect("IDENT", "a type name")
                self.expect(":")
                tref = self.type_ref(allow_decl=True)
                init = None
                if self.accept(":="):
                    init = self.initializer()
                self.type_end()
                out.append(A.TypeDecl(self.loc(n), n.value, tref, init, n.text))
            except ParseAbort:
                self.sync({"END_TYPE"} | POU_START)
                self.ensure_progress(start)
        self.expect("END_TYPE")
        return out

    def type_end(self) -> None:
        """The ``;`` after a type declaration; CODESYS and TIA Portal let a declaration that
        ends with END_STRUCT (or the last one, before END_TYPE) go without it."""
        if self.accept(";"):
            return
        prev = self.toks[self.i - 1] if self.i else None
        if self.dialect.type_semicolon_optional and (
                self.at("END_TYPE") or (prev is not None and prev.kind == "END_STRUCT")):
            return
        if prev is not None and prev.kind == "END_STRUCT" or self.at("END_TYPE"):
            self.error("PLC0171", f"';' missing after this type declaration: the dialect "
                       f"'{self.dialect.name}' needs it (CODESYS and S7 do not); add ';' or "
                       "choose {dialect 'codesys'}")
            raise ParseAbort
        self.expect(";")

    def type_ref(self, allow_decl: bool = True) -> A.TypeRef:
        with self.nested("type"):
            return self._type_ref(allow_decl)

    @contextmanager
    def nested(self, what: str):
        """Count nesting of types and initial values written inside each other; beyond
        :data:`NESTING_LIMIT` levels report PLC0124 and give up the declaration."""
        if self.depth >= NESTING_LIMIT:
            self.error("PLC0124", f"this {what} is nested more than {NESTING_LIMIT} levels "
                       "deep; declare the inner levels as named TYPEs with fewer levels")
            raise ParseAbort
        self.depth += 1
        try:
            yield
        finally:
            self.depth -= 1

    def _type_ref(self, allow_decl: bool = True) -> A.TypeRef:
        t = self.tok
        loc = self.loc()
        ref = oop.ref_type(self)  # REF_TO T, POINTER TO T, REFERENCE TO T (ADR 0021)
        if ref is not None:
            return ref
        if t.kind in ("STRING", "WSTRING"):
            self.advance()
            length = None
            if self.accept("[") or self.accept("("):
                length = self.expr()
                if not (self.accept("]") or self.accept(")")):
                    self.fail_expected("']' after the string length")
            return A.StringTypeRef(loc, t.kind == "WSTRING", length)
        if t.kind == "ARRAY":
            self.advance()
            self.expect("[", "'[' and the index ranges, e.g. ARRAY[1..10] OF INT")
            if self.at("*"):  # ARRAY[*, *] OF T: variable length (IEC 61131-3 ed.3 6.5.3)
                star = 0
                while self.accept("*"):
                    star += 1
                    if not self.accept(","):
                        break
                self.expect("]", "']' after the '*' of each dimension, e.g. ARRAY[*, *] OF INT")
                self.expect("OF", "OF and the element type")
                return A.ArrayTypeRef(loc, [], self.type_ref(), star)
            ranges = []
            while True:
                lo = self.expr()
                self.expect("..", "'..' between the lower and upper bound")
                hi = self.expr()
                ranges.append((lo, hi))
                if not self.accept(","):
                    break
            self.expect("]")
            self.expect("OF", "OF and the element type")
            return A.ArrayTypeRef(loc, ranges, self.type_ref())
        if t.kind == "STRUCT":
            self.advance()
            fields: list[A.VarDecl] = []
            while not self.at("END_STRUCT"):
                if self.at("EOF", "END_TYPE"):
                    self.fail_expected("END_STRUCT")
                fields.extend(self.var_decl("STRUCT", False, False))
            self.expect("END_STRUCT")
            return A.StructTypeRef(loc, fields)
        if t.kind == "(":
            self.advance()
            members = []
            spellings: dict[str, str] = {}
            while True:
                n = self.expect("IDENT", "an enumeration value name")
                val = None
                if self.accept(":="):
                    val = self.expr()
                members.append((n.value, val, self.loc(n)))
                spellings[n.value] = n.text
                if not self.accept(","):
                    break
            self.expect(")", "')' to close the enumeration")
            base = None
            if self.at("IDENT") and not self.at(";"):
                base = A.NamedTypeRef(self.loc(), self.advance().value)
            return A.EnumTypeRef(loc, members, base, spellings)
        if t.kind == "IDENT":
            self.advance()
            base = A.NamedTypeRef(loc, t.value)
            if self.at("(") and self._fb_init_args(t.value):
                # a : FB(k := 3): the arguments of the block's FB_init (CODESYS; ADR 0052)
                self.advance()
                base.args = self.call_args()
                return base
            if self.at("(") and self.peek().kind != "IDENT" or (
                self.at("(") and self.peek(2).kind == ".."
            ):
                self.advance()
                lo = self.expr()
                self.expect("..", "'..' in the subrange")
                hi = self.expr()
                self.expect(")")
                return A.SubrangeTypeRef(loc, base, lo, hi)
            if self.at("(") and self.peek().kind == "IDENT":
                # typed enumeration: INT (A, B)  -- rare; treat as enum with base
                enum = self.type_ref()
                assert isinstance(enum, A.EnumTypeRef)
                enum.base = base
                return enum
            return base
        self.fail_expected("a type name")
        raise AssertionError
