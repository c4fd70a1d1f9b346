"""Test-suite set-up: the fuzz, security and render-check helpers (``tests/fuzz``,
``tests/security``, ``tests/viz/render_checks.py``) are
plain modules, importable by name from their tests (``import harness``, ``import payloads``)."""

import os
import sys
from pathlib import Path

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
