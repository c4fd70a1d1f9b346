"""Run every TEST block of the ST example suites (worked examples of the source texts)."""

from pathlib import Path

import pytest

from plclab.testing import run_test_files

SUITES = sorted((Path(__file__).parent.parent / "st").glob("*.st"))


@pytest.mark.parametrize("path", SUITES, ids=[p.name for p in SUITES])
def test_st_suite(path):
    results = run_test_files([str(path)])
    assert results, f"{path.name} has no TEST blocks"
    failures = [str(r) for r in results if not r.passed]
    assert not failures, "\n".join(failures)


def test_suites_exist():
    assert len(SUITES) >= 8
