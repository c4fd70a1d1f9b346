"""The Gradescope side of an autograder bundle: grade ``ROOT/submission`` into
``ROOT/results/results.json``.

``run_autograder`` (written by :mod:`plclab.grade.bundle`) runs ``python3 -m
plclab.grade.autograder LAB_DIR``. ROOT is ``$PLCLAB_AUTOGRADER_ROOT`` (default
``/autograder``, Gradescope's tree), so a test can run it in a fake tree. The submission is
graded with every scenario of the bundled lab, hidden ones included, in a child process with the
lab's limits (:meth:`~plclab.grade.grader.Grader.grade_one`); the student sees the concept tier
of the hints only and just passed/failed for hidden scenarios.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

ROOT_ENV = "PLCLAB_AUTOGRADER_ROOT"
DEFAULT_ROOT = "/autograder"


def autograder_root() -> Path:
    """``$PLCLAB_AUTOGRADER_ROOT`` or ``/autograder``."""
    return Path(os.environ.get(ROOT_ENV) or DEFAULT_ROOT)


def run(lab_dir: str | os.PathLike, root: Path | None = None) -> Path:
    """Grade ``root/submission`` against the lab in *lab_dir*; returns the results.json path."""
    from plclab.errors import PlcError

    from .engine import failed_result, read_submission
    from .errors import grade_error
    from .grader import Grader
    from .gradescope import results_json, write_json
    from .lab import load_lab

    root = root or autograder_root()
    sub = root / "submission"
    if not sub.is_dir():
        raise grade_error("PLC5058", f"{sub}: no such folder; run_autograder grades "
                          f"${ROOT_ENV}/submission (Gradescope: /autograder/submission)")
    lab = load_lab(lab_dir, deep=True)
    out = root / "results" / "results.json"
    try:
        sources, _ = read_submission(sub)
    except PlcError as e:  # links, sizes, special files: a results.json that says why
        res = failed_result(lab, "rejected", f"This submission was not graded: {e.message} "
                            f"({e.code}). Nothing of it was run; fix it and submit again.",
                            lab.scenarios)
    else:
        with tempfile.TemporaryDirectory(prefix="plclab-autograder-") as work:
            res = Grader(lab, work, jobs=1, media=False).grade_one(sources).result
    write_json(out, results_json(res))
    return out


def main(argv: list[str] | None = None) -> int:
    """``python -m plclab.grade.autograder LAB_DIR``."""
    from plclab.errors import PlcError

    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print("usage: python -m plclab.grade.autograder LAB_DIR", file=sys.stderr)
        return 2
    try:
        path = run(args[0])
    except PlcError as e:
        print(e, file=sys.stderr)
        return 1
    print(f"results: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
