"""The grader against hostile submissions and a hostile child (issue 11: "the grader trusts too
much"). One folder of attacks is graded once (module fixture); the other tests are unit tests
of the pieces or run the grader on one submission."""

import csv
import json
import multiprocessing
import os
import pickle
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from plclab.grade import safety
from plclab.grade.engine import cap_diagnostics, read_submission
from plclab.grade.grader import SIDECAR, Grader, Submission, _Running
from plclab.grade.gradescope import gradebook_csv
from plclab.grade.lab import load_lab
from plclab.grade.protocol import Inbox, Rejected, encode
from plclab.grade.scaffold import create_lab

LAB = load_lab("motor-start-stop")
GOOD = (LAB.path / "solution" / "motor.st").read_text(encoding="utf-8")
NEWLINE_NAME = "eve\n# Pwned\n```\nrm -rf ~\n```\n<img src=x>`"
FORMULA_NAME = '=HYPERLINK("x","y")'
PASSWD = Path("/etc/passwd")


def passwd_tokens() -> list[str]:
    if not PASSWD.is_file():
        return []
    return [ln for ln in PASSWD.read_text(errors="replace").splitlines() if ln.count(":") >= 6]


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    root = tmp_path_factory.mktemp("hostile")
    subs = root / "subs"
    subs.mkdir()
    (subs / "alice.st").write_text(GOOD, encoding="utf-8")
    os.symlink(subs / "alice.st", subs / "mallory.st")            # another student's file
    (subs / "trudy").mkdir()                                       # a link inside a folder
    os.symlink(subs / "alice.st", subs / "trudy" / "motor.st")
    if PASSWD.is_file():
        os.symlink(PASSWD, subs / "oscar.st")
        (subs / "peggy").mkdir()
        os.symlink(PASSWD, subs / "peggy" / "passwd.st")
    with open(subs / "sparse.st", "wb") as fh:                     # 6 GB, no blocks on disk
        os.truncate(fh.fileno(), 6 * 2**30)
    (subs / "nul.st").write_bytes(b"\0" * 2**20)
    (subs / "grades.csv.st").write_text(GOOD, encoding="utf-8")
    (subs / f"{FORMULA_NAME}.st").write_text(GOOD, encoding="utf-8")
    (subs / "-2+3.st").write_text(GOOD, encoding="utf-8")
    (subs / f"{NEWLINE_NAME}.st").write_text(GOOD, encoding="utf-8")
    (subs / "a b.st").write_text(GOOD, encoding="utf-8")          # same folder name as a_b
    (subs / "a_b.st").write_text(GOOD, encoding="utf-8")
    out = root / "out"
    t0 = time.monotonic()
    outcomes = Grader(LAB, out, jobs=2, timeout=20.0, memory_mb=600,
                      media=False).grade_folder(subs)
    res = {o.result.student: o for o in outcomes}
    return subs, out, res, time.monotonic() - t0


def all_output(out: Path) -> str:
    return "\n".join(p.read_text(encoding="utf-8", errors="replace")
                     for p in out.rglob("*") if p.is_file())


def test_links_are_rejected_and_never_followed(hostile):
    _, out, res, _ = hostile
    assert res["alice"].result.score == LAB.max_score
    for who in ("mallory", "trudy") + (("oscar", "peggy") if PASSWD.is_file() else ()):
        r = res[who].result
        assert r.status == "rejected" and r.score == 0, who
        fb = (out / res[who].dirname / "feedback.md").read_text(encoding="utf-8")
        assert "PLC5030" in fb and "symbolic link" in fb, who


def test_no_token_of_a_linked_system_file_in_any_output(hostile):
    _, out, _, _ = hostile
    text = all_output(out)
    tokens = passwd_tokens()
    if not tokens:
        pytest.skip("no /etc/passwd here")
    assert not [t for t in tokens if t in text]
    assert "root:x:0" not in text


def test_a_6gb_sparse_file_is_rejected_without_reading_it(hostile, tmp_path):
    _, out, res, _ = hostile
    r = res["sparse"].result
    assert r.status == "rejected" and r.score == 0
    assert "PLC5031" in (out / "sparse" / "feedback.md").read_text(encoding="utf-8")
    big = tmp_path / "big.st"
    with open(big, "wb") as fh:
        os.truncate(fh.fileno(), 6 * 2**30)
    t0 = time.process_time()
    with pytest.raises(Exception) as e:
        read_submission(big)
    assert getattr(e.value, "code", "") == "PLC5031"
    assert time.process_time() - t0 < 0.5, "rejected from fstat, not by reading"


