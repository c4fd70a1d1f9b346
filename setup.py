"""Builds plclab with its courseware: the student copy of labs/, examples/ and notebooks/ goes
into the wheel as plclab/courseware/ (docs/adr/0019-installable-labs.md). Everything else is
in pyproject.toml."""

import importlib.util
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent


def _courseware_module():
    spec = importlib.util.spec_from_file_location(
        "plclab_courseware_build", ROOT / "plclab" / "grade" / "courseware.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class BuildWithCourseware(build_py):
    """``build_py``, then the student copy of the courseware into the built package."""

    def run(self):
        super().run()
        if not self.editable_mode:  # an editable install reads the repository's own folders
            _courseware_module().copy_courseware(ROOT, Path(self.build_lib) / "plclab" /
                                                 "courseware")


setup(cmdclass={"build_py": BuildWithCourseware})
