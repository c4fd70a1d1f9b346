"""Fuzzing every language and the runtime: generated valid programs and mutated repository
files go through parse, check, compile and a few scans with random inputs; only PlcErrors
(diagnostics, run-time faults) may come out, never another exception or a hang.

The bounded run is deterministic (fixed seed, fixed number of cases, about a minute).
``PLCLAB_FUZZ_SECONDS=900`` makes it a long, time-bounded run (``PLCLAB_FUZZ_SEED`` changes
the seed); ``python tests/fuzz/run_long.py`` does the same outside pytest.
"""

from __future__ import annotations

import os
import random
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent


import gen  # noqa: E402
import harness  # noqa: E402
import known_issues  # noqa: E402
import worker  # noqa: E402

SEED = int(os.environ.get("PLCLAB_FUZZ_SEED", "20261"))
SECONDS = float(os.environ.get("PLCLAB_FUZZ_SECONDS", "0") or 0)
CASES = int(os.environ.get("PLCLAB_FUZZ_CASES", "1500"))


@pytest.fixture(scope="module")
def campaign():
    stats = harness.campaign(SEED, n_cases=None if SECONDS else CASES,
                             seconds=SECONDS or None, minimise_budget=150,
                             skip=lambda sig: known_issues.match(sig) is not None)
    print("\n" + stats.report())
    return stats


def test_campaign_covers_every_language(campaign):
    for lang in ("st", "il", "ld", "xml"):
        assert campaign.cases[(lang, "gen")] > 0 and campaign.cases[(lang, "mut")] > 0, lang
        assert campaign.outcomes[(lang, "ok")] > 0, f"no {lang} case compiled and scanned"


def test_campaign_finds_no_new_failure(campaign):
    """Every crash or hang found is a known issue (tests/fuzz/known_issues.py)."""
    new = [f for f in campaign.failures.values() if known_issues.match(f.sig) is None]
    assert not new, "\n" + campaign.report()


@pytest.mark.xfail(bool(known_issues.KNOWN), strict=False, reason="open known issues")
def test_campaign_finds_no_failure_at_all(campaign):
    assert not campaign.failures, "\n" + campaign.report()


@pytest.mark.parametrize("lang", list(gen.GENERATORS))
def test_generated_programs_are_valid(lang):
    """The generators write programs the checker accepts (else the fuzzer only tests errors)."""
    from plclab.project import check_sources

    bad = []
    for seed in range(25):
        text, name = gen.GENERATORS[lang](random.Random(seed))
        project, diags = check_sources([(text, name)])
        if project is None:
            bad.append(next(str(d) for d in diags if d.severity == "error"))
    assert len(bad) <= 1, bad


def test_mutations_are_deterministic_and_change_the_text():
    text = (HERE.parents[1] / "examples" / "tank_level.st").read_text()
    a = [harness.mutate(text, random.Random(s)) for s in range(30)]
    b = [harness.mutate(text, random.Random(s)) for s in range(30)]
    assert a == b
    assert sum(m != text for m in a) >= 28


def test_the_minimiser_keeps_the_failure_and_drops_the_rest():
    items = list("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM")

    def fails(pieces):
        s = "".join(pieces)
        return "VAR" in s and ":=" in s

    small = "".join(harness._ddmin(items, fails, [10_000]))
    assert fails(list(small)) and len(small) == len("VAR:=")


def test_the_oracle_calls_a_python_exception_a_crash(monkeypatch):
    import plclab.project

    def boom(sources):
        raise KeyError("oops")

    monkeypatch.setattr(plclab.project, "check_sources", boom)
    res = worker.run_case("PROGRAM P END_PROGRAM", "p.st", 0, 1)
    assert res["outcome"] == "crash" and res["sig"].startswith("crash:check:KeyError")


def test_the_oracle_accepts_diagnostics_and_faults():
    assert worker.run_case("PROGRAM P VAR x : INT; END_VAR x := ; END_PROGRAM", "p.st", 0,
                           1)["outcome"] == "rejected"
    res = worker.run_case("PROGRAM P VAR x, y : INT; END_VAR x := 1 / y; END_PROGRAM", "p.st",
                          0, 2)
    assert res["outcome"] == "ok"


def test_the_runner_reports_a_worker_that_never_answers():
    """A case stuck in C code does not answer even the alarm: the worker is killed, the case
    is a hang, and the next case gets a fresh worker."""
    stuck = [sys.executable, "-c", "import time; time.sleep(60)"]
    with harness.Runner(soft_timeout=0.2, hard_margin=0.5, argv=stuck) as r:
        res = r.run("PROGRAM P END_PROGRAM", "p.st")
        assert res["outcome"] == "hang" and r.proc is None
        r.argv, r.soft, r.hard = harness.Runner().argv, 5.0, 10.0
        assert r.run("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM",
                     "p.st")["outcome"] == "ok"


def _known_params():
    return [pytest.param(k, id=k.id, marks=pytest.mark.xfail(
        strict=False, reason=f"{k.area}: {k.reason}")) for k in known_issues.KNOWN] + [
        pytest.param(k, id=f"fixed-{k.id}") for k in known_issues.FIXED]


@pytest.mark.parametrize("k", _known_params())
def test_known_issue_reproducer(k):
    """Each reproducer must only give diagnostics or PlcErrors; passes once the fix lands."""
    with harness.Runner(soft_timeout=5.0) as r:
        res = r.run(k.text, k.name)
    assert res["outcome"] not in ("crash", "hang"), f"{res['sig']}: {res.get('msg', '')}"