def test_a_megabyte_of_nul_bytes_gives_bounded_outputs(hostile):
    _, out, res, _ = hostile
    r = res["nul"].result
    assert r.score == 0 and r.status in ("compile_error", "memory", "timeout")
    assert len(r.diagnostics) <= 300
    d = out / res["nul"].dirname
    assert (d / SIDECAR).stat().st_size < 400_000
    assert (d / "results.json").stat().st_size < 100_000
    assert (d / "feedback.md").stat().st_size < 100_000


def test_diagnostics_are_capped_per_file_with_a_count_of_the_rest():
    from plclab.errors import Diagnostic, Location

    diags = [Diagnostic("PLC0001", "bad", Location("a.st", 1, i)) for i in range(10_000)]
    diags += [Diagnostic("PLC0001", "bad", Location("b.st", 1, 1))]
    kept = cap_diagnostics(diags)
    assert len([k for k in kept if k.startswith("a.st")]) == 50
    assert any(k.startswith("b.st") for k in kept)
    assert "... and 9950 more in a.st" in kept[-1]


def test_a_student_named_like_the_gradebook(hostile):
    _, out, res, _ = hostile
    assert (out / "grades.csv").is_file()
    oc = res["grades.csv"]
    assert oc.result.score == LAB.max_score
    assert oc.dirname != "grades.csv" and (out / oc.dirname / "results.json").is_file()
    rows = list(csv.DictReader((out / "grades.csv").open(encoding="utf-8")))
    assert "grades.csv" in [r["student"] for r in rows]


def test_per_student_folders_never_collide(hostile):
    _, out, res, _ = hostile
    dirs = [o.dirname for o in res.values()]
    assert len(set(d.lower() for d in dirs)) == len(dirs)
    assert res["a b"].dirname != res["a_b"].dirname
    for o in res.values():
        assert (out / o.dirname).parent == out and not o.dirname.startswith(".")


def test_formula_names_are_not_formulas_in_the_gradebook(hostile):
    _, out, _, _ = hostile
    rows = list(csv.reader((out / "grades.csv").open(encoding="utf-8")))
    for row in rows[1:]:
        for cell in row:
            assert not cell.startswith(("=", "+", "-", "@", "\t", "\r")), cell
    students = [r[0] for r in rows[1:]]
    assert "'" + FORMULA_NAME in students and "'-2+3" in students


@pytest.mark.parametrize("name", ['=HYPERLINK("http://x","y")', "+1", "-1", "@SUM(A1)",
                                  "\tx", "\rx"])
def test_gradebook_cells_are_neutralised(name):
    from plclab.grade.engine import Result

    text = gradebook_csv([Result("lab", student=name)], [])
    cell = next(csv.reader(text.splitlines()[1:]))[0]
    assert not cell.startswith(("=", "+", "-", "@", "\t", "\r"))
    assert cell.lstrip("'\\") .endswith(name.lstrip()[-3:].strip("\t\r"))


def test_a_name_with_newlines_and_backticks_cannot_inject_markdown(hostile):
    _, out, res, _ = hostile
    who = safety.clean_text(NEWLINE_NAME)
    assert "\n" not in who and who in res
    fb = (out / res[who].dirname / "feedback.md").read_text(encoding="utf-8")
    lines = fb.splitlines()
    assert "# Pwned" not in lines and not any(ln.startswith("```") for ln in lines)
    for ln in lines:  # HTML only inside the code span of the file list, escaped elsewhere
        assert ln.startswith("Files: ````") or not re.search(r"(?<!\\)<img", ln), ln
    assert sum(ln.startswith("# ") for ln in lines) == 1
    json.loads((out / res[who].dirname / "results.json").read_text(encoding="utf-8"))


def test_markdown_helpers():
    assert safety.md_fence(["````x"])[0].startswith("`````")
    assert safety.md_code("a``b") == "``` a``b ```"
    assert "\n" not in safety.md_line("a\n# b")


def test_the_whole_run_stays_fast(hostile):
    assert hostile[3] < 120


# ---------------------------------------------------------------------------- the child


def _inbox(tmp_path):
    d = tmp_path / "student"
    d.mkdir()
    return Inbox(LAB, d), d


def _good_scenario():
    sc = LAB.scenarios[0]
    tests = [{"name": f"{sc.name}: {c.name}", "scenario": sc.name, "criterion": c.name,
              "score": c.points, "max_score": c.points, "passed": True, "message": "ok",
              "detail": "ok", "t_fail": None, "diagram": None}
             for c in LAB.criteria_for(sc.name)]
    return {"name": sc.name, "ran": True, "notes": []}, tests


