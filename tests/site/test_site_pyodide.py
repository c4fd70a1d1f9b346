"""The core runs in Pyodide: node loads the npm package, unpacks the zip the site ships,
compiles the tank program and scans it on the tank for 60 s of virtual time."""

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


def test_the_zip_holds_the_core_and_no_heavy_package(tmp_path):
    import zipfile

    names = zipfile.ZipFile(core_zip(tmp_path / "c.zip")).namelist()
    assert "plclab/site/playground_api.py" in names and "plants/tank.py" in names
    assert "plclab/runtime/stdlib.st" in names and "plclab/problems.toml" in names
    assert not any(n.startswith(("plclab/sim/", "plclab/viz/", "plclab/grade/",
                                 "plants/conveyor")) for n in names)
