"""The build step that puts the student copy of the courseware into the wheel.

``pyproject.toml`` names :class:`BuildWithCourseware` as setuptools' ``build_py`` command
(``[tool.setuptools.cmdclass]``). Setuptools loads this file by its path while building, before
plclab is importable, so it imports only setuptools and loads :mod:`plclab.grade.courseware`
(standard library only) by path too. Never imported at run time
(``docs/adr/0019-installable-labs.md``).
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parents[2]


def _courseware_module():
    spec = importlib.util.spec_from_file_location(
        "plclab_courseware_build", Path(__file__).with_name("courseware.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class BuildWithCourseware(build_py):
    """``build_py``, then the student copy of the courseware into the built package."""

    def run(self):
        super().run()
        if self.editable_mode:  # an editable install reads the repository's own folders
            return
        if not (ROOT / "labs").is_dir():
            raise SystemExit("plclab's courseware (labs/, examples/, notebooks/) is not in this "
                             "source tree: build the wheel from the repository (pip wheel .), "
                             "not from an sdist")
        _courseware_module().copy_courseware(ROOT, Path(self.build_lib) / "plclab" /
                                             "courseware")