FORGED = {
    "score above the points": lambda run, t: (run, [dict(x, score=1e9) for x in t]),
    "negative score": lambda run, t: (run, [dict(x, score=-1) for x in t]),
    "NaN score": lambda run, t: (run, [dict(x, score=float("nan")) for x in t]),
    "score as text": lambda run, t: (run, [dict(x, score="9") for x in t]),
    "score but failed": lambda run, t: (run, [dict(x, passed=False) for x in t]),
    "another criterion": lambda run, t: (run, [dict(x, criterion="free points") for x in t]),
    "an extra test": lambda run, t: (run, t + t[:1]),
    "unknown scenario": lambda run, t: (dict(run, name="bonus"), t),
    "a diagram never sent": lambda run, t: (run, [dict(x, diagram="../../grades.csv")
                                                  for x in t]),
    "a huge message": lambda run, t: (run, [dict(x, message="x" * 10**6) for x in t]),
    "too many notes": lambda run, t: (dict(run, notes=["n"] * 10_000), t),
}


@pytest.mark.parametrize("attack", FORGED)
def test_forged_scenario_messages_are_rejected(tmp_path, attack):
    box, d = _inbox(tmp_path)
    run, tests = FORGED[attack](*_good_scenario())
    raw = json.dumps(["scenario", run, tests]).encode()
    with pytest.raises(Rejected):
        box.receive(raw)
    assert not box.tests


def test_an_honest_scenario_message_is_taken(tmp_path):
    box, _ = _inbox(tmp_path)
    box.receive(encode("scenario", *_good_scenario()))
    assert box.tests and all(t.score == t.max_score for t in box.tests)
    assert [t.hint for t in box.tests] == [c.hint for c in LAB.criteria_for(LAB.scenarios[0].name)]


@pytest.mark.parametrize("name, blob", [
    ("../../evil.png", b"\x89PNG\r\n\x1a\n"),
    ("..png", b"\x89PNG\r\n\x1a\n"),
    ("grades.csv", b"a,b"),
    ("x.png", b"#!/bin/sh\necho not a picture"),
    ("x.rrd", b"\x89PNG\r\n\x1a\n"),
    ("x.png", b"\x89PNG\r\n\x1a\n" + b"\0" * (3 * 2**20)),
])
def test_forged_media_are_rejected_and_not_written(tmp_path, name, blob):
    import base64

    box, d = _inbox(tmp_path)
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    with pytest.raises(Rejected):
        box.receive(json.dumps(["media", name, base64.b64encode(blob).decode()]).encode())
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before


def test_pickle_and_garbage_are_rejected(tmp_path):
    box, _ = _inbox(tmp_path)
    for raw in (pickle.dumps(("done", {"score": 100})), b"\xff\xfe", b"[]", b'["exec", "x"]',
                b"[" * 100_000):
        with pytest.raises(Rejected):
            box.receive(raw)


class _DeadProc:
    exitcode = 0
    sentinel = None

    def join(self, timeout=None):
        return None

    def kill(self):
        return None


def test_the_grader_rejects_a_forged_child_and_writes_only_its_own_files(tmp_path):
    """A child that sends full marks plus a picture aimed at another student's folder: the
    parent rejects it, scores 0 and writes nothing but that student's three files."""
    import base64

    out = tmp_path / "out"
    (out / "bob").mkdir(parents=True)
    (out / "bob" / "results.json").write_text("{}", encoding="utf-8")
    g = Grader(LAB, out, jobs=1, media=True)
    sub = Submission("eve", [], dirname="eve", files=["eve.st"], hash="h")
    (out / "eve").mkdir()
    parent, child = multiprocessing.Pipe(duplex=False)
    run, tests = _good_scenario()
    child.send_bytes(encode("scenario", run, tests))
    child.send_bytes(json.dumps(["media", "../bob/results.png",
                                 base64.b64encode(b"\x89PNG\r\n\x1a\n").decode()]).encode())
    child.close()
    work = tmp_path / "work"
    work.mkdir()
    r = _Running(sub, _DeadProc(), parent, out / "eve", work, Inbox(LAB, out / "eve"))
    r.drain()
    assert r.rejected and r.final
    oc = g._finish(r, False)
    assert oc.result.status == "rejected" and oc.result.score == 0
    assert "PLC5034" in (out / "eve" / "feedback.md").read_text(encoding="utf-8")
    assert sorted(p.name for p in (out / "eve").iterdir()) == sorted(
        ["results.json", "feedback.md", SIDECAR])
    assert (out / "bob" / "results.json").read_text(encoding="utf-8") == "{}"
    assert not (out / "bob" / "results.png").exists() and not work.exists()


