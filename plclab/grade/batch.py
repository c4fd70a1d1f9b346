"""What ``plclab grade`` needs around the grader: where results go by default, a course
manifest (many labs in one run), an LMS export given as a zip, and the end-of-run summary.

* **Default output: a folder beside the submissions**, ``SUBS-grades`` (``subs/`` ->
  ``subs-grades/``). Not ``./grades``: the current folder is often a checkout (a run left
  files in the repository), while the folder the instructor points at is theirs; beside it,
  not inside, so the results are never taken for a student's submission, and running the same
  command again finds them and resumes. ``--out DIR`` still wins.
* **Manifest** (``--manifest course.toml``)::

      [labs]
      tank-two-position = "submissions/tank"      # relative to the manifest's folder
      motor-start-stop = "submissions/motor"

  Each lab's results go beside its submissions, or to ``OUT/<lab>/`` with ``--out OUT``.
* **LMS exports**: a folder with one folder per student (Moodle) or one file per student
  (Canvas) is graded as it is; a ``.zip`` of either is unpacked (sources only, no links, no
  paths outside, size-capped) into a private temporary folder first.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
import tomllib
import zipfile
from collections import Counter
from pathlib import Path, PurePosixPath
from typing import Any

from .errors import grade_error

ZIP_LIMITS = {"files": 20_000, "bytes": 512 * 2**20, "file": 4 * 2**20}
"""What an LMS zip may hold: entries, unpacked bytes, bytes of one file."""


def default_out(submissions: str | os.PathLike) -> Path:
    """``SUBS-grades`` beside the submissions folder (or beside the zip, without .zip)."""
    p = Path(submissions)
    name = p.stem if p.suffix.lower() == ".zip" else p.name
    return p.parent / f"{name or 'submissions'}-grades"


def read_manifest(path: str | os.PathLike) -> list[tuple[str, Path]]:
    """The (lab, submissions folder) pairs of a course manifest, in its order (PLC5062)."""
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except OSError as e:
        raise grade_error("PLC5062", f"--manifest {p}: cannot read it ({e.strerror or e})"
                          ) from None
    except tomllib.TOMLDecodeError as e:
        raise grade_error("PLC5062", f"--manifest {p}: not TOML ({e})") from None
    labs = data.get("labs")
    if not isinstance(labs, dict) or not labs:
        raise grade_error("PLC5062", f"--manifest {p}: write a [labs] table, one line per "
                          'lab: tank-two-position = "submissions/tank"')
    out = []
    for lab, folder in labs.items():
        if not isinstance(folder, str) or not folder:
            raise grade_error("PLC5062", f"--manifest {p}: {lab} = ... must be the path of a "
                              "submissions folder (a string)")
        out.append((lab, (p.parent / folder)))
    return out


def unpack_zip(zpath: Path, dest: Path) -> Path:
    """Unpack the source files of an LMS zip into ``dest`` (each entry's folders kept, so a
    folder per student stays one) and return the folder holding the submissions: ``dest``, or
    its only top-level folder when the zip wraps everything in one (PLC5063). Every other
    file (a report, a picture) becomes an empty stand-in of the same name, never its bytes, so
    that it gets its gradebook row ("not a program", PLC5071) as in a folder; only what
    archivers and file managers leave (:data:`plclab.grade.grader.JUNK`) is dropped."""
    from .grader import JUNK
    from .lab import SOURCE_EXTS

    try:
        zf = zipfile.ZipFile(zpath)
    except (OSError, zipfile.BadZipFile) as e:
        raise grade_error("PLC5063", f"{zpath}: not a readable zip ({e})") from None
    total = 0
    stand_ins: set[Path] = set()
    with zf:
        infos = zf.infolist()
        if len(infos) > ZIP_LIMITS["files"]:
            raise grade_error("PLC5063", f"{zpath}: {len(infos)} entries (at most "
                              f"{ZIP_LIMITS['files']}); split the export")
        for info in infos:
            name = PurePosixPath(info.filename.replace("\\", "/"))
            mode = info.external_attr >> 16
            if info.is_dir() or stat.S_ISLNK(mode) or JUNK.intersection(name.parts):
                continue  # no links; folders come with their files
            if name.is_absolute() or ".." in name.parts or not name.parts:
                raise grade_error("PLC5063", f"{zpath}: entry {info.filename!r} points outside "
                                  "the zip; it was not unpacked")
            if name.suffix.lower() not in SOURCE_EXTS:
                target = dest.joinpath(*name.parts)
                target.parent.mkdir(parents=True, exist_ok=True)
                target.touch()  # a stand-in: the student's row says what it was
                stand_ins.add(target)
                continue
            if info.file_size > ZIP_LIMITS["file"]:
                raise grade_error("PLC5063", f"{zpath}: {info.filename} has {info.file_size} "
                                  f"bytes (at most {ZIP_LIMITS['file']})")
            total += info.file_size
            if total > ZIP_LIMITS["bytes"]:
                raise grade_error("PLC5063", f"{zpath}: more than {ZIP_LIMITS['bytes']} bytes "
                                  "unpacked; split the export")
            target = dest.joinpath(*name.parts)
            target.parent.mkdir(parents=True, exist_ok=True)
            with zf.open(info) as src, open(target, "wb") as fh:
                shutil.copyfileobj(src, fh, 1 << 16)
    # a wrapper folder is decided on the programs alone, as if the stand-ins were not there
    tops = [p for p in dest.iterdir() if not p.name.startswith(".") and p not in stand_ins]
    if len(tops) == 1 and tops[0].is_dir():
        inner = [c for c in tops[0].iterdir() if c not in stand_ins]
        if any(c.is_dir() or c.suffix.lower() in SOURCE_EXTS for c in inner) and (
                len(inner) > 1 or inner[0].is_dir()):
            for p in dest.iterdir():  # a stray file beside the wrapper still gets its row
                if p in stand_ins and not (tops[0] / p.name).exists():
                    p.rename(tops[0] / p.name)
            return tops[0]
    return dest


class Unpacked:
    """``with Unpacked(path) as folder``: the folder of submissions for a path that may be
    a zip (unpacked into a private temporary folder, removed afterwards)."""

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        self._tmp: str | None = None

    def __enter__(self) -> Path:
        if self.path.suffix.lower() == ".zip" and self.path.is_file():
            self._tmp = tempfile.mkdtemp(prefix="plclab-lms-")
            return unpack_zip(self.path, Path(self._tmp))
        return self.path

    def __exit__(self, *exc: Any) -> None:
        if self._tmp:
            shutil.rmtree(self._tmp, ignore_errors=True)


def histogram(scores: list[float], max_score: float, bins: int = 10, width: int = 30
              ) -> list[str]:
    """A text histogram of scores in ``bins`` equal bins from 0 to ``max_score``.

    >>> histogram([0, 5, 10, 10], 10, bins=2, width=4)
    [' 0-5 |#    1', '5-10 |#### 3']
    """
    if not scores or max_score <= 0:
        return []
    counts = [0] * bins
    for s in scores:
        counts[min(bins - 1, max(0, int(s / max_score * bins)))] += 1
    top = max(counts)
    step = max_score / bins
    labels = [f"{k * step:g}-{(k + 1) * step:g}" for k in range(bins)]
    pad = max(len(x) for x in labels)
    return [f"{lab:>{pad}} |{'#' * round(n / top * width):<{width}} {n}"
            for lab, n in zip(labels, counts, strict=True)]


def run_summary(outcomes: list[Any]) -> str:
    """The end of a run: counts by status (unchanged ones apart) and the score histogram."""
    if not outcomes:
        return "no submissions"
    status = Counter(o.result.status for o in outcomes if not o.skipped)
    skipped = sum(1 for o in outcomes if o.skipped)
    parts = [f"{n} {s}" for s, n in sorted(status.items(), key=lambda kv: (-kv[1], kv[0]))]
    if skipped:
        parts.append(f"{skipped} unchanged")
    mx = outcomes[0].result.max_score
    lines = [f"status: {', '.join(parts)}", f"scores (of {mx:g}):"]
    lines += ["  " + ln for ln in histogram([o.result.score for o in outcomes], mx)]
    return "\n".join(lines)
