"""``plclab grade-bundle LAB -o autograder.zip``: a Gradescope autograder zip.

The zip holds ``setup.sh`` (installs plclab from the wheel inside, ``pip wheel . --no-deps`` of
this checkout, so plclab itself needs no package index), ``run_autograder`` (grades
``/autograder/submission`` into ``/autograder/results/results.json`` with
``python -m plclab.grade.autograder``), the wheel in ``wheels/`` and the whole lab in
``labs/LAB/`` — hidden scenarios included, so the bundle is for instructors only. Gradescope
unpacks the zip into ``/autograder/source``. See docs/adr/0020-gradescope-bundle.md.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import tomllib
import zipfile
from pathlib import Path

from .errors import grade_error

SETUP_SH = """\
#!/usr/bin/env bash
# Gradescope runs this once when it builds the autograder image.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PY="${PLCLAB_PYTHON:-python3}"
# plclab from the wheel in this zip; its [sim] extras (numpy, pymunk, ...) from the index, or
# from wheels/ if you put them there (pip download plclab[sim] -d wheels) for an offline image
"$PY" -m pip install --find-links "$HERE/wheels" "$(ls "$HERE"/wheels/plclab-*.whl)[sim]"
"""

RUN_AUTOGRADER = """\
#!/usr/bin/env bash
# Gradescope runs this for every submission: /autograder/submission -> results/results.json
set -euo pipefail
ROOT="${{PLCLAB_AUTOGRADER_ROOT:-/autograder}}"
PY="${{PLCLAB_PYTHON:-python3}}"
export PLCLAB_AUTOGRADER_ROOT="$ROOT"
exec "$PY" -m plclab.grade.autograder "$ROOT/source/labs/{lab_id}"
"""


def checkout_root() -> Path:
    """The source checkout this plclab runs from (the folder with pyproject.toml)."""
    root = Path(__file__).resolve().parents[2]
    if not (root / "pyproject.toml").is_file():
        raise grade_error("PLC5057", f"{root}: not a source checkout of plclab (no "
                          "pyproject.toml); run from a checkout or give --wheel FILE")
    return root


def build_wheel(dest: Path) -> Path:
    """``pip wheel CHECKOUT --no-deps -w dest``; the wheel's path."""
    root = checkout_root()
    proc = subprocess.run([sys.executable, "-m", "pip", "wheel", str(root), "--no-deps",
                           "-q", "-w", str(dest)],
                          capture_output=True, text=True, check=False)
    wheels = sorted(dest.glob("plclab-*.whl"))
    if proc.returncode or not wheels:
        tail = (proc.stderr or proc.stdout).strip().splitlines()[-15:]
        raise grade_error("PLC5057", "pip wheel . --no-deps failed:\n" + "\n".join(tail))
    return wheels[-1]


def lab_files(lab_path: Path) -> list[tuple[Path, str]]:
    """(file, name in the zip) of the lab folder and of a wiring file outside it."""
    parent = lab_path.parent
    out = [(f, f"labs/{f.relative_to(parent).as_posix()}") for f in sorted(lab_path.rglob("*"))
           if f.is_file() and "__pycache__" not in f.parts
           and f.relative_to(lab_path).parts[0] != "solution"]  # not needed to grade
    data = tomllib.loads((lab_path / "lab.toml").read_text(encoding="utf-8-sig"))
    wiring = data.get("wiring")
    if isinstance(wiring, str):
        f = (lab_path / wiring).resolve()
        try:
            rel = f.relative_to(parent.resolve())
        except ValueError:
            raise grade_error("PLC5056", f"wiring = {wiring!r}: the bundle carries files of "
                              f"the lab's parent folder only ({parent})") from None
        if not str(rel).startswith(lab_path.name + os.sep):
            out.append((f, f"labs/{rel.as_posix()}"))
    return out


def build_bundle(lab_id: str, out: str | os.PathLike, extra_labs: list[str] | None = None,
                 wheel: str | os.PathLike | None = None) -> Path:
    """Write the autograder zip of *lab_id* to *out* (see the module docstring)."""
    from .lab import load_lab, require_hidden

    out = Path(out)
    if out.suffix != ".zip" or out.is_dir():
        raise grade_error("PLC5056", f"-o {out}: give a file name ending in .zip, e.g. "
                          f"-o {lab_id}-autograder.zip")
    lab = load_lab(lab_id, extra_labs or [], deep=True)  # a broken lab fails here, not later
    require_hidden(lab, use="grade-bundle")
    with tempfile.TemporaryDirectory(prefix="plclab-bundle-") as tmp:
        whl = Path(wheel) if wheel else build_wheel(Path(tmp))
        if not whl.is_file() or not whl.name.startswith("plclab-") or whl.suffix != ".whl":
            raise grade_error("PLC5057", f"--wheel {whl}: not a plclab-*.whl file")
        part = out.with_name(f".{out.name}.{os.getpid()}.tmp")
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
            with zipfile.ZipFile(part, "w", zipfile.ZIP_DEFLATED) as z:
                for name, text in (("setup.sh", SETUP_SH),
                                   ("run_autograder", RUN_AUTOGRADER.format(lab_id=lab.path.name))):
                    info = zipfile.ZipInfo(name)
                    info.external_attr = 0o100755 << 16
                    info.compress_type = zipfile.ZIP_DEFLATED
                    z.writestr(info, text)
                z.write(whl, f"wheels/{whl.name}")
                for f, name in lab_files(lab.path):
                    z.write(f, name)
            os.replace(part, out)
        except OSError as e:
            part.unlink(missing_ok=True)
            raise grade_error("PLC5056", f"-o {out}: cannot be written ({e})") from None
    return out
