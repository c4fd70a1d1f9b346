"""Test-suite set-up: the fuzz, security and render-check helpers (``tests/fuzz``,
``tests/security``, ``tests/viz/render_checks.py``) are
plain modules, importable by name from their tests (``import harness``, ``import payloads``)."""

import os
import sys
from pathlib import Path

import pytest

# The suite asserts English messages: a developer's Russian locale must not change them
# (tests/i18n chooses its languages itself). Subprocesses inherit it.
os.environ["PLCLAB_LANG"] = "en"

_HERE = Path(__file__).resolve().parent
for _folder in ("fuzz", "security", "viz"):
    if str(_HERE / _folder) not in sys.path:
        sys.path.insert(0, str(_HERE / _folder))


# Markers by folder: `pytest -m "not slow"` is the quick run while editing; the optional-part
# markers say which extra a test needs (`pytest -m "not modbus"` on a machine without it).
# Registered in pyproject.toml; a test may carry more with @pytest.mark.
FOLDER_MARKERS = {
    "fuzz": ("slow",),
    "notebooks": ("slow", "notebooks"),
    "modbus": ("slow", "modbus"),
    "opcua": ("slow",),
    "grade": ("slow",),
    "runtime/control": ("control",),
    "security/test_escape_cli.py": ("slow",),
    "sim/test_sim_closed_loops.py": ("slow",),
    "plants/test_plants_conveyor.py": ("physics",),
    "viz/test_viz_trace.py": ("rerun",),
    "site/test_site_browser.py": ("slow",),
    "site/test_site_pyodide.py": ("slow",),
}


def pytest_collection_modifyitems(config, items):
    import pytest

    for item in items:
        rel = Path(str(item.path)).resolve().relative_to(_HERE).as_posix()
        for prefix, marks in FOLDER_MARKERS.items():
            if rel == prefix or rel.startswith(prefix.rstrip("/") + "/"):
                for mark in marks:
                    item.add_marker(getattr(pytest.mark, mark))


@pytest.fixture(autouse=True)
def _fresh_compile_cache():
    """Each test compiles its programs afresh: the memory cache of ``compile_sources`` (ADR
    0057) must not hand a test what another test compiled under other monkeypatches."""
    from plclab.project import COMPILED

    COMPILED.clear()
    yield


def pytest_configure(config):
    """The compile cache (ADR 0057) of this run and of every command it starts lives in a
    folder of its own under the system's temporary folder, removed at the end: a test run
    leaves nothing in the home folder or the repository. A test of the cache itself sets
    ``PLCLAB_CACHE_DIR`` to its ``tmp_path``."""
    import os
    import tempfile

    folder = tempfile.mkdtemp(prefix="plclab-test-cache-")
    os.environ["PLCLAB_CACHE_DIR"] = folder
    config._plclab_cache_dir = folder


def pytest_unconfigure(config):
    import shutil

    folder = getattr(config, "_plclab_cache_dir", None)
    if folder:
        shutil.rmtree(folder, ignore_errors=True)
