"""`plclab view` without a display says how to open the file and exits non-zero at once."""

from __future__ import annotations

import time

from plclab.cli import main
from plclab.viz.display import display_available


def test_display_available_by_platform_and_environment():
    assert not display_available({}, "linux")
    assert display_available({"DISPLAY": ":0"}, "linux")
    assert display_available({"WAYLAND_DISPLAY": "wayland-0"}, "linux")
    assert display_available({}, "darwin") and display_available({}, "win32")


def test_view_without_a_display_exits_quickly_and_says_what_to_do(tmp_path, capsys,
                                                                  monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.setattr("sys.platform", "linux")
    t = time.perf_counter()
    assert main(["view", str(tmp_path / "run.npz")]) == 1
    assert time.perf_counter() - t < 10  # generous: it must not wait for a viewer
    err = capsys.readouterr().err
    assert "PLC5053" in err and "--rrd" in err and "rerun run.rrd" in err
