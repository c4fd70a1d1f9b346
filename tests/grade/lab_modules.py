"""A lab's own Python checks (``labs/LAB/checks.py``), loaded for the tests of those checks."""

import importlib.util
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def lab_checks(lab_id: str) -> ModuleType:
    """The module ``labs/<lab_id>/checks.py``, loaded from its file (it is not a package)."""
    path = ROOT / "labs" / lab_id / "checks.py"
    spec = importlib.util.spec_from_file_location(f"checks_{lab_id.replace('-', '_')}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