def test_an_oversized_message_is_rejected_without_reading_it(tmp_path):
    parent, child = multiprocessing.Pipe(duplex=False)
    sub = Submission("eve", [], dirname="eve")
    r = _Running(sub, _DeadProc(), parent, tmp_path, tmp_path, Inbox(LAB, None))
    from plclab.grade import protocol

    old = protocol.LIMITS["message"]
    protocol.LIMITS["message"] = 1000
    try:
        child.send_bytes(b"[" + b" " * 5000 + b"]")
        r.drain()
    finally:
        protocol.LIMITS["message"] = old
    assert r.rejected


def test_the_job_holds_text_and_data_not_paths(tmp_path):
    """What a child receives names no path of the lab, the submissions or the results."""
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ann.st").write_text(GOOD, encoding="utf-8")
    out = tmp_path / "out"
    captured = {}

    class Ctx:
        def Pipe(self, duplex):
            return multiprocessing.Pipe(duplex=False)

        def Process(self, target, args, **kw):
            captured["job"] = args[0]

            class P:
                def start(self):
                    return None
            return P()

    g = Grader(LAB, out)
    from plclab.grade.grader import discover

    sub = discover(subs)[0]
    r = g._start(Ctx(), sub)
    blob = pickle.dumps(captured["job"])
    for path in (LAB.path, subs, out, Path(LAB.path).parent):
        assert str(path).encode() not in blob, path
    assert captured["job"]["sources"] == [(GOOD, "ann.st")]
    shutil.rmtree(r.workdir)


PROBE = '''

_full_cycles = full_cycles


def full_cycles(trace, min_cycles=1):
    import ctypes
    import json
    import os
    import resource

    ok, msg, t, sig = _full_cycles(trace, min_cycles)
    death = ctypes.c_int(0)
    ctypes.CDLL(None).prctl(2, ctypes.byref(death), 0, 0, 0)
    report = {"cwd": os.getcwd(), "files": sorted(os.listdir(".")), "env": sorted(os.environ),
              "home": os.environ.get("HOME"), "cpu": resource.getrlimit(resource.RLIMIT_CPU)[0],
              "deathsig": death.value, "file": __file__}
    return ok, msg + " PROBE" + json.dumps(report), t, sig
'''


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="prctl is Linux only")
@pytest.mark.parametrize("direct", [False, True], ids=["forkserver", "direct"])
def test_a_child_runs_confined(tmp_path, monkeypatch, direct):
    """An instructor check (which runs in the child) reports the child's surroundings: the
    same for a forkserver's child (``grade``) and a direct one (``lab check``, ADR 0057)."""
    lab_dir = create_lab("probe-lab", tmp_path)
    with open(lab_dir / "checks.py", "a", encoding="utf-8") as fh:
        fh.write(PROBE)
    lab = load_lab(lab_dir)
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(lab_dir / "solution" / "solution.st", subs / "ann.st")
    monkeypatch.setenv("INSTRUCTOR_TOKEN", "s3cret")
    out = tmp_path / "out"
    if direct:
        sources = [((subs / "ann.st").read_text(encoding="utf-8"), "ann.st")]
        oc = Grader(lab, out, jobs=1, timeout=60, media=False, direct=True).grade_one(sources)
    else:
        [oc] = Grader(lab, out, jobs=1, timeout=60, media=False).grade_folder(subs)
    msg = next(t.message for t in oc.result.tests if "PROBE" in t.message)
    rep = json.loads(msg.split("PROBE", 1)[1])
    assert "INSTRUCTOR_TOKEN" not in rep["env"]
    assert set(rep["env"]) <= set(
        "PATH LANG LC_ALL LC_CTYPE LC_NUMERIC TZ HOME TMPDIR MPLBACKEND MPLCONFIGDIR "
        "OMP_NUM_THREADS OPENBLAS_NUM_THREADS MKL_NUM_THREADS PLCLAB_GRADE_CHILD".split()
        ) | {k for k in rep["env"] if k.startswith("PYTHON")}
    assert rep["home"] == rep["cwd"] and not rep["cwd"].startswith(str(tmp_path))
    assert set(rep["files"]) <= {"child.log", "media"}
    assert rep["deathsig"] == signal.SIGKILL
    assert 0 < rep["cpu"] <= 70
    assert str(lab_dir) not in rep["file"]
    assert not os.path.exists(rep["cwd"]), "the parent removes the child's folder"


