"""What ``plclab check`` imports (issue 35: its start-up is part of the student's loop): never a
heavy library, and on a compile-cache hit not even the front end (ADR 0057). Behaviour, not
time: the speed is measured by ``benchmarks/bench_startup.py``."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("numpy", "matplotlib", "pymunk", "rerun", "pymodbus", "asyncio", "PIL", "control",
         "pygls", "multiprocessing", "xml.etree.ElementTree")
PROGRAM = """PROGRAM Main
VAR start AT %IX0.0 : BOOL; lamp AT %QX0.0 : BOOL; t : TON; END_VAR
t(IN := start, PT := T#2s);
lamp := t.Q;
END_PROGRAM
"""
RUN = ("import sys, json\nfrom plclab.cli import main\nrc = main(sys.argv[1:])\n"
       "print('@@' + json.dumps([rc, sorted(sys.modules)]))")


def modules_of_check(tmp_path: Path, *args: str) -> tuple[int, set[str]]:
    env = dict(os.environ, PYTHONPATH=str(ROOT), PLCLAB_CACHE_DIR=str(tmp_path / "cache"))
    env.pop("PLCLAB_NO_CACHE", None)
    out = subprocess.run([sys.executable, "-c", RUN, "check", *args], env=env, cwd=tmp_path,
                         capture_output=True, text=True, check=True).stdout
    rc, mods = json.loads(out.rsplit("@@", 1)[1])
    return rc, set(mods)


def test_check_imports_no_heavy_library_and_a_hit_no_front_end(tmp_path):
    f = tmp_path / "small.st"
    f.write_text(PROGRAM, encoding="utf-8")
    rc, cold = modules_of_check(tmp_path, str(f))
    assert rc == 0
    assert "plclab.lang.frontends.st" in cold  # the harness sees imports: a miss parses
    assert not [m for m in HEAVY if m in cold]
    assert not [m for m in cold if m.startswith(("plclab.sim", "plclab.grade", "plclab.viz",
                                                 "plclab.runtime.plc", "plclab.compile.codegen"))]
    rc, warm = modules_of_check(tmp_path, str(f))
    assert rc == 0
    assert not [m for m in warm if m.startswith(("plclab.lang.frontends", "plclab.lang.check",
                                                 "plclab.project"))]
    assert not [m for m in HEAVY if m in warm]
    rc, again = modules_of_check(tmp_path, "--no-cache", str(f))  # the switch is honoured
    assert rc == 0 and "plclab.lang.frontends.st" in again
