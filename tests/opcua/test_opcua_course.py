"""Course chapter 15's OPC UA section tells the truth: its command starts the boiler behind the
server, the browsed program shows the level input, the wire break turns LEVEL_RAW Bad
(BadSensorFailure) while the level switch and the computed level stay Good, and the banner the
text prints is the one the server prints."""

from __future__ import annotations

import re
import shlex

import pytest

pytest.importorskip("asyncua")

from plclab.modbus._testing import PlclabProcess, free_port, wait_until  # noqa: E402

from .test_opcua_clients import ROOT, WAIT, read, tool  # noqa: E402

CHAPTER = ROOT / "course" / "15-scada" / "chapter.md"


def section() -> str:
    text = CHAPTER.read_text(encoding="utf-8")
    start = text.index("## OPC UA: tags with quality")
    return text[start:text.index("\n## ", start + 1)]


def test_the_chapters_command_shows_a_wire_break_as_bad_quality():
    text = section()
    command = re.search(r"^\$ plclab (opcua .*)$", text, re.M).group(1)
    banner = re.search(r"^(OPC UA server on .*)$", text, re.M).group(1)
    node = re.search(r'^\$ uasubscribe .* -n "([^"]+)"', text, re.M).group(1)
    port = free_port()
    # ten times faster than the text's real time: the break at 60 s comes after 6 wall seconds
    p = PlclabProcess([*shlex.split(command), "--port", str(port), "--speed", "10"],
                      port=port, cwd=str(ROOT), timeout=WAIT)
    p.start()
    url = f"opc.tcp://127.0.0.1:{port}"
    try:
        listing = tool("uals", url, "-n", "ns=2;s=PLC:Programs.Boiler").stdout
        assert node in listing and "ns=2;s=Boiler.level" in listing, listing
        assert wait_until(lambda: "BadSensorFailure" in read(url, node, "datavalue"), WAIT)
        for good in ("ns=2;s=Boiler.LEVEL_MIN", "ns=2;s=Boiler.level"):
            assert "StatusCode(value=0)" in read(url, good, "datavalue"), good
    finally:
        p.stop()
    shown = banner.replace("4840", str(port)).replace("speed 1x", "speed 10x")
    assert shown in p.output, p.output
    assert "0x808C0000" in text and 0x808C0000 == 2156658688 and "2156658688" in text
