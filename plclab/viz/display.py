"""Is there a screen to open the rerun viewer on? Without one, say how to look at the file."""

from __future__ import annotations

import os
import sys

from ..errors import PlcError


def display_available(environ: dict[str, str] | None = None, platform: str | None = None
                      ) -> bool:
    """True on Windows and macOS, and on Linux/BSD when ``DISPLAY`` or ``WAYLAND_DISPLAY``
    is set (an SSH session, a container or CI has neither)."""
    env = os.environ if environ is None else environ
    plat = sys.platform if platform is None else platform
    if plat.startswith(("win", "darwin")):
        return True
    return bool(env.get("DISPLAY") or env.get("WAYLAND_DISPLAY"))


def require_display(what: str = "the recording") -> None:
    """PLC5053 at once when the viewer could not open a window (instead of waiting for a
    viewer that never shows), with the command that writes a file instead."""
    if not display_available():
        raise PlcError("PLC5053", f"there is no display to open the rerun viewer on (neither "
                       f"DISPLAY nor WAYLAND_DISPLAY is set): write {what} to a file with "
                       "--rrd run.rrd (or a picture with --png run.png) and open it where there "
                       "is a screen: rerun run.rrd")