# ---------------------------------------------------------------------------- orphans


SLOW = GOOD.replace("END_VAR", "    i : DINT;\n    x : LREAL;\nEND_VAR", 1).replace(
    "END_PROGRAM", "FOR i := 1 TO 400000 DO x := x + 1.0; END_FOR;\nEND_PROGRAM")


def _group(pgid: int) -> list[tuple[int, str]]:
    """Live (not zombie) processes of a process group: (pid, comm)."""
    out = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            stat_ = (d / "stat").read_text()
            comm = (d / "comm").read_text().strip()
        except OSError:
            continue
        fields = stat_.rsplit(")", 1)[1].split()
        if int(fields[2]) == pgid and fields[0] != "Z":
            out.append((int(d.name), comm))
    return out


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
@pytest.mark.parametrize("command", ["grade", "lab check"])
def test_no_grading_process_outlives_a_killed_grader(tmp_path, command):
    """Neither a forkserver's child (``grade``) nor a direct one (``lab check``, ADR 0057)."""
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "slow.st").write_text(SLOW, encoding="utf-8")
    (tmp_path / "tmp").mkdir()  # a killed grader cannot remove its child's folder: keep it here
    env = dict(os.environ, TMPDIR=str(tmp_path / "tmp"), PYTHONPATH=os.pathsep.join(
        [str(Path(__file__).resolve().parents[2])] + sys.path))
    args = (["grade", "motor-start-stop", str(subs), "--out", str(tmp_path / "out"),
             "--jobs", "1", "--timeout", "300s", "--no-media", "-q"] if command == "grade"
            else ["lab", "check", "motor-start-stop", str(subs / "slow.st")])
    proc = subprocess.Popen([sys.executable, "-m", "plclab", *args], env=env,
                            start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline:
            if any(c == "plclab-grade" for _, c in _group(proc.pid)):
                break
            assert proc.poll() is None, "the grader ended before its child started"
            time.sleep(0.2)
        else:
            pytest.fail("no grading child started")
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=10)
        deadline = time.monotonic() + 10
        while _group(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _group(proc.pid) == [], "grading processes survived their grader"
    finally:
        for pid, _ in _group(proc.pid):
            os.kill(pid, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()


def _py(code: str) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(__file__).resolve().parents[2])] + sys.path))
    return subprocess.Popen([sys.executable, "-c", code], env=env)


@pytest.mark.skipif(not hasattr(signal, "SIGXCPU"), reason="no RLIMIT_CPU here")
def test_the_cpu_limit_stops_a_busy_child():
    p = _py("from plclab.grade.sandbox import limit_cpu\nlimit_cpu(1)\nwhile True:\n    pass")
    assert p.wait(timeout=60) in (-signal.SIGXCPU, -signal.SIGKILL)


def test_the_watchdog_ends_a_child_whose_grader_is_gone():
    """The fallback where prctl is missing: the grader's pid disappears, the child ends (its
    own parent, this test, stays alive, so only the watchdog can notice)."""
    grader = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    child = _py(f"import time\nfrom plclab.grade.sandbox import die_with_parent\n"
                f"die_with_parent({grader.pid}, interval=0.1)\ntime.sleep(60)")
    try:
        time.sleep(1.0)
        assert child.poll() is None
        grader.kill()
        grader.wait()
        assert child.wait(timeout=10) == -signal.SIGKILL
    finally:
        for p in (grader, child):
            if p.poll() is None:
                p.kill()


def test_a_long_file_name_keeps_its_language(tmp_path):
    """LMS exports prefix names (``name_id_subid_...``): a name far over the display limit is
    cut in the middle, so the front end is still chosen by its real extension."""
    from plclab.grade.engine import grade_sources

    long = tmp_path / ("doe_jane_123456_7890123_" + "motor_start_stop_final_v2_" * 8 + ".st")
    long.write_text(GOOD, encoding="utf-8")
    sources, _ = read_submission(long)
    (text, name), = sources
    assert len(name) <= safety.MAX_NAME and name.endswith(".st") and "…" in name
    res = grade_sources(LAB, sources, scenarios=[LAB.scenarios[0].name])
    assert res.status == "ok" and res.score == res.max_score > 0
