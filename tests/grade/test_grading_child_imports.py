"""A grading child imports nothing the forkserver did not preload: a module imported in the
child is compiled again in every child (ADR 0033)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = r"""
import json, sys, tempfile
from pathlib import Path
from plclab.grade.worker import lab_from_payload, lab_payload, preload
from plclab.grade.lab import load_lab
lab = lab_from_payload(*lab_payload(load_lab("tank-two-position")))  # as a child gets it
preload()
before = set(sys.modules)
from plclab.grade.engine import grade_sources
src = Path("labs/tank-two-position/mistakes/follows_ls1.st")
media = Path(tempfile.mkdtemp())
res = grade_sources(lab, [(src.read_text(), src.name)], media_dir=media)
drawn = sorted(p.suffix for p in media.iterdir())
new = sorted(set(sys.modules) - before)
print(json.dumps({"new": new, "drawn": drawn, "score": res.score}))
"""


def test_grading_a_failing_tank_submission_imports_nothing_new():
    out = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                         cwd=ROOT, timeout=300, check=True)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert ".png" in got["drawn"] and ".rrd" in got["drawn"]  # the media were drawn
    assert got["new"] == []
