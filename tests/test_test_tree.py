"""The test tree mirrors the package tree, and the folder markers point at real tests."""

import importlib.util
from pathlib import Path

TESTS = Path(__file__).resolve().parent
_spec = importlib.util.spec_from_file_location("tests_conftest", TESTS / "conftest.py")
conftest = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(conftest)
ROOT = TESTS.parent
# folders that test the project as a whole rather than one package
CROSS_CUTTING = {"fuzz", "security", "snapshots", "st", "cli", "notebooks", "corpus",
                 "schema", "i18n"}


def test_every_test_folder_mirrors_a_package_or_is_cross_cutting():
    packages = {p.name for p in (ROOT / "plclab").iterdir() if (p / "__init__.py").exists()}
    packages |= {"plants"}
    folders = {p.name for p in TESTS.iterdir() if p.is_dir() and not p.name.startswith(("_", "."))}
    assert folders - packages - CROSS_CUTTING == set()


def test_every_folder_marker_names_an_existing_test_path():
    for prefix in conftest.FOLDER_MARKERS:
        assert (TESTS / prefix).exists(), prefix
