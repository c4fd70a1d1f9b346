"""Installable courseware: the student copy of every lab loads and keeps no private part; a
wheel built from the sources, installed in a fresh venv, lists, copies and checks a lab from a
folder outside the repository (issue 15)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.grade import check
from plclab.grade.courseware import PRIVATE_DIRS, copy_courseware, student_lab_toml
from plclab.grade.lab import get_lab_files, list_labs, load_lab, repo_labs_dir

ROOT = Path(__file__).resolve().parents[2]
OWN_LABS = [p for p in list_labs() if p.parent == repo_labs_dir()]


@pytest.fixture(scope="module")
def student_copy(tmp_path_factory) -> Path:
    dest = tmp_path_factory.mktemp("cw") / "courseware"
    copy_courseware(ROOT, dest)
    return dest


def test_the_student_copy_of_every_lab_loads_without_its_private_part(student_copy):
    assert len(OWN_LABS) >= 8
    for src in OWN_LABS:
        full = load_lab(src)
        folder = student_copy / "labs" / src.name
        lab = load_lab(folder)
        assert not any((folder / d).exists() for d in PRIVATE_DIRS), src.name
        assert [s.name for s in lab.scenarios] == [s.name for s in full.visible_scenarios]
        assert lab.mistakes == []
        text = (folder / "lab.toml").read_text(encoding="utf-8")
        for s in full.scenarios:
            if not s.visible:  # a hidden scenario is not even named
                assert f'"{s.name}"' not in text, (src.name, s.name)
        for c in lab.criteria:  # a visible criterion keeps its points and visible scenarios
            orig = next(o for o in full.criteria if o.name == c.name)
            assert c.points == orig.points
            assert c.scenarios == [s for s in orig.scenarios if full.scenario(s).visible]


def test_the_student_copy_has_the_scenario_files_of_the_labs(student_copy):
    files = sorted(ROOT.glob("labs/*/*_scenario.toml"))  # to run with plclab sim --scenario
    assert len(files) >= 3
    for f in files:
        assert (student_copy / "labs" / f.parent.name / f.name).read_bytes() == f.read_bytes()
    assert not (student_copy / "labs" / "wiring").exists()  # the tables are package data now


def test_the_student_copy_scores_the_visible_scenarios_like_the_full_lab(student_copy):
    src = ROOT / "labs" / "tank-two-position"
    for program in [src / "mistakes" / "never_stops.st", src / "solution" / "tank.st"]:
        full = check("tank-two-position", program.read_text(encoding="utf-8"))
        mine = check(student_copy / "labs" / "tank-two-position",
                     program.read_text(encoding="utf-8"))
        assert (mine.score, mine.max_score) == (full.score, full.max_score), program.name


def test_student_lab_toml_drops_hidden_scenarios_and_their_criteria():
    text = """title = "t"
