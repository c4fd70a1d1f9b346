"""Labs and the autograder.

Layer ``grade`` (``docs/adr/0013-layers-and-lazy-cli.md``): above the simulator and the viewers
(it runs scenarios and draws the diagrams of failures), below only the CLI.

A lab (``labs/<id>/lab.toml``) joins a plant, a wiring table and an I/O table to scenarios and
criteria with points; :mod:`plclab.grade.criteria` is the library of checks. The autograder
(``plclab grade LAB SUBMISSIONS_DIR``) grades a folder of submissions, one process each, and
writes Gradescope ``results.json``, ``feedback.md`` with timing diagrams and a ``grades.csv``
gradebook. From Python (notebooks)::

    from plclab.grade import check
    r = check("tank-two-position", "tank.st")      # or the program text
    r.score, r.max_score, r.tests                  # r shows itself as Markdown in Jupyter

Nothing heavy is imported with this package; NumPy and friends come with the first grading.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

__all__ = ["Result", "check", "list_labs", "load_lab"]


def __getattr__(name: str) -> Any:
    if name == "Result":
        from .engine import Result

        return Result
    if name in ("load_lab", "list_labs"):
        from . import lab

        return getattr(lab, name)
    raise AttributeError(name)


def _is_text(s: str) -> bool:
    return "\n" in s or ";" in s or s.lstrip().upper().startswith(("PROGRAM", "FUNCTION", "(*",
                                                                   "<?XML"))


def check(lab_id: str | os.PathLike, source_text_or_paths: Any, language: str | None = None,
          *, include_hidden: bool = False, scenarios: Iterable[str] | None = None,
          media_dir: str | os.PathLike | None = None, labs: Iterable[str] = ()) -> Any:
    """Grade a program against a lab in this process and return the
    :class:`~plclab.grade.engine.Result`.

    Parameters
    ----------
    lab_id : str or path
        A lab id (``"tank-two-position"``) or a lab folder.
    source_text_or_paths : str, path or list of them
        Program text, or source files / a submission folder.
    language : {"st", "il", "ld", "xml"}, optional
        The language of program *text* (guessed when not given).
    include_hidden : bool
        Also run the hidden scenarios (instructors).
    scenarios : names, optional
        Only these scenarios.
    media_dir : path, optional
        Write the timing diagrams of failures (and .rrd recordings) there.

    Returns
    -------
    Result
        ``.score``, ``.max_score``, ``.tests``, ``.feedback_markdown``, ``.traces`` (scenario
        name -> Trace).
    """
    from .engine import grade_sources, guess_language, read_submission
    from .errors import grade_error
    from .lab import LANGUAGES, load_lab

    lab = load_lab(lab_id, labs)
    items = source_text_or_paths
    if isinstance(items, str | os.PathLike):
        items = [items]
    sources: list[tuple[str, str]] = []
    for i, it in enumerate(items):
        if isinstance(it, str) and _is_text(it):
            lang = language or guess_language(it)
            if lang not in LANGUAGES:
                raise grade_error("PLC5026", f"language {lang!r}: use st, il, ld or xml")
            sources.append((it, f"<submission{i + 1 if len(items) > 1 else ''}>.{lang}"))
        else:
            p = Path(it)
            if not p.exists():
                raise grade_error("PLC5021", f"{p}: no such file or folder (program text needs "
                                  "a newline or a ';' to be recognised as text)")
            got, _ = read_submission(p)
            sources += got
    return grade_sources(lab, sources, scenarios=scenarios, include_hidden=include_hidden,
                         media_dir=media_dir, keep_traces=True)
