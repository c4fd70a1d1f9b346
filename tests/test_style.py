"""The code base stays ruff-clean (ruff is part of the [test] extra)."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_clean():
    ruff = shutil.which("ruff")
    cmd = [ruff] if ruff else [sys.executable, "-m", "ruff"]
    try:
        r = subprocess.run(cmd + ["check", "--output-format", "concise", "."], cwd=ROOT,
                           capture_output=True, text=True, timeout=120)
    except FileNotFoundError:
        pytest.skip("ruff is not installed (pip install -e '.[test]')")
    assert r.returncode == 0, r.stdout + r.stderr


def test_import_plclab_is_light():
    code = ("import sys, plclab; heavy = {'numpy', 'pymunk', 'pymodbus', 'rerun', 'control', "
            "'matplotlib', 'filterpy'} & set(sys.modules); print(sorted(heavy))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.stdout.strip() == "[]", r.stdout + r.stderr


def test_core_imports_only_the_standard_library():
    """plclab.lang, plclab.compile and plclab.runtime stay pure Python (DESIGN.md)."""
    code = ("import sys; before = set(sys.modules); import plclab; "
            "plc = plclab.loads('PROGRAM P VAR t : TON; END_VAR t(IN := TRUE, PT := T#1s); "
            "END_PROGRAM'); plc.run(seconds=1); "
            "new = {m.split('.')[0] for m in set(sys.modules) - before}; "
            "print(sorted(m for m in new if m not in sys.stdlib_module_names and m != 'plclab'))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.stdout.strip() == "[]", r.stdout + r.stderr
