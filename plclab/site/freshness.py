"""Whether a built site is still up to date, and its pre-compressed assets.

A build records a fingerprint of everything it is made from (the course, the labs, the
notebooks, the docs it shows, the site's own sources, plants and plclab itself) and of its
options in its marker file; ``plclab site serve`` serves a site whose fingerprint still
matches without building it again (60-90 s saved), and ``--rebuild`` forces a build.

After a build every text asset and the playground's WebAssembly get a ``.gz`` copy beside
them, which the server sends to a browser that accepts gzip (the 10 MB wasm travels as 3 MB).
"""

from __future__ import annotations

import gzip
import hashlib
import json
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[2]
INPUTS = ("course", "labs", "notebooks", "docs", "site", "plants", "plclab", "README.md",
          "pyproject.toml")
"""What a site is built from, relative to the repository."""
SKIP_DIRS = {"__pycache__", ".ipynb_checkpoints", "node_modules", ".git"}
COMPRESSIBLE = {".html", ".css", ".js", ".mjs", ".json", ".svg", ".wasm", ".txt", ".xml",
                ".py", ".map", ".zip"}
MIN_COMPRESS = 1024


def fingerprint(options: dict[str, Any], root: Path = REPO,
                inputs: tuple[str, ...] = INPUTS) -> str:
    """A hash of every input file's path and content, and of the build options.

    >>> import tempfile; d = Path(tempfile.mkdtemp()); _ = (d / "a.md").write_text("x")
    >>> fingerprint({}, d, ("a.md",)) == fingerprint({}, d, ("a.md",))
    True
    >>> fingerprint({}, d, ("a.md",)) == fingerprint({"figures": False}, d, ("a.md",))
    False
    """
    h = hashlib.sha256(json.dumps(options, sort_keys=True).encode())
    for name in inputs:
        top = root / name
        files = [top] if top.is_file() else sorted(
            p for p in top.rglob("*") if p.is_file() and not SKIP_DIRS & set(p.parts))
        for f in files:
            h.update(f.relative_to(root).as_posix().encode() + b"\0")
            h.update(hashlib.sha256(f.read_bytes()).digest())
    return h.hexdigest()


def recorded(marker: Path) -> str | None:
    """The fingerprint a built site's marker file records (None: none, or an older marker)."""
    try:
        return json.loads(marker.read_text("utf-8")).get("fingerprint")
    except (OSError, ValueError, AttributeError):
        return None


def record(marker: Path, print_: str) -> None:
    marker.write_text(json.dumps({"built_by": "plclab site build", "fingerprint": print_}),
                      "utf-8")


def precompress(out: Path) -> int:
    """Write ``NAME.gz`` beside every compressible file of at least 1 KB that gzip makes
    smaller; returns how many were written."""
    n = 0
    for f in sorted(out.rglob("*")):
        if not f.is_file() or f.suffix not in COMPRESSIBLE or f.stat().st_size < MIN_COMPRESS:
            continue
        data = f.read_bytes()
        packed = gzip.compress(data, compresslevel=9, mtime=0)
        if len(packed) < len(data) * 0.9:
            f.with_name(f.name + ".gz").write_bytes(packed)
            n += 1
    return n
