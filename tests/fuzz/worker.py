"""The fuzz worker: runs one case at a time, read as a JSON line on stdin, answered on stdout.

Started by ``harness.Runner`` as ``python worker.py``. Each case goes through parse, check,
compile and, when it compiles, a few scans with random inputs. A soft hang guard
(``setitimer`` on the process's CPU time, ITIMER_PROF: a loaded machine that gives the worker
little CPU does not make a case a hang) turns a case that runs too long into a ``hang`` answer
with the place it was stuck; the parent kills the worker when even that does not come back
within a wall-clock margin (a hang in C code, or waiting on nothing). The
address space is limited, so a runaway allocation is a ``MemoryError`` here, not a dead machine.

Answer: ``{"outcome": "ok" | "rejected" | "plcerror" | "crash" | "hang", "stage", "sig", "msg"}``
where only ``crash`` and ``hang`` are failures (``rejected`` = diagnostics, ``plcerror`` = a
PlcError raised, both as designed).
"""

from __future__ import annotations

import json
import os
import random
import resource
import signal
import sys
import traceback

MEMORY_LIMIT = 2 * 1024**3
INTERNAL_CODES = ("PLC9999", "PLC9990")  # plclab's own failures: each one is a finding


class Hang(KeyboardInterrupt):
    """Raised by the alarm; a KeyboardInterrupt so that the PLC does not wrap it as a fault."""


def _on_alarm(signum, frame):
    raise Hang()


def _where(tb, function: bool = True) -> str:
    """The innermost frame inside plclab or the generated code (``<plclab>``) of a traceback:
    ``file:function`` (``file`` alone for hangs, whose innermost frame varies)."""
    best = "?"
    for fs in traceback.extract_tb(tb):
        fn = fs.filename.replace(os.sep, "/")
        if "/plclab/" in fn:
            best = fn[fn.rindex("/plclab/") + 1:] + (":" + fs.name if function else "")
        elif fn == "<plclab>":
            best = "generated" + (":" + fs.name if function else "")
    return best


def _random_value(rng: random.Random, current: str) -> str:
    """A random IEC literal of the same kind as ``current`` (a formatted value)."""
    if current in ("TRUE", "FALSE"):
        return rng.choice(["TRUE", "FALSE"])
    if current.startswith(("T#", "TIME#")):
        return rng.choice(["T#0ms", "T#15ms", "T#1s", "T#-3s", "T#24d"])
    if current.startswith("'"):
        return rng.choice(["''", "'abc'", "'$N$$$''"])
    if current.lstrip("-").isdigit():
        return str(rng.choice([0, 1, -1, 7, 255, 32767, -32768, 2**31 - 1, rng.randint(-99, 99)]))
    try:
        float(current)
    except ValueError:
        return current
    return rng.choice(["0.0", "1.5", "-2.5E3", "1.0E30", "3.0"])


def run_case(text: str, name: str, seed: int, scans: int) -> dict:
    from plclab.errors import PlcError
    from plclab.project import check_sources
    from plclab.runtime.plc import Plc

    stage = "check"
    try:
        project, diags = check_sources([(text, name)])
        if project is None:
            return {"outcome": "rejected", "stage": stage,
                    "code": next(d.code for d in diags if d.severity == "error")}
        stage = "compile"
        from plclab.compile.codegen import generate

        compiled = generate(project, "<plclab>")
        stage = "load"
        plc = Plc(compiled, watchdog=20_000)
        stage = "scan"
        rng = random.Random(seed)
        names = plc.variables()
        for _ in range(scans):
            plc.inputs[:] = rng.randbytes(len(plc.inputs))
            for n in rng.sample(names, min(3, len(names))):
                try:
                    plc[n] = _random_value(rng, plc.format(n))
                except PlcError:
                    pass
            try:
                plc.scan()
            except PlcError as fault:  # a run-time fault stops the PLC, as designed
                if fault.code in INTERNAL_CODES:
                    raise
                stage = "restart"
                plc.cold_restart()
                stage = "scan"
        return {"outcome": "ok", "stage": stage}
    except Hang as e:
        where = _where(e.__traceback__, function=False)
        return {"outcome": "hang", "stage": stage, "sig": f"hang:{stage}:{where}", "msg": ""}
    except PlcError as e:
        if e.code in INTERNAL_CODES:  # an internal error dressed as a PlcError is still a bug
            kind = e.message.partition("(")[2].partition(":")[0] or "?"
            return {"outcome": "crash", "stage": stage, "sig": f"crash:{stage}:{e.code}:{kind}",
                    "msg": str(e)[:500]}
        return {"outcome": "plcerror", "stage": stage, "code": e.code}
    except RecursionError as e:
        return {"outcome": "crash", "stage": stage,
                "sig": f"crash:{stage}:RecursionError:{_where(e.__traceback__)}", "msg": ""}
    except BaseException as e:  # noqa: BLE001 - every other exception is the finding
        return {"outcome": "crash", "stage": stage,
                "sig": f"crash:{stage}:{type(e).__name__}:{_where(e.__traceback__)}",
                "msg": f"{type(e).__name__}: {e}"[:500]}


def main() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    signal.signal(signal.SIGPROF, _on_alarm)
    sys.setrecursionlimit(4000)
    out = sys.stdout
    sys.stdout = sys.stderr  # stray prints of the code under test do not break the protocol
    for line in sys.stdin:
        job = json.loads(line)
        signal.setitimer(signal.ITIMER_PROF, job.get("timeout", 3.0))
        try:
            res = run_case(job["text"], job["name"], job.get("seed", 0), job.get("scans", 3))
        except Hang:
            res = {"outcome": "hang", "stage": "?", "sig": "hang:?:?", "msg": ""}
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
        res["id"] = job.get("id")
        out.write(json.dumps(res) + "\n")
        out.flush()


if __name__ == "__main__":
    main()
