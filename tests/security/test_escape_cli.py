"""The escape suite through the command line: ``plclab check``, ``run``, ``test``, ``lab check``
and ``grade`` run hostile files, file names, student names and lab TOML values in a subprocess
under an audit hook (``audit.py``). Each run must not import the sentinel module, read outside
its inputs (the secret file in particular), write outside its output folder, or start a process
other than plclab's own grading workers; and it prints no Python traceback.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
MOTOR = ROOT / "labs" / "motor-start-stop"


import audit  # noqa: E402
import payloads  # noqa: E402


@pytest.fixture
def box(tmp_path):
    return audit.Sandbox(tmp_path)


def _clean(run, box, reads=(), writes=()):
    assert "Traceback" not in run.output, run.output[-3000:]
    assert "TOKEN-do-not-leak" not in run.output
    bad = audit.violations(run, box, list(reads), list(writes))
    assert bad == [], "\n".join(bad[:30])


def _write_cases(folder: Path, cases) -> list[Path]:
    """Each case's files under its own subfolder (the cases reuse POU names)."""
    out = []
    for cid, files in cases:
        d = folder / cid
        d.mkdir(parents=True)
        for name, text in files.items():
            p = d / name
            p.write_text(text.replace("../secret/hidden.txt", "../../../secret/hidden.txt"))
            out.append(p)
    return out


def test_the_audit_sees_an_escape(box):
    """The harness can fail: a program that does import the sentinel is reported."""
    run = box.run(["explain", "PLC0100"])
    _clean(run, box)
    code = f"import pwned_sentinel; open({str(box.secret)!r}).read()"
    evil = box.cwd / "evil.py"
    evil.write_text(code)
    import os
    import subprocess

    env = dict(os.environ, PYTHONPATH=f"{box.hook}{os.pathsep}{ROOT}",
               PLCLAB_AUDIT_LOG=str(box.log))
    box.log.write_text("")
    subprocess.run([sys.executable, str(evil)], env=env, cwd=box.cwd, check=True)
    events = [audit.json.loads(x) for x in box.log.read_text().splitlines()]
    bad = audit.violations(audit.Run(0, "", "", events, box.cwd), box, [box.cwd], [])
    assert any("imported" in b for b in bad) and any("hidden.txt" in b for b in bad)


def test_the_audit_allows_a_fork_only_to_lab_check_and_prctl_only_to_its_child(box):
    """ADR 0057's direct grading child: ``lab check`` may fork, and the forked child may look
    up prctl; any other command's fork, or prctl in a started interpreter, is reported."""
    def run_of(argv: list[str], *events: tuple[int, str, list]) -> audit.Run:
        start = {"ev": "start", "pid": 1, "args": [["python", "-c", "import plclab.cli", *argv], str(box.cwd)]}
        return audit.Run(0, "", "", [start] + [{"ev": ev, "pid": pid, "args": args}
                                               for pid, ev, args in events], box.cwd)

    fork, prctl = (1, "os.fork", []), (2, "ctypes.dlsym", ["<CDLL 'None'>", "prctl"])
    assert audit.violations(run_of(["lab", "check", "m", "f.st"], fork, prctl), box, [], []) == []
    bad = audit.violations(run_of(["check", "f.st"], fork), box, [], [])
    assert any("os.fork" in b for b in bad)
    bad = audit.violations(run_of(["lab", "check", "m", "f.st"], (1, *prctl[1:])), box, [], [])
    assert any("prctl" in b for b in bad)  # in the command itself: not the sandbox's child
    bad = audit.violations(run_of(["lab", "check", "m", "f.st"],
                                  (2, "ctypes.dlsym", ["<CDLL 'None'>", "system"])), box, [], [])
    assert any("system" in b for b in bad)


@pytest.mark.parametrize("group", ["st", "il-ld", "xml"])
def test_check_every_hostile_file(box, group):
    cases = {"st": payloads.st_cases(), "il-ld": payloads.il_cases() + payloads.ld_cases(),
             "xml": payloads.xml_cases()}[group]
    files = _write_cases(box.cwd / "src", cases)
    # all at once: the cases reuse POU names, which only adds diagnostics
    run = box.run(["check", *map(str, files)])
    assert run.returncode in (0, 1) and "error(s)" in run.stdout, run.output[-2000:]
    _clean(run, box, reads=[box.cwd])


RUN_CASES = ["string-0", "string-1", "string-2", "string-4", "string-5", "wstring-0",
             "comment-0", "comment-4", "ident-var-0", "ident-var-1", "ident-var-24",
             "ident-type-30", "pragma-7", "il-label-1", "ld-names-1", "xml-cdata-end",
             "xml-xxe", "xml-billion-laughs", "config-names"]


@pytest.mark.parametrize("cid", RUN_CASES)
def test_run_hostile_program(box, cid):
    cases = [c for c in payloads.all_cases() if c[0] == cid]
    files = _write_cases(box.cwd / "src", cases)
    run = box.run(["run", *map(str, files), "--cycles", "3",
                   "--set", "Main.s=$'); import pwned_sentinel #"])
    _clean(run, box, reads=[box.cwd])
    run = box.run(["run", *map(str, files), "--cycles", "2"])
    _clean(run, box, reads=[box.cwd])


