"""`plclab grade-bundle`: a Gradescope autograder zip whose run_autograder grades a submission
in a (fake) /autograder tree into results/results.json (issue 15)."""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import plclab
from plclab.cli import main
from plclab.grade.gradescope import validate_results
from plclab.grade.lab import load_lab

pytestmark = pytest.mark.slow

LAB = load_lab("motor-start-stop", deep=True)
HIDDEN = {s.name for s in LAB.scenarios if not s.visible}


@pytest.fixture(scope="module")
def bundle(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("bundle") / "motor.zip"
    assert main(["grade-bundle", "motor-start-stop", "-o", str(out)]) == 0
    return out


def autograde(bundle: Path, root: Path, files: dict[str, str]) -> dict:
    """Unpack like Gradescope (zip -> ROOT/source, run_autograder -> ROOT), grade *files*."""
    with zipfile.ZipFile(bundle) as z:
        z.extractall(root / "source")
        mode = z.getinfo("run_autograder").external_attr >> 16
    assert mode & stat.S_IXUSR, "run_autograder is executable in the zip"
    run = root / "run_autograder"
    run.write_bytes((root / "source" / "run_autograder").read_bytes())
    run.chmod(0o755)
    (root / "submission").mkdir()
    for name, text in files.items():
        (root / "submission" / name).write_text(text, encoding="utf-8")
    env = dict(os.environ, PLCLAB_AUTOGRADER_ROOT=str(root), PLCLAB_PYTHON=sys.executable,
               PYTHONPATH=str(Path(plclab.__file__).parents[1]))
    proc = subprocess.run(["bash", str(run)], env=env, capture_output=True, text=True,
                          timeout=600, check=False)
    assert proc.returncode == 0, proc.stderr
    return json.loads((root / "results" / "results.json").read_text(encoding="utf-8"))


def test_the_zip_carries_setup_the_wheel_and_the_hidden_lab(bundle):
    with zipfile.ZipFile(bundle) as z:
        names = set(z.namelist())
        toml = z.read("labs/motor-start-stop/lab.toml").decode("utf-8")
    assert {"setup.sh", "run_autograder", "labs/motor-start-stop/lab.toml"} <= names
    assert any(n.startswith("wheels/plclab-") and n.endswith(".whl") for n in names)
    assert HIDDEN and all(f'name = "{h}"' in toml for h in HIDDEN)
    assert not any("/solution/" in n for n in names)


@pytest.mark.parametrize("mistake, full", [("solution/motor.st", True),
                                           ("mistakes/no_seal_in.ld", False)])
def test_run_autograder_grades_the_submission(bundle, tmp_path, mistake, full):
    src = LAB.path / mistake
    data = autograde(bundle, tmp_path, {src.name: src.read_text(encoding="utf-8")})
    assert validate_results(data) == []
    assert len(data["tests"]) == sum(len(LAB.criteria_for(s.name)) for s in LAB.scenarios)
    assert (data["score"] == LAB.max_score) == full
    hidden = [t for t in data["tests"] if t["tags"][0] in HIDDEN]
    assert hidden and all(t["visibility"] == "after_published" for t in hidden)
    assert all(t["visibility"] == "visible" for t in data["tests"] if t not in hidden)


def test_an_empty_submission_scores_zero_with_a_reason(bundle, tmp_path):
    data = autograde(bundle, tmp_path, {})
    assert data["score"] == 0 and validate_results(data) == []
    assert "no_source" in data["output"] and "PLC5021" in data["output"]


def test_a_missing_submission_folder_is_PLC5058(tmp_path, monkeypatch, capsys):
    from plclab.grade.autograder import main as ag_main

    monkeypatch.setenv("PLCLAB_AUTOGRADER_ROOT", str(tmp_path))
    assert ag_main([str(LAB.path)]) == 1
    assert "PLC5058" in capsys.readouterr().err


def test_a_wiring_file_beside_the_lab_travels_with_it_and_one_further_away_is_PLC5056(tmp_path):
    from plclab.errors import PlcError
    from plclab.grade.bundle import lab_files

    lab = tmp_path / "labs" / "x"
    (tmp_path / "labs" / "shared").mkdir(parents=True)
    lab.mkdir()
    (tmp_path / "labs" / "shared" / "w.toml").write_text('plant = "tank"\n', encoding="utf-8")
    (lab / "solution").mkdir()
    (lab / "solution" / "x.st").write_text("", encoding="utf-8")
    (lab / "lab.toml").write_text('wiring = "../shared/w.toml"\n', encoding="utf-8")
    assert [name for _, name in lab_files(lab)] == ["labs/x/lab.toml", "labs/shared/w.toml"]
    (lab / "lab.toml").write_text('wiring = "../../w.toml"\n', encoding="utf-8")
    with pytest.raises(PlcError) as e:
        lab_files(lab)
    assert e.value.code == "PLC5056"


def test_a_bundle_name_without_zip_is_PLC5056(tmp_path, capsys):
    assert main(["grade-bundle", "motor-start-stop", "-o", str(tmp_path)]) == 1
    assert "PLC5056" in capsys.readouterr().err


def test_a_wheel_that_is_not_plclab_is_PLC5057(tmp_path, capsys):
    bad = tmp_path / "other-1.0-py3-none-any.whl"
    bad.write_bytes(b"")
    assert main(["grade-bundle", "motor-start-stop", "-o", str(tmp_path / "a.zip"),
                 "--wheel", str(bad)]) == 1
    assert "PLC5057" in capsys.readouterr().err
