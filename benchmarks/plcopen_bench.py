"""PLCopen XML import speed: seconds to import (and to load: import, check, compile) projects of
1k, 2k, 4k, 8k and 16k elements, side by side. A linear importer doubles its time when the size
doubles: the ``x prev`` columns stay near 2 (a quadratic one shows 4).

    python benchmarks/plcopen_bench.py            # all sizes
    python benchmarks/plcopen_bench.py --quick    # 1k..4k

Shapes (an element is one graphical element or one declared variable):

* ``rungs``: an LD body of rungs ``a AND NOT b -> c`` (the shape of an exported ladder program);
* ``series``: one LD rung of contacts in series (a worst case for recursion);
* ``fbd``: an FBD body of independent ``ADD`` networks (inVariable, inVariable, block, outVariable).

This is a measurement, not a test: the numbers depend on the machine.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import plclab  # noqa: E402
from plclab.lang.frontends.plcopen import parse_plcopen_collect  # noqa: E402

HEAD = ('<?xml version="1.0" encoding="utf-8"?>\n'
        '<project xmlns="http://www.plcopen.org/xml/tc6_0201">\n<types><dataTypes/><pous>\n')
RAIL = ('<leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/>'
        '</leftPowerRail>')


def _pou(variables: list[str], lang: str, body: list[str]) -> str:
    return (HEAD + '<pou name="P" pouType="program"><interface><localVars>\n' +
            "\n".join(variables) + f"\n</localVars></interface><body><{lang}>\n" +
            "\n".join(body) + f"\n</{lang}></body></pou>\n</pous></types></project>\n")


def _var(name: str, ty: str = "BOOL") -> str:
    return f'<variable name="{name}"><type><{ty}/></type></variable>'


def _in(ref: int) -> str:
    return f'<connectionPointIn><connection refLocalId="{ref}"/></connectionPointIn>'


def rungs(n: int) -> str:
    """About ``n`` elements: n/6 rungs of two contacts and a coil, three variables each."""
    k = max(1, n // 6)
    variables = [_var(f"{p}{i}") for i in range(k) for p in "abc"]
    body = [RAIL]
    for i in range(k):
        lid, y = 2 + 3 * i, 40 * i
        body += [f'<contact localId="{lid}"><position x="50" y="{y}"/>{_in(1)}'
                 f'<connectionPointOut/><variable>a{i}</variable></contact>',
                 f'<contact localId="{lid + 1}" negated="true"><position x="100" y="{y}"/>'
                 f'{_in(lid)}<connectionPointOut/><variable>b{i}</variable></contact>',
                 f'<coil localId="{lid + 2}"><position x="200" y="{y}"/>{_in(lid + 1)}'
                 f'<connectionPointOut/><variable>c{i}</variable></coil>']
    return _pou(variables, "LD", body)


def series(n: int) -> str:
    """About ``n`` elements: one rung of n/2 contacts in series driving one coil."""
    k = max(1, n // 2)
    variables = [_var(f"a{i}") for i in range(k)] + [_var("q")]
    body = [RAIL]
    for i in range(k):
        body.append(f'<contact localId="{i + 2}"><position x="{10 * i}" y="0"/>{_in(i + 1)}'
                    f'<connectionPointOut/><variable>a{i}</variable></contact>')
    body.append(f'<coil localId="{k + 2}"><position x="{10 * k}" y="0"/>{_in(k + 1)}'
                '<connectionPointOut/><variable>q</variable></coil>')
    return _pou(variables, "LD", body)


def fbd(n: int) -> str:
    """About ``n`` elements: n/7 networks ``c := a + b`` (four boxes, three variables)."""
    k = max(1, n // 7)
    variables = [_var(f"{p}{i}", "INT") for i in range(k) for p in "abc"]
    body = []
    for i in range(k):
        lid, y = 1 + 4 * i, 60 * i
        body += [f'<inVariable localId="{lid}"><position x="0" y="{y}"/><connectionPointOut/>'
                 f'<expression>a{i}</expression></inVariable>',
                 f'<inVariable localId="{lid + 1}"><position x="0" y="{y + 20}"/>'
                 f'<connectionPointOut/><expression>b{i}</expression></inVariable>',
                 f'<block localId="{lid + 2}" typeName="ADD"><position x="50" y="{y}"/>'
                 f'<inputVariables><variable formalParameter="IN1">{_in(lid)}</variable>'
                 f'<variable formalParameter="IN2">{_in(lid + 1)}</variable></inputVariables>'
                 '<inOutVariables/><outputVariables><variable formalParameter="OUT">'
                 '<connectionPointOut/></variable></outputVariables></block>',
                 f'<outVariable localId="{lid + 3}"><position x="100" y="{y}"/>{_in(lid + 2)}'
                 f'<expression>c{i}</expression></outVariable>']
    return _pou(variables, "FBD", body)


SHAPES = {"rungs": rungs, "series": series, "fbd": fbd}


def best_of(fn, text: str, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn(text, "bench.xml")
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="only 1k, 2k and 4k elements")
    args = ap.parse_args()
    sizes = [1000, 2000, 4000] if args.quick else [1000, 2000, 4000, 8000, 16000]
    print(f"{'shape':8} {'elements':>8} {'import s':>9} {'x prev':>7} {'load s':>8} {'x prev':>7}")
    for shape, make in SHAPES.items():
        prev: tuple[float, float] | None = None
        for n in sizes:
            text = make(n)
            t_imp = best_of(parse_plcopen_collect, text)
            t_load = best_of(plclab.loads, text, repeat=1)
            r1 = f"{t_imp / prev[0]:.2f}" if prev else ""
            r2 = f"{t_load / prev[1]:.2f}" if prev else ""
            print(f"{shape:8} {n:>8} {t_imp:>9.3f} {r1:>7} {t_load:>8.3f} {r2:>7}", flush=True)
            prev = (t_imp, t_load)


if __name__ == "__main__":
    main()
