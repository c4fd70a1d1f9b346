"""Pass: the whole program -- configuration and tasks, recursion among POUs, data that contains
itself or is too large (PLC0100, PLC0110, PLC0123, PLC0124, PLC0129)."""

from __future__ import annotations

from ...errors import Location
from .. import ast as A
from .. import datasize
from .. import types as T
from ..datasize import DataSizes
from ..limits import MAX_INTERVAL_NS, MIN_INTERVAL_NS
from .pass_api import Pass


class ProgramChecks(Pass):
    """Checks what needs every POU checked first."""

    def configuration(self) -> tuple[list[tuple[str, A.Pou, str | None]], list[A.TaskDecl]]:
        """The program instances and the tasks; without a CONFIGURATION every PROGRAM runs
        once, in the default task. The symbol table remembers the instances."""
        tasks: list[A.TaskDecl] = []
        programs: list[tuple[str, A.Pou, str | None]] = []
        if self.table.configs:
            for c in self.table.configs:
                tasks.extend(c.tasks)
                for t in c.tasks:
                    self.check_task(t)
                programs += self.table.instances(c, self.cx.report)
        else:
            programs = self.table.programs()
        self.table.set_programs(programs)
        if self.table.resource_externals:
            self.check_resource_externals(programs)
        return programs, tasks

    def check_resource_externals(self, programs: list[tuple[str, A.Pou, str | None]]) -> None:
        """Each VAR_EXTERNAL naming a resource's global (ADR 0037) must find it, of its type, in
        every resource whose programs reach the POU declaring it (PLC0132, PLC0103)."""
        done: set[tuple[int, str | None]] = set()
        for inst, pou, _ in programs:
            res = self.table.resource_of(inst)
            own = self.table.resource_globals.get(res or "", {})
            for q in self.reachable(pou):
                for d in self.table.resource_externals.get(q.name, []):
                    if (id(d), res) in done:
                        continue
                    done.add((id(d), res))
                    g = own.get(d.name)
                    if g is None:
                        where = [r for r, gs in self.table.resource_globals.items() if d.name in gs]
                        self.err("PLC0132", f"VAR_EXTERNAL {d.name} of {q.spelling or q.name} "
                                 f"names a global of resource {', '.join(where)}, but program "
                                 f"instance {inst} runs in " + (f"resource {res}" if res else
                                 "no resource") + ", which cannot see it; declare it in the "
                                 "configuration's VAR_GLOBAL or in that resource's", d.loc)
                    elif d.ty is not None and g.ty is not T.ANY and \
                            not T.same_type(d.ty, g.ty):
                        self.err("PLC0103", f"VAR_EXTERNAL {d.name} is {d.ty} but the global of "
                                 f"resource {res} is {g.ty}", d.loc)
                    else:
                        g.used = True

    def reachable(self, root: A.Pou) -> list[A.Pou]:
        """``root`` and every POU its instances run: block instances it declares (through
        arrays), their bases and methods, the POUs it calls."""
        seen: dict[str, A.Pou] = {}
        stack = [root]
        while stack:
            p = stack.pop()
            if p.name in seen:
                continue
            seen[p.name] = p
            stack += self.table.bases(p) + list(getattr(p, "methods", []) or [])
            for d in self.table.members(p).values():
                t = T.resolve(d.ty) if d.ty is not None else None
                while isinstance(t, T.ArrayType):
                    t = T.resolve(t.elem)
                if isinstance(t, T.FBType) and isinstance(t.pou, A.Pou):
                    stack.append(t.pou)
            stack += [c for n in self.cx.call_graph.get(p.name, ()) if
                      (c := self.table.pous.get(n)) is not None]
        return list(seen.values())

    def check_task(self, t: A.TaskDecl) -> None:
        """INTERVAL a TIME constant > 0, PRIORITY an integer constant 0..31 (CODESYS; 0..65535 in
        iec and matiec, ``Dialect.max_priority``) (PLC0129); both are
        replaced by their folded literal, which is what the runtime reads."""
        if t.interval is not None:
            e = t.interval
            ty = T.resolve(self.cx.exprs.expr(e, None))
            v = self.cx.consts.const_value(e) if ty.kind == "time" else None
            if ty.kind != "time" or not isinstance(v, int):
                self.err("PLC0129", f"the INTERVAL of task {t.name} must be a TIME constant, "
                         "e.g. INTERVAL := T#10ms", e.loc)
            elif ty is not T.LTIME and v % 1_000_000 and v < 1_000_000:
                self.err("PLC0129", f"the INTERVAL of task {t.name} is less than 1 ms, which a "
                         "TIME (whole milliseconds) cannot hold; write LTIME#500us or more than "
                         "T#1ms", e.loc)
            elif not MIN_INTERVAL_NS <= v <= MAX_INTERVAL_NS:
                self.err("PLC0129", f"the INTERVAL of task {t.name} is {v / 1e6:g} ms; it must "
                         "lie between 0.1 ms (LTIME#100us) and 1 day, e.g. INTERVAL := T#10ms",
                         e.loc)
            else:
                t.interval = A.Literal(e.loc, v if ty is T.LTIME else v // 1_000_000 * 1_000_000,
                                       "TIME", None,
                                       e.text if isinstance(e, A.Literal | A.Name) else "")
                t.interval.ty = ty
        if t.priority is not None:
            e = t.priority
            ty = T.resolve(self.cx.exprs.expr(e, None))
            v = self.cx.consts.const_value(e)
            top = self.cx.dialect(e.loc).max_priority
            if ty.kind != "int" or isinstance(v, bool) or not isinstance(v, int) or \
                    not 0 <= v <= top:
                self.err("PLC0129", f"the PRIORITY of task {t.name} must be an integer constant "
                         f"0..{top} (0 is the most urgent)" + (
                             "; IEC and MATIEC take larger ones ({dialect 'matiec'})"
                             if top < 65535 and isinstance(v, int) and 0 <= v <= 65535 else ""),
                         e.loc)
            else:
                t.priority = A.Literal(e.loc, v, "INT", None, str(v))
                t.priority.ty = ty

    def check_recursion(self) -> None:
        """PLC0110 at the call that closes each circle of calls, naming it (F -> G -> F).
        Iterative depth-first walk: long call chains are fine."""
        state: dict[str, int] = {}
        for root in list(self.cx.call_graph):
            if root in state:
                continue
            state[root] = 1
            path = [root]
            stack = [iter(sorted(self.cx.call_graph.get(root, ())))]
            while stack:
                m = next(stack[-1], None)
                if m is None:
                    stack.pop()
                    state[path.pop()] = 2
                    continue
                if state.get(m) == 1:
                    n = path[-1]
                    cyc = path[path.index(m):] + [m]
                    names = [self.table.pous[x].spelling or x for x in cyc]
                    if len(names) > 9:
                        names = names[:4] + [f"({len(names) - 8} more)"] + names[-4:]
                    where = self.cx.call_sites.get((n, m), self.table.pous[m].loc)
                    self.err("PLC0110", "recursion is not allowed in IEC 61131-3 (a PLC has no "
                             f"dynamic stack): {' -> '.join(names)}; this call closes the "
                             "circle: rewrite it as a loop", where)
                elif m not in state:
                    state[m] = 1
                    path.append(m)
                    stack.append(iter(sorted(self.cx.call_graph.get(m, ()))))

    def check_data(self, programs: list, tests: list[A.TestBlock]) -> None:
        """Blocks and structures must not contain themselves; every POU's and TEST's data and
        the program's whole data must stay within :data:`datasize.DATA_LIMIT` bytes and
        :data:`datasize.NESTING_LIMIT` levels (PLC0123, PLC0124)."""
        ds = DataSizes()
        for p in self.table.pous.values():
            if p.kind != "FUNCTION":
                ds.ensure(p)
        for t in list(self.table.types.values()):
            if isinstance(T.resolve(t), T.StructType):
                ds.ensure(T.resolve(t))
        seen: set[frozenset] = set()
        for closing, text, ring in ds.cycles:
            key = frozenset(id(c) for c in ring)
            if key not in seen:
                seen.add(key)
                self.err("PLC0123", f"{text}: {datasize.container_name(ring[0])} contains an "
                         "instance of itself, which would be infinitely large; remove "
                         f"{closing.spelling or closing.name} or pass the block as VAR_IN_OUT",
                         closing.loc)
        if seen:
            return  # sizes are meaningless until the circle is gone
        scopes: list[tuple[str, list[A.VarDecl], Location]] = [
            (f"{p.kind} {p.spelling or p.name}", datasize.members(p), p.loc)
            for p in self.table.pous.values() if not p.loc.file.startswith("<plclab>/")]
        scopes += [(f"TEST '{t.title}'", t.decls, t.loc) for t in tests]
        for what, decls, loc in scopes:
            if self._data_fits(ds, what, decls, loc, None):
                continue
            return
        top = list(self.table.globals.values())
        total, depth, _ = ds.decls_cost(top)
        big, big_bytes, owner = None, -1, None
        for d in top:
            b, _ = ds.type_cost(d.ty)
            if b > big_bytes:
                big, big_bytes, owner = d, b, None
        for inst, p, _ in programs:
            b, dep = ds.type_cost(self.table.types.get(p.name))
            total += b
            if b > big_bytes:
                big, big_bytes, owner = ds.biggest.get(id(p)), b, inst
        if total > datasize.DATA_LIMIT and big is not None:
            self.err("PLC0124", f"the program's data takes {total:,} bytes, more than the limit "
                     f"of {datasize.DATA_LIMIT:,} (16 MiB); the largest part: "
                     f"{ds.chain(big, owner)}. Use smaller arrays", big.loc)

    def _data_fits(self, ds: DataSizes, what: str, decls: list[A.VarDecl], loc: Location,
                   owner: str | None) -> bool:
        size, depth, big = ds.decls_cost(decls)
        if big is None:
            return True
        name = what.split(" ", 1)[1].strip("'")
        if depth > datasize.NESTING_LIMIT:
            self.err("PLC0124", f"the data of {what} nests {depth} levels deep (arrays, "
                     f"structures and instances inside each other; the limit is "
                     f"{datasize.NESTING_LIMIT}): {ds.chain(big, name)}", big.loc)
            return False
        if size > datasize.DATA_LIMIT:
            self.err("PLC0124", f"the data of {what} takes {size:,} bytes, more than the limit "
                     f"of {datasize.DATA_LIMIT:,} (16 MiB): {ds.chain(big, name)}; use smaller "
                     "arrays", big.loc)
            return False
        return True