def test_test_blocks_with_hostile_names(box):
    from plclab.project import check_sources

    body = payloads._prog("x := x + 1;", "    x : INT;\n")
    for lit in payloads.STRINGS:  # the ones that are valid ST strings
        test = (f"TEST {lit}\n  Main();\n  ASSERT_EQ(Main.x, 2);\n"
                f"  ASSERT_TRUE(LEN({lit}) > 1000);\nEND_TEST\n")
        if check_sources([(body + test, "t.st")])[0] is not None:
            body += test
    assert body.count("TEST") >= 5
    f = box.cwd / "t.st"
    f.write_text(body)
    run = box.run(["test", str(f), "-v"])
    assert re.search(r"0 passed, \d+ failed", run.stdout), run.output[-2000:]
    _clean(run, box, reads=[box.cwd])
    run = box.run(["test", str(f), "-k", "'); import pwned_sentinel #"])
    _clean(run, box, reads=[box.cwd])


def _hostile_names() -> list[str]:
    names = [n for n in payloads.FILE_NAMES if "/" not in n]
    return names


@pytest.mark.parametrize("name", _hostile_names())
def test_check_and_run_hostile_file_names(box, name):
    f = box.cwd / name
    f.write_text((MOTOR / "solution" / "motor.st").read_text())
    run = box.run(["check", "--", str(f)] if name.startswith("-") else ["check", str(f)])
    _clean(run, box, reads=[box.cwd])
    run = box.run(["run", str(f), "--cycles", "2"])
    _clean(run, box, reads=[box.cwd])


def _hostile_solution() -> str:
    sol = (MOTOR / "solution" / "motor.st").read_text()
    extra = (f"\n(* {payloads.COMMENTS[0]} *)\n{payloads.PRAGMAS[7]}\n"
             f"FUNCTION_BLOCK Extra\nVAR s : STRING[255] := {payloads.STRINGS[0]}; END_VAR\n"
             f"s := {payloads.STRINGS[1]};\nEND_FUNCTION_BLOCK\n")
    return sol + extra


def test_lab_check_hostile_file(box):
    f = box.cwd / "new\nline '); import pwned_sentinel #.st"
    f.write_text(_hostile_solution())
    out = box.tmp / "fb"
    run = box.run(["lab", "check", "motor-start-stop", str(f), "--out", str(out)])
    assert run.stdout.rstrip().splitlines()[-1].startswith("score: "), run.output[-2000:]
    _clean(run, box, reads=[box.cwd, out], writes=[out])


def test_grade_hostile_students(box):
    subs = box.cwd / "subs"
    subs.mkdir()
    sol = _hostile_solution()
    for i, name in enumerate(_hostile_names()):
        if i % 2:
            d = subs / Path(name).stem
            d.mkdir()
            (d / "main.st").write_text(sol)
        else:
            (subs / name).write_text(sol)
    for cid, files in payloads.st_cases()[::25]:
        d = subs / f"case {cid}'"
        d.mkdir()
        for n, text in files.items():
            (d / n).write_text(text)
    out = box.tmp / "grades"
    run = box.run(["grade", "motor-start-stop", str(subs), "--out", str(out), "--jobs", "2",
                   "--no-media"], timeout=600)
    assert run.returncode == 0, run.output[-3000:]
    _clean(run, box, reads=[subs, out], writes=[out])


def _evil_lab(box, **edits: str) -> Path:
    lab = box.cwd / "labs" / "evil-lab"
    lab.mkdir(parents=True)
    for p in MOTOR.rglob("*"):
        if p.is_file():
            q = lab / p.relative_to(MOTOR)
            q.parent.mkdir(parents=True, exist_ok=True)
            q.write_bytes(p.read_bytes())
    text = (lab / "lab.toml").read_text()
    for old, new in edits.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    (lab / "lab.toml").write_text(text)
    return lab


S = payloads.S
LAB_EDITS = {
    "expression": {'trigger = "START and STOP and not OVERLOAD"': f'trigger = "__import__(\'{S}\')"'},
    "dunder": {'condition = "RUN"': 'condition = "().__class__.__bases__[0].__subclasses__()"'},
    "python-check": {'check = "within"': f'python = "{S}:main"\ncheck = "within"'},
    "python-path": {'check = "within"': 'python = "../../hook/pwned_sentinel:main"\n'
                                        'check = "within"'},
    "texts": {
        'title = "Motor': 'title = "\\n# {0.__class__} ``` $(id) \\"\\"\\" <script>Motor',
        'message = "the motor does not start': 'message = "{lab.__init__.__globals__} '
        '`; import pwned_sentinel` | x |\\n## the motor does not start',
        'name = "starts"': 'name = "starts"\nhint = "]]> {0!r:{1}} %s %(x)s"'},
    "names": {'name = "start-stop"': 'name = "../../../escaped"',
              '["start-stop", "overload"': '["../../../escaped", "overload"',
              'scenarios = ["start-stop"]': 'scenarios = ["../../../escaped"]'},
    "wiring-module": {'wiring = [': f'wiring = [{{ plc = "%IX0.0", signal = "START", '
                      f'module = "{S}" }}]\nold_wiring = ['},
}


@pytest.mark.parametrize("edit", list(LAB_EDITS))
def test_hostile_lab_toml(box, edit):
    lab = _evil_lab(box, **LAB_EDITS[edit])
    f = box.cwd / "motor.st"
    f.write_text((MOTOR / "solution" / "motor.st").read_text())
    out = box.tmp / "fb"
    run = box.run(["lab", "check", str(lab), str(f), "--out", str(out)])
    _clean(run, box, reads=[box.cwd, out], writes=[out])
    subs = box.tmp / "subs"
    subs.mkdir()
    (subs / "alice.st").write_text(f.read_text())
    grades = box.tmp / "grades"
    run = box.run(["grade", str(lab), str(subs), "--out", str(grades), "--jobs", "1"],
                  timeout=600)
    _clean(run, box, reads=[box.cwd, subs, grades], writes=[grades])
