"""The core runs in Pyodide: node loads the npm package, unpacks the zip the site ships,
compiles the tank program and scans it on the tank for 60 s of virtual time, then asks the
editor's side what the playground's editor asks: highlighting (Pygments' lexer core travels in
the zip), diagnostics, hover and completion from the language server's feature functions."""

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.site.bundle import core_zip, pyodide_dir

SCRIPT = Path(__file__).resolve().parents[2] / "site" / "playground" / "node_check.mjs"


@pytest.fixture(scope="module")
def pyodide():
    if shutil.which("node") is None:
        pytest.skip("node is not installed (apt-get install nodejs npm): Pyodide cannot run")
    try:
        return pyodide_dir()
    except PlcError as e:
        pytest.skip(f"Pyodide from npm is not available here: {e.message}")


def test_core_compiles_and_scans_the_tank_in_pyodide(pyodide, tmp_path):
    zip_path = core_zip(tmp_path / "plclab-core.zip")
    done = subprocess.run(["node", str(SCRIPT), str(pyodide), str(zip_path)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["ok"] and out["scans"] == 3000
    assert out["pump"][0] is True and out["pump"][-1] is False
    assert out["bad"][0]["code"] == "PLC0010" and out["bad"][0]["line"] == 3
    src = ("PROGRAM P\nVAR t1 : TON; n : INT; END_VAR (* note *)\nt1(IN := TRUE, PT := T#1s);"
           "\nn := ABS(n);\nIF t1.\nEND_PROGRAM\n")
    assert ["".join(v for _, v in line) for line in out["spans"]] == src.split("\n")
    pieces = {v: c for line in out["spans"] for c, v in line}
    assert pieces["(*"] == "cm" and pieces["TON"] == "nb" and pieces["END_VAR"] == "k"
    assert pieces["INT"] == "kt" and "err" not in pieces.values()
    assert [(d["code"], d["line"]) for d in out["lint"]] == [("PLC0010", 6)]
    assert "VAR t1 : TON" in out["hover_var"] and "ABS(IN)" in out["hover_fn"]
    assert {"Q", "ET", "IN", "PT"} <= set(out["members"]) and "n" not in out["members"]


def test_the_zip_holds_the_core_and_no_heavy_package(tmp_path):
    import zipfile

    names = zipfile.ZipFile(core_zip(tmp_path / "c.zip")).namelist()
    assert "plclab/site/playground_api.py" in names and "plants/tank.py" in names
    assert "plclab/runtime/stdlib.st" in names and "plclab/problems.toml" in names
    assert "plclab/viz/highlight.py" in names and "pygments/lexer.py" in names
    assert "plclab/lsp/features.py" in names and "pygments/LICENSE" in names
    assert not any(n.startswith(("plclab/sim/", "plclab/grade/", "plants/conveyor",
                                 "pygments/lexers/", "pygments/formatters/"))
                   for n in names)
    assert [n for n in names if n.startswith("plclab/viz/")] == ["plclab/viz/__init__.py",
                                                               "plclab/viz/highlight.py"]
