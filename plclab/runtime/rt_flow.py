"""Statements that need help at run time: FOR loops (a variable that wraps, charged to the
watchdog), large CASE statements, and the ASSERTs of TEST blocks."""

from __future__ import annotations

import bisect

from .rt_faults import AssertFailure, Budget, Fault
from .rt_strings import format_value


def _wd(where: int):
    raise Fault("PLC2003", "watchdog: the scan did not finish within its budget; this loop "
                "runs too long or never ends (inputs do not change during a scan, so waiting "
                "for one in a loop never ends: use IF and let the next scan check again)", where)


def _frange(s: int, e: int, st: int, lo: int, hi: int, where: int, budget: Budget | None):
    """The values of ``FOR v := s TO e BY st`` for a variable of range lo..hi, as the hardware
    runs it (``v := v + st`` wraps): a ``range`` when the loop ends without wrapping (the fast
    path), else a :class:`_ForWrap`, which charges ``budget`` per pass."""
    if st == 0:
        raise Fault("PLC2005", "FOR ... BY 0 never ends; use a step other than 0", where)
    if (e - s) * st < 0:  # no pass at all
        return range(s, s)
    last = s + (e - s) // st * st
    if lo <= last + st <= hi:
        return range(s, e + (1 if st > 0 else -1), st)
    return _ForWrap(s, e, st, lo, hi, where, budget)


class _ForWrap:
    """A FOR loop whose variable wraps at its type's limits (SINT 127 + 1 = -128), so it ends
    late or never; ``len()`` is 0 because each pass is charged to the watchdog as it runs."""

    def __init__(self, s: int, e: int, st: int, lo: int, hi: int, where: int,
                 budget: Budget | None) -> None:
        self.s, self.e, self.st, self.lo, self.hi = s, e, st, lo, hi
        self.where, self.budget = where, budget
        self.final = s
        self.wrapped: tuple[int, int] | None = None  # the last wrap: value before, after

    def __len__(self) -> int:
        return 0

    def __iter__(self):
        v, e, st, lo, hi, budget = self.s, self.e, self.st, self.lo, self.hi, self.budget
        while v <= e if st > 0 else v >= e:
            if budget is not None:
                budget.left -= 1
                if budget.left < 0:
                    self.overrun()
            yield v
            if not lo <= v + st <= hi:
                self.wrapped = (v, (v + st - lo) % (hi - lo + 1) + lo)
                v = self.wrapped[1]
            else:
                v += st
        self.final = v

    def overrun(self):
        if self.wrapped is None:
            _wd(self.where)
        a, b = self.wrapped
        step = f"+ {self.st}" if self.st > 0 else f"- {-self.st}"
        raise Fault("PLC2003", f"watchdog: this FOR loop never ends: its variable wraps around "
                    f"at the limit of its type ({a} {step} gives {b}, range {self.lo}.."
                    f"{self.hi}), so it never passes the end value {self.e}; use a wider type for "
                    "the variable", self.where)


def _fend(r) -> int:
    """The FOR variable's value after the loop ended normally: one step past the last pass."""
    if type(r) is range:
        return r.start + len(r) * r.step
    return r.final


def _case_range(x: int, table: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]],
                default: int) -> int:
    """The branch of a large CASE whose label range holds ``x`` (table: sorted disjoint
    starts, ends, branches), or ``default``."""
    starts, ends, branches = table
    i = bisect.bisect_right(starts, x) - 1
    return branches[i] if i >= 0 and x <= ends[i] else default


def _assert_cmp(a, b, want_equal: bool, where: int, kind: str) -> None:
    equal = a == b
    if equal != want_equal:
        rel = "==" if not want_equal else "<>"
        raise AssertFailure(f"expected {'' if want_equal else 'not '}equal, but "
                            f"{format_value(a, kind)} {rel} {format_value(b, kind)}", where)


def _assert_bool(a, want: bool, where: int) -> None:
    if bool(a) != want:
        raise AssertFailure(f"expected {'TRUE' if want else 'FALSE'}, got "
                            f"{'TRUE' if a else 'FALSE'}", where)


def _assert_near(a, b, tol, where: int) -> None:
    if not abs(a - b) <= tol:
        raise AssertFailure(f"expected {b} +- {tol}, got {a} (off by {abs(a - b):.6g})", where)
