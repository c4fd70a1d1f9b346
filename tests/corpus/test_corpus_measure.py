"""``benchmarks/corpus_measure.py``: building the corpus out of a git mirror and the rule that
says which files are valid and self-contained (ADR 0060), with files each rule must catch."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")


def _module():
    spec = importlib.util.spec_from_file_location("corpus_measure",
                                                  ROOT / "benchmarks" / "corpus_measure.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["corpus_measure"] = mod
    spec.loader.exec_module(mod)
    return mod


FILES = {
    "AnnexF/good_st.txt": "PROGRAM Good\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n",
    "tests/zz_copy_st.txt": "PROGRAM Good\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n",
    "lib/uses_lib.txt": "PROGRAM U\nVAR b : VendorBlock; END_VAR\nb();\nEND_PROGRAM\n",
    "lib/gap.txt": "PROGRAM G\nVAR t : TIME; END_VAR\nt := NOT_A_STANDARD_FN(1) + TIME_GAP;\n"
                   "END_PROGRAM\n",
    "lib/typo.txt": "PROGRAM T\nVAR x : INT; END_VAR\nx := y + 1;\nx := 1.5;\nEND_PROGRAM\n",
    "lib/external.txt": "{external}\nFUNCTION F : INT\nEND_FUNCTION\n",
    "tests/bad_thing.st": "PROGRAM B\nx := ;\nEND_PROGRAM\n",
    "tests/body_only.st": "x := x + 1;\n",
    "README.md": "not a source",
}


@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    mod = _module()
    mirror = tmp_path_factory.mktemp("m") / "beremiz+matiec" / "repo"
    mirror.mkdir(parents=True)
    for rel, text in FILES.items():
        (mirror / rel).parent.mkdir(parents=True, exist_ok=True)
        (mirror / rel).write_text(text)
    git = ["git", "-C", str(mirror), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(git[:3] + ["init", "-q"], check=True)
    subprocess.run(git + ["add", "."], check=True)
    subprocess.run(git + ["commit", "-qm", "x"], check=True)
    out = tmp_path_factory.mktemp("corpus")
    written = mod.build(out, [mirror])
    outcomes = {o.path.relative_to(out).as_posix(): o for o in mod.measure(out, 2, 120)}
    return mod, out, written, outcomes


def test_build_copies_the_sources_files_once_with_their_origin(measured):
    _mod, out, written, outcomes = measured
    # README.md is not a source; copy_st is good_st's text again
    assert written == 7 and len(outcomes) == 7
    assert (out / "matiec" / "DIALECT").read_text().strip() == "matiec"
    assert (out / "matiec" / "AnnexF" / "good_st.st").exists()  # .txt read as ST
    sources = (out / "SOURCES.txt").read_text()
    assert "github:beremiz/matiec@" in sources and ":AnnexF/good_st.txt" in sources
    assert "zz_copy_st" not in sources


def test_a_valid_program_is_counted_accepted_and_run(measured):
    o = measured[3]["matiec/AnnexF/good_st.st"]
    assert o.excluded == "" and o.native and o.as_is and o.result["run"]["ok"]


@pytest.mark.parametrize("path, reason", [
    ("matiec/lib/uses_lib.st", "needs a missing library: VENDORBLOCK"),
    ("matiec/lib/external.st", "vendor project context"),
    ("matiec/tests/bad_thing.st", "invalid on purpose"),
    ("matiec/tests/body_only.st", "fragment"),
])
def test_each_rule_leaves_out_the_file_it_is_for(measured, path, reason):
    assert measured[3][path].excluded.startswith(reason)


def test_a_rejection_that_is_not_a_missing_name_stays_counted(measured):
    outcomes = measured[3]
    typo = outcomes["matiec/lib/typo.st"]  # an undeclared name beside a type error
    assert not typo.native and typo.excluded == ""
    gap = outcomes["matiec/lib/gap.st"]  # a function and a variable declared nowhere
    assert not gap.native
    assert gap.excluded.startswith("needs project context") and "TIME_GAP" in gap.excluded


def test_a_missing_standard_name_is_plclabs_gap_not_a_missing_library():
    mod = _module()
    o = mod.Outcome(Path("x/a.st"), "x", "matiec")
    o.result = {"native": {"ok": False, "errors": [["PLC0106", "LOWER_BOUND is not a function"]]}}
    assert mod.classify(o, "PROGRAM P END_PROGRAM") == ""
    o.result["native"]["errors"] = [["PLC0106", "FB_Vendor is not a function"]]
    assert mod.classify(o, "PROGRAM P END_PROGRAM").startswith("needs a missing library")
    o.result["native"]["errors"] = [["PLC0106", "FB_Own is not a function"]]
    assert mod.classify(o, "FUNCTION_BLOCK FB_Own END_FUNCTION_BLOCK PROGRAM P END_PROGRAM") == ""
