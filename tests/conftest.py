"""Test-suite set-up: the fuzz and security helpers (``tests/fuzz``, ``tests/security``) are
plain modules, importable by name from their tests (``import harness``, ``import payloads``)."""

import sys
from pathlib import Path

_HERE = Path(__file__).resolve().parent
for _folder in ("fuzz", "security"):
    if str(_HERE / _folder) not in sys.path:
        sys.path.insert(0, str(_HERE / _folder))
