"""Reading the SCADA configuration files (alarms, recipes, watch tables): TOML, with a clear
error carrying each kind's own code."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from plclab.errors import PlcError


def read_toml(path: str | Path, code: str, what: str) -> dict[str, Any]:
    """The TOML table in ``path``; ``PlcError(code)`` naming ``what`` (e.g. "alarm file")
    when the file cannot be read or is not TOML."""
    import tomllib

    path = Path(path)
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise PlcError(code, f"cannot read {what} {path}: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise PlcError(code, f"{path}: not valid TOML ({e})") from None