[[scenario]]
name = "seen"
[[scenario]]
name = "secret"
visible = false
[[criterion]]
name = "a"
scenarios = ["seen", "secret"]
[[criterion]]
name = "only secret"
scenario = "secret"
[[criterion]]
name = "b"
scenario = "seen"
requires = ["a", "only secret"]
[[mistake]]
file = "x.st"
"""
    data = tomllib.loads(student_lab_toml(text))
    assert [s["name"] for s in data["scenario"]] == ["seen"]
    assert [c["name"] for c in data["criterion"]] == ["a", "b"]
    assert data["criterion"][0]["scenarios"] == ["seen"]
    assert data["criterion"][1]["requires"] == ["a"]
    assert "mistake" not in data and "secret" not in student_lab_toml(text)


def test_lab_get_copies_the_student_files_and_keeps_existing_work(tmp_path):
    files = get_lab_files("tank-two-position", tmp_path / "w")
    names = sorted(f.name for f in files)
    assert names == ["README.md", "starter.st", "tank-two-position.ipynb"]
    (tmp_path / "w" / "starter.st").write_text("my work", encoding="utf-8")
    with pytest.raises(PlcError) as e:
        get_lab_files("tank-two-position", tmp_path / "w")
    assert e.value.code == "PLC5050"
    assert (tmp_path / "w" / "starter.st").read_text(encoding="utf-8") == "my work"


def _source_tree(dest: Path) -> Path:
    """The files a build reads, copied so that building writes nothing into the repository."""
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info", "build")
    for d in ("plclab", "plants", "labs", "examples", "notebooks", "course"):
        shutil.copytree(ROOT / d, dest / d, ignore=ignore)
    for f in ("pyproject.toml", "README.md"):
        shutil.copyfile(ROOT / f, dest / f)
    return dest


def _run(cmd: list[str], cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess:
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, f"{cmd}\n{r.stdout}\n{r.stderr}"
    return r


def test_a_wheel_in_a_fresh_venv_has_the_labs(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PLCLAB_LABS")}
    src = _source_tree(tmp_path / "src")
    _run([sys.executable, "-m", "pip", "wheel", str(src), "--no-deps", "-q", "-w",
          str(tmp_path / "dist")], tmp_path, env)
    wheel = next((tmp_path / "dist").glob("plclab-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    assert "plclab/courseware/labs/tank-two-position/lab.toml" in names
    assert "plclab/courseware/examples/tank_level.st" in names
    assert "plclab/sim/wirings/tank_vfd.toml" in names  # the wiring tables are package data
    assert "plclab/courseware/labs/tank-two-position/tank_demand_scenario.toml" in names
    assert "plclab/courseware/course/01-what-is-a-plc/quiz.toml" in names  # the course ships
    assert not [n for n in names if any(f"/{d}/" in n for d in PRIVATE_DIRS)]

    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], tmp_path, env)
    bindir = venv / ("Scripts" if os.name == "nt" else "bin")
    py = bindir / "python"
    _run([str(py), "-m", "pip", "install", "--no-deps", "-q", str(wheel)], tmp_path, env)
    work = tmp_path / "work"
    work.mkdir()
    where = _run([str(py), "-c", "import plclab; print(plclab.__file__)"], work, env).stdout
    assert str(venv) in where  # the wheel, not a checkout on the path

    plclab = str(bindir / "plclab")
    chapters = _run([plclab, "course", "list"], work, env).stdout
    assert "What a PLC is" in chapters
    listed = _run([plclab, "lab", "list"], work, env).stdout
    ids = [line.split()[0] for line in listed.splitlines()[1:] if line.strip()]
    assert len(ids) >= 8 and "tank-two-position" in ids
    _run([plclab, "lab", "get", "tank-two-position"], work, env)
    starter = work / "tank-two-position" / "starter.st"
    assert starter.is_file()
    out = _run([plclab, "lab", "check", "tank-two-position", str(starter), "--no-media"],
               work, env).stdout
    assert "score: " in out.splitlines()[-1]
    assert sorted(p.name for p in work.iterdir()) == ["tank-two-position"]


def test_grading_with_the_student_copy_is_refused_unless_asked(student_copy, tmp_path, capsys):
    """An instructor grading from a pip install would grade without the hidden scenarios:
    refused (PLC5072) with where the instructor's lab folder is, unless --visible-only;
    grade-bundle never builds an autograder from the student copy."""
    from plclab.cli import main

    lab = student_copy / "labs" / "tank-two-position"
    assert load_lab(lab).student_copy and not load_lab("tank-two-position").student_copy
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ann.st").write_text((ROOT / "labs" / "tank-two-position" / "solution" /
                                  "tank.st").read_text(encoding="utf-8"), encoding="utf-8")
    args = ["grade", str(lab), str(subs), "--out", str(tmp_path / "out"), "--no-media",
            "--jobs", "1"]
    assert main(args) == 1
    err = capsys.readouterr().err
    assert "PLC5072" in err and "labs/tank-two-position" in err and "--visible-only" in err
    assert not (tmp_path / "out" / "grades.csv").exists()
    assert main(args + ["--visible-only"]) == 0
    assert "visible scenarios only" in capsys.readouterr().out
    assert main(["grade-bundle", str(lab), "-o", str(tmp_path / "b.zip")]) == 1
    assert "PLC5072" in capsys.readouterr().err and not (tmp_path / "b.zip").exists()
