"""Command-line sub-commands ``plclab grade`` and ``plclab lab``.

``plclab grade LAB SUBMISSIONS [--jobs N] [--out DIR] [--executor dask://HOST:PORT]`` (or
``--manifest course.toml``) grades a folder (or an LMS zip) of submissions; ``plclab lab list``, ``plclab lab show LAB``, ``plclab lab
check LAB FILE...`` (a student's local run of the visible scenarios, ending with ``score:
X/Y``) and ``plclab lab new ID`` (an instructor's scaffold).
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any

from plclab.cli_registry import arg, command

from .errors import grade_error
from .scaffold import (
    CRITERIA_END,
    CRITERIA_START,
    README_END,
    README_START,
    readme_table,
    replace_block,
)


def _labs_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("--labs", action="append", default=[], metavar="DIR",
                   help="also look for labs in DIR (PLCLAB_LABS works too)")


# ---------------------------------------------------------------------------- plclab grade


@command("grade")
@arg("lab", metavar="LAB", nargs="?", help="lab id (see: plclab lab list) or lab folder")
@arg("submissions", metavar="SUBMISSIONS", nargs="?",
     help="folder with one file or one folder per student, or an LMS export .zip of either")
@arg("--manifest", default=None, metavar="TOML", help="grade many labs in one run: a [labs] "
     'table of lab = "submissions folder" lines (instead of LAB SUBMISSIONS)')
@arg("--executor", default="local", metavar="WHERE", help="local (a process pool, the "
     "default) or dask://HOST:PORT (the workers of a Dask scheduler; see docs/grading-cluster.md)")
@arg("--jobs", "-j", type=int, default=None, help="submissions graded in parallel "
     "(default: the number of CPUs; local executor)")
@arg("--out", default=None, metavar="DIR", help="output folder (default: SUBMISSIONS-grades "
     "beside the submissions; with --manifest: DIR/<lab>/)")
@arg("--timeout", default=None, help="wall-clock limit per submission, e.g. 30s (default: the "
     "lab's time_limit)")
@arg("--memory", default=None, help="memory limit per submission, e.g. 1.5GB (default: the "
     "lab's memory_limit)")
@arg("--force", action="store_true", help="regrade submissions that did not change")
@arg("--no-media", action="store_true", help="no timing diagrams and recordings (faster)")
@arg("--labs", action="append", default=[], metavar="DIR", help="also look for labs in DIR")
@arg("--quiet", "-q", action="store_true", help="no table of students")
@arg("--visible-only", action="store_true", help="grade with a lab that has no hidden "
     "scenarios (the student copy installed with plclab); refused otherwise")
def cmd_grade(ns: argparse.Namespace) -> int:
    from plclab.sim import parse_seconds

    from .batch import default_out, read_manifest
    from .cluster import parse_executor
    from .lab import parse_memory

    if ns.manifest and (ns.lab or ns.submissions):
        raise grade_error("PLC5062", "give either --manifest TOML or LAB SUBMISSIONS, not both")
    if ns.manifest:
        runs = read_manifest(ns.manifest)
        where = [(lab, subs, Path(ns.out) / Path(lab).name if ns.out else default_out(subs))
                 for lab, subs in runs]
    elif ns.lab and ns.submissions:
        where = [(ns.lab, Path(ns.submissions),
                  Path(ns.out) if ns.out else default_out(ns.submissions))]
    else:
        raise grade_error("PLC5026", "give LAB SUBMISSIONS (e.g. plclab grade tank-two-position "
                          "submissions/) or --manifest course.toml")
    jobs = ns.jobs if ns.jobs is not None else (os.cpu_count() or 1)
    if jobs < 1:
        raise grade_error("PLC5026", "--jobs must be 1 or more")
    timeout = None
    if ns.timeout is not None:
        try:
            timeout = parse_seconds(ns.timeout, "--timeout", allow_zero=False)
        except Exception as e:  # noqa: BLE001
            raise grade_error("PLC5026", f"--timeout {ns.timeout}: write e.g. 30s or 2min "
                              f"({e})") from None
    memory = None
    if ns.memory is not None:
        try:
            memory = parse_memory(ns.memory)
        except ValueError as e:
            raise grade_error("PLC5026", f"--memory: {e}") from None
    executor = parse_executor(ns.executor)
    for lab_name, subs, out in where:
        _grade_one_lab(ns, lab_name, subs, out, jobs, timeout, memory, executor,
                       multi=len(where) > 1)
    return 0


def _grade_one_lab(ns: argparse.Namespace, lab_name: str, subs: Path, out: Path, jobs: int,
                   timeout: float | None, memory: int | None, executor: str | None,
                   multi: bool) -> None:
    from .batch import Unpacked, run_summary
    from .grader import Grader
    from .lab import lacks, load_lab, require_hidden
    from .progress import ProgressBar, summary_table

    lab = load_lab(lab_name, ns.labs, deep=True)
    require_hidden(lab, ns.visible_only)
    if lab.student_copy:
        print(f"note: grading {lab.id} on its visible scenarios only (--visible-only): "
              f"{lacks(lab)}")
    if multi:
        print(f"== {lab.id}: {subs} -> {out}")
    bar = ProgressBar() if sys.stdout.isatty() else None
    g = Grader(lab, out, jobs, timeout, memory, ns.force, not ns.no_media, progress=bar,
               executor=executor)
    with Unpacked(subs) as folder:
        outcomes = g.grade_folder(folder)
    if not ns.quiet:
        print(summary_table(outcomes))
    print(run_summary(outcomes))
    graded = sum(1 for o in outcomes if not o.skipped)
    print(f"{graded} graded, {len(outcomes) - graded} unchanged; results in {out}/<student>/, "
          f"gradebook {out / 'grades.csv'}")
    lost = [o.result.student for o in outcomes if o.result.status == "infrastructure"]
    if lost:
        from plclab.errors import printable  # student names come from file names

        names = ", ".join(printable(n) for n in lost[:10]) + (
            f" and {len(lost) - 10} more" if len(lost) > 10 else "")
        print(f"{len(lost)} submission(s) lost to the grading machine, not graded (PLC5070: "
              f"{names}): their processes were killed from outside (out of memory?). Run the "
              "same command again: it grades these again and keeps the grades already given "
              "(with fewer --jobs if it happens again)")


@command("grade-bundle")
@arg("lab", metavar="LAB", help="lab id (see: plclab lab list) or lab folder")
@arg("-o", "--output", default=None, metavar="ZIP", help="the zip to write (default: "
     "LAB-autograder.zip)")
@arg("--wheel", default=None, metavar="FILE", help="a plclab wheel to ship (default: built "
     "from this checkout with pip wheel . --no-deps)")
@arg("--labs", action="append", default=[], metavar="DIR", help="also look for labs in DIR")
def cmd_grade_bundle(ns: argparse.Namespace) -> int:
    from .bundle import build_bundle

    out = build_bundle(ns.lab, ns.output or f"{Path(str(ns.lab)).name}-autograder.zip",
                       ns.labs, ns.wheel)
    print(f"{out}: Gradescope autograder (setup.sh, run_autograder, the plclab wheel, the lab "
          "with its hidden scenarios): upload it to Gradescope, never give it to students")
    return 0


# ---------------------------------------------------------------------------- plclab lab


def _lab_args(p: argparse.ArgumentParser) -> None:
    from plclab.viz.from_trace import add_export_args

    sub = p.add_subparsers(dest="lab_cmd", metavar="ACTION")
    sp = sub.add_parser("list", help="list the labs")
    _labs_arg(sp)
    sp = sub.add_parser("show", help="the task and the I/O table of a lab")
    sp.add_argument("lab", metavar="LAB")
    sp.add_argument("--update-readme", action="store_true",
                    help="rewrite the I/O table in the lab's README.md from lab.toml")
    _labs_arg(sp)
    sp = sub.add_parser("check", help="run the visible scenarios on your program and get the "
                        "feedback (ends with score: X/Y)")
    sp.add_argument("lab", metavar="LAB")
    sp.add_argument("files", nargs="+", metavar="FILE", help="your source files (or a folder)")
    sp.add_argument("--scenario", default=None, help="only this scenario (and export it)")
    sp.add_argument("--hidden", action="store_true", help="also the hidden scenarios "
                    "(instructors)")
    sp.add_argument("--out", default=None, metavar="DIR", help="write feedback.md, the "
                    "diagrams and recordings of the failures into DIR (replaced on each run; "
                    "default: nothing is written)")
    sp.add_argument("--no-media", action="store_true", help="no diagrams and recordings")
    sp.add_argument("--hint", type=int, default=1, metavar="N", help="hints of the failures: "
                    "0 none, 1 the concept (default), 2 also the literal fix")
    sp.add_argument("--watch", action="append", default=[], metavar="NAME",
                    help="also record and draw this variable of your program, e.g. "
                    "Thermostat.temp (repeat or comma-separate)")
    add_export_args(sp)
    _labs_arg(sp)
    sp = sub.add_parser("get", help="copy a lab's task, starter and notebook into a working "
                        "folder")
    sp.add_argument("lab", metavar="LAB")
    sp.add_argument("dir", nargs="?", default=None, metavar="DIR",
                    help="working folder (default: ./LAB)")
    sp.add_argument("--force", action="store_true", help="overwrite files that are there")
    _labs_arg(sp)
    sp = sub.add_parser("audit", help="test the lab's rubric (instructors): its mistakes, "
                        "its correct variants and mutants of its solution")
    sp.add_argument("lab", metavar="LAB", help="lab id or lab folder")
    sp.add_argument("--mutants", type=int, default=60, metavar="N",
                    help="mutants of each solution at most (a seeded sample; default 60)")
    sp.add_argument("--seed", type=int, default=0, help="the sample's seed (default 0)")
    sp.add_argument("--jobs", "-j", type=int, default=None, help="mutants graded in parallel "
                    "(default: the number of cores)")
    sp.add_argument("--json", default=None, metavar="FILE", help="also write the report as "
                    "JSON")
    sp.add_argument("--min-score", type=float, default=None, metavar="X",
                    help="exit 1 when the mutation score is below X (e.g. 0.9), a mistake "
                    "exceeds its bound or a variant scores under 95 %%")
    _labs_arg(sp)
    sp = sub.add_parser("new", help="create a lab folder with a working example (instructors)")
    sp.add_argument("id", metavar="ID", help="lab id: lower-case words with dashes")
    sp.add_argument("--dir", default=None, help="parent folder (default: ./labs if it exists, "
                    "else .)")
    p.set_defaults(_lab_parser=p)


@command("lab", add_args=_lab_args)
def cmd_lab(ns: argparse.Namespace) -> int:
    action = getattr(ns, "lab_cmd", None)
    if action == "list":
        return lab_list(ns)
    if action == "show":
        return lab_show(ns)
    if action == "check":
        return lab_check(ns)
    if action == "get":
        return lab_get(ns)
    if action == "new":
        return lab_new(ns)
    if action == "audit":
        return lab_audit(ns)
    ns._lab_parser.print_help()
    return 2


def lab_audit(ns: argparse.Namespace) -> int:
    import json

    from .audit import audit
    from .lab import load_lab, require_hidden

    if ns.mutants < 0:
        raise grade_error("PLC5026", "--mutants must be 0 or more")
    lab = load_lab(ns.lab, ns.labs, deep=True)
    require_hidden(lab, use="lab audit")
    jobs = ns.jobs if ns.jobs is not None else (os.cpu_count() or 1)
    report = audit(lab, limit=ns.mutants, seed=ns.seed, jobs=max(1, jobs))
    print(report.text())
    if ns.json:
        Path(ns.json).write_text(json.dumps(report.to_json(), indent=2) + "\n",
                                 encoding="utf-8")
    if ns.min_score is not None and (report.mutation_score < ns.min_score
                                     or not report.mistakes_ok or not report.variants_ok):
        return 1
    return 0


def lab_list(ns: argparse.Namespace) -> int:
    from plclab.i18n import tr
    from plclab.i18n_labs import lab_texts

    from .lab import LEVELS, list_labs, load_lab, repo_labs_dir

    own = repo_labs_dir().resolve()
    head = (tr("lab"), tr("level"), tr("chapters"), tr("plant"), tr("languages"), tr("points"),
            tr("title"))
    labs, broken = [], []
    for p in list_labs(ns.labs):
        try:
            labs.append((load_lab(p), p))
        except Exception as e:  # noqa: BLE001 - show the broken lab, go on
            broken.append((p.name, "?", "", "?", "?", "?", f"(broken: {e})"))
    # easiest first (labs without a level last), then by points: the path through the course
    labs.sort(key=lambda lp: (lp[0].level or 99, lp[0].max_score, lp[0].id))
    rows = [head]
    for k, (lab, p) in enumerate(labs):
        where = "" if p.parent.resolve() == own else f"  [{p}]"
        start = tr("  <- start here") if k == 0 and lab.level == 1 else ""
        title = lab_texts(lab).get("title") or lab.title
        rows.append((lab.id, tr(LEVELS[lab.level]) if lab.level in LEVELS else "-",
                     ",".join(map(str, lab.chapters)), lab.plant, ",".join(lab.languages),
                     f"{lab.max_score:g}", title + where + start))
    rows += broken
    widths = [max(len(r[i]) for r in rows) for i in range(6)]
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r[:6], widths, strict=True)) + "  " + r[6])
    return 0


def show_text(lab) -> str:
    """What ``plclab lab show`` prints: the task summary and the I/O table, in the language
    chosen (``lab.<lang>.toml``, ADR 0063; English where a text is missing)."""
    from plclab.i18n import tr
    from plclab.i18n_labs import (
        criterion_text,
        io_table_markdown,
        lab_text,
        lab_texts,
        scenario_text,
    )
    from plclab.sim import format_duration

    texts = lab_texts(lab)
    lines = [f"# {lab_text(texts, 'title', lab.title)}", ""]
    if lab.summary:
        lines += [lab_text(texts, "summary", lab.summary), ""]
    if lab.goals:
        lines += [tr("Learning goals:"), ""]
        lines += [f"- {g}" for g in lab_text(texts, "goals", lab.goals)] + [""]
    lines += [tr("Plant: `{plant}` (`plclab plants {plant}`); scan {scan}; languages: "
                 "{languages}; time limit {limit} s.", plant=lab.plant, scan=lab.scan,
                 languages=", ".join(lab.languages), limit=f"{lab.time_limit:g}"), ""]
    lines += [f"## {tr('I/O table')}", "", io_table_markdown(lab), ""]
    lines += [f"## {tr('Scenarios')}", ""]
    for s in lab.scenarios:
        pts = f"{sum(c.points for c in lab.criteria_for(s.name)):g}"
        if s.visible:
            lines.append(tr("- `{name}` ({duration}, {points} points): {description}",
                            name=s.name, duration=format_duration(s.duration), points=pts,
                            description=scenario_text(texts, s.name, s.description)))
        else:
            lines.append(tr("- `{name}` (hidden, {points} points)", name=s.name, points=pts))
    lines += ["", f"## {tr('Criteria')}", ""]
    for c in lab.criteria:
        vis = [s for s in c.scenarios if lab.scenario(s).visible]
        where = ", ".join(vis) if vis else tr("hidden scenarios")
        desc = criterion_text(texts, c.name, "description", c.description)
        lines.append(tr("- {name} ({points} points each, in {where})", points=f"{c.points:g}",
                        name=criterion_text(texts, c.name, "name", c.name), where=where)
                     + (f": {desc}" if desc else ""))
    lines += ["", tr("Total: {points} points. Check your program with "
                     "`plclab lab check {lab} FILE...`.", points=f"{lab.max_score:g}",
                     lab=lab.id)]
    return "\n".join(lines)


def update_readmes(lab) -> list[str]:
    """Rewrite the generated blocks (the I/O table, the criteria table) of the lab's
    ``README.md`` and of each ``README.<lang>.md`` from ``lab.toml`` and ``lab.<lang>.toml``;
    the lines to print."""
    from plclab.i18n import LANGUAGES, SOURCE
    from plclab.i18n_labs import criteria_table_markdown, io_table_markdown, tr_in

    from .gradescope import write_atomic

    out = []
    for lang in LANGUAGES:
        path = lab.path / ("README.md" if lang == SOURCE else f"README.{lang}.md")
        if lang != SOURCE and not path.is_file():
            continue
        text = path.read_text(encoding="utf-8") if path.is_file() else f"# {lab.title}\n"
        io = io_table_markdown(lab, lang)
        if readme_table(text) is not None:
            text = replace_block(text, README_START, README_END, io)
        else:
            text = (text.rstrip() + f"\n\n## {tr_in(lang, 'I/O table')}\n\n"
                    f"{README_START}\n{io}\n{README_END}\n")
        done = "I/O table"
        if readme_table(text, CRITERIA_START, CRITERIA_END) is not None:
            text = replace_block(text, CRITERIA_START, CRITERIA_END,
                                  criteria_table_markdown(lab, lang))
            done += " and criteria table"
        write_atomic(path, text)
        out.append(f"{path}: {done} updated")
    return out


def lab_show(ns: argparse.Namespace) -> int:
    from plclab.i18n import tr
    from plclab.i18n_labs import readme_path

    from .lab import load_lab

    lab = load_lab(ns.lab, ns.labs)
    if ns.update_readme:
        for line in update_readmes(lab):
            print(line)
        return 0
    print(show_text(lab))
    readme = readme_path(lab.path)
    if readme.is_file():
        print("\n" + tr("The task: {path}", path=readme))
    return 0


def lab_check(ns: argparse.Namespace) -> int:
    """A student's run of the visible scenarios, in a child process with the lab's time and
    memory limits, exactly as ``plclab grade`` runs it; exports run the program again here."""
    import shutil
    import tempfile

    from .engine import grade_sources, read_submission
    from .feedback import render_feedback
    from .grader import Grader
    from .gradescope import write_atomic
    from .lab import hidden_note, load_lab

    if ns.hint not in (0, 1, 2):
        raise grade_error("PLC5054", f"--hint {ns.hint}: write --hint 0 (no hints), 1 (the "
                          "concept, the default) or 2 (also the literal fix)")
    lab = load_lab(ns.lab, ns.labs)
    sources: list[tuple[str, str]] = []
    for f in ns.files:
        if not Path(f).exists():
            raise grade_error("PLC5021", f"{f}: no such file or folder")
        got, _ = read_submission(f)
        sources += got
    lab.student_watch = [w.strip() for item in ns.watch for w in item.split(",") if w.strip()]
    scen = [ns.scenario] if ns.scenario else None
    if scen and not lab.scenario(ns.scenario).visible and not ns.hidden:
        raise grade_error("PLC5026", f"scenario '{ns.scenario}' is hidden; it runs when your "
                          "work is graded")
    names = scen or [s.name for s in lab.scenarios if s.visible or ns.hidden]
    if ns.hidden and hidden_note(lab):  # the student copy: not silently without them
        print(hidden_note(lab))
    for line in lint_lines(lab, sources):
        print(line)
    out = fresh_output_dir(Path(ns.out)) if ns.out and not ns.no_media else None
    work = Path(tempfile.mkdtemp(prefix="plclab-check-"))
    try:
        grader = Grader(lab, work, jobs=1, media=out is not None, scenarios=names,
                        direct=True)  # one child: no forkserver (ADR 0057)
        res = grader.grade_one(sources)
        if out is not None:
            for f in (work / "check").iterdir():
                if f.suffix in (".png", ".rrd"):
                    shutil.move(str(f), out / f.name)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    res = res.result
    from plclab.i18n_labs import localize_result

    shown, fixes = localize_result(res, lab)
    text = render_feedback(shown, instructor=ns.hidden, hint_level=ns.hint, fixes=fixes)
    if out is not None:
        write_atomic(out / FEEDBACK_MARK, text)
    print(text)
    wants_export = any(getattr(ns, k, None) for k in ("rrd", "vcd", "wavedrom", "png", "spawn"))
    if wants_export and res.status in ("timeout", "memory", "crash", "rejected"):
        from plclab.i18n import tr

        print(tr("no export: the program did not finish within the lab's limits ({status})",
                 status=res.status))
    elif wants_export:
        from plclab.viz.from_trace import run_exports

        # within the limits above, so running it again here is bounded
        again = grade_sources(lab, sources, scenarios=names, keep_traces=True)
        if again.traces:
            first = first_failure(lab, res.tests, again.traces)
            name = ns.scenario or (first.scenario if first else next(iter(again.traces)))
            if first is not None and ns.scenario and first.scenario != ns.scenario:
                first = None
            student_picture(lab, again, name, ns, first)
            ns.cursor = first.t_fail if first is not None else None  # --spawn: the failure
            from plclab.viz.layout import signal_labels

            ns.labels = signal_labels(lab.io, again.traces[name])  # PUMP %QX0.0
            if ns.png and first is not None:  # the failure, its criterion and limits
                print(failure_picture(lab, again.traces[name], first, ns))
                ns.png, ns.png_done = None, True
            if ns.rrd and not ns.spawn:  # one file per scenario, the first failure first
                from plclab.viz.from_trace import write_lab_rrd

                from .feedback import run_limits

                print(write_lab_rrd(lab, again, ns.rrd,  # with the counts of each run
                                    ", ".join(Path(f).name for f in ns.files), ns,
                                    limits=run_limits(lab)))
                ns.rrd = None
            for line in run_exports(again.traces[name], ns):
                print(line)
    if out is not None:
        from plclab.i18n import tr
        from plclab.i18n_labs import criterion_text, lab_texts

        print(tr("feedback with diagrams: {path}", path=out / FEEDBACK_MARK))
        first = first_failure(lab, res.tests, {t.scenario: None for t in res.tests})
        if first is not None and getattr(first, "diagram", None):
            when = (tr("at t = {t:num} s", t=f"{first.t_fail:.2f}") if first.t_fail is not None
                    else tr("over the run"))
            print(tr("first failure: {path} (scenario '{scenario}', criterion '{criterion}', "
                     "failed {when})", path=out / first.diagram, scenario=first.scenario,
                     criterion=criterion_text(lab_texts(lab), first.criterion, "name",
                                              first.criterion), when=when))
    elif any(not t.passed for t in res.tests) and not ns.no_media and not getattr(ns, "png_done",
                                                                                  False):
        from plclab.i18n import tr

        print(tr("timing diagrams of the failures: add --out DIR (or --png F for one scenario)"))
    from plclab.i18n import decimal, tr

    print(tr("score: {score}/{max_score}", score=decimal(f"{res.score:g}"),
             max_score=decimal(f"{res.max_score:g}")))
    return 0


def lab_get(ns: argparse.Namespace) -> int:
    from .lab import get_lab_files

    dest = Path(ns.dir) if ns.dir else Path(Path(str(ns.lab)).name)
    files = get_lab_files(ns.lab, dest, ns.labs, force=ns.force)
    print(f"{dest}: " + ", ".join(f.name for f in files))
    starter = next((f for f in files if f.name.startswith("starter.")), None)
    if starter is not None:
        print(f"the task is in {dest / 'README.md'}; try: plclab lab check {ns.lab} {starter}")
    return 0


def first_failure(lab, tests, traces) -> Any:
    """The test every picture opens on: the first failing scenario in the lab's order (a
    criterion that really failed, not one 'not run'), and in it the criterion that failed
    first (one with a moment of failure before one failed over the whole run)."""
    from .feedback import real_failure

    order = {s.name: k for k, s in enumerate(lab.scenarios)}
    failed = [t for t in tests if real_failure(t) and t.scenario in traces]
    if not failed:
        return None
    crit_order = {c.name: k for k, c in enumerate(lab.criteria)}
    return min(failed, key=lambda t: (order.get(t.scenario, len(order)), t.t_fail is None,
                                      t.t_fail or 0.0, crit_order.get(t.criterion, 0)))


def failure_picture(lab, trace, test, ns: argparse.Namespace) -> str:
    """``lab check --png F`` after a failure: the diagram of the first failing scenario
    around the moment of its first failure, the failed criterion and its limits drawn, as
    ``--out`` draws it; returns the line that says what was drawn."""
    from plclab.i18n import tr
    from plclab.viz.from_trace import parse_window
    from plclab.viz.layout import signal_labels

    from .feedback import criterion_picture, diagram_names, picture_texts, timing_png

    crit = next(c for c in lab.criteria if c.name == test.criterion)
    if getattr(ns, "signals", None) and ns.signals != getattr(ns, "_default_signals", None):
        names = [trace.resolve(n.strip()) for n in ns.signals.split(",") if n.strip()]
    else:
        names = diagram_names(trace, lab, crit)
    t0, t1 = parse_window(ns.window)
    t0 = 0.0 if t0 is None else t0
    t1 = trace.t_end if t1 is None else t1
    words = picture_texts(lab, crit, test.scenario)
    markers = [(test.t_fail, words["marker"])] if test.t_fail is not None else []
    markers += [(e.time, tr("PLC fault")) for e in trace.events_of("plc_fault")
                if t0 <= e.time <= t1]
    timing_png(trace, names, Path(ns.png), t0, t1, markers, words["title"],
               signal_labels(lab.io, trace), drawing=criterion_picture(trace, crit, names),
               caption=words["caption"], keep=words["keep"])
    when = f"at t = {test.t_fail:.2f} s" if test.t_fail is not None else "over the run"
    return (f"timing diagram: {ns.png} (scenario '{test.scenario}', criterion "
            f"'{test.criterion}', failed {when})")


def student_picture(lab, res, scenario: str, ns: argparse.Namespace, first: Any = None
                    ) -> None:
    """Defaults of ``--png`` and the other exports in ``lab check``: the lab's diagram signals
    and the student's ``--watch`` variables, over the window around the scenario's first
    failure (``first``, the test every picture opens on) or the lab's diagram window from
    the start."""
    from .feedback import failure_window, judged_at_end

    trace = res.traces[scenario]
    if not getattr(ns, "signals", None):
        names = [n for n in [*lab.diagram_signals, *lab.student_watch] if n in trace]
        ns.signals = ",".join(names) or None
        ns._default_signals = ns.signals
    if not getattr(ns, "window", None):
        fails = [t.t_fail for t in res.tests if t.scenario == scenario and not t.passed
                 and t.t_fail is not None]
        if first is not None and first.scenario == scenario:
            fails = [first.t_fail] if first.t_fail is not None else []
            if first.t_fail is None or judged_at_end(first.t_fail, trace.t_end):
                # failed over the whole run, or judged at its end: show the whole run
                ns.window = f"0s..{trace.t_end:.3f}s"
                return
        crit = next((c for c in lab.criteria if first is not None
                     and c.name == first.criterion), None)
        width = (crit.window if crit is not None and crit.window else lab.diagram_window)
        t0, t1 = failure_window(min(fails) if fails else None, width, trace.t_end)
        if not fails:
            t0, t1 = 0.0, min(trace.t_end, lab.diagram_window)
        ns.window = f"{t0:.3f}s..{t1:.3f}s"


def lint_lines(lab, sources: list[tuple[str, str]]) -> list[str]:
    """The beginner warnings (PLC0210-PLC0216, the lab's I/O table included) that ``lab
    check`` prints before it runs the program; none when the program does not compile (the
    feedback shows those errors)."""
    from plclab.project import check_sources

    _, diags = check_sources(sources, lab.dialect, lint=True, io_table=lab.io)
    from plclab.i18n import tr

    found = [d.render() for d in diags if d.code.startswith("PLC021")]
    return ([tr("{n} warning(s) about your program:", n=len(found)), *found, ""] if found
            else [])


FEEDBACK_MARK = "feedback.md"
"""The file that makes a folder one of ``lab check --out``'s, which a new run may replace."""


def fresh_output_dir(out: Path) -> Path:
    """An empty *out* for this run: a folder an earlier run wrote (it holds feedback.md) is
    replaced, so no diagram of a criterion that now passes stays; any other folder with
    files in it is refused (PLC5051), so --out never deletes someone's work."""
    import shutil

    if out.exists() and not out.is_dir():
        raise grade_error("PLC5051", f"--out {out}: that is a file; give a folder")
    if out.is_dir() and any(out.iterdir()):
        if not (out / FEEDBACK_MARK).is_file():
            raise grade_error("PLC5051", f"--out {out}: the folder holds other files; give a "
                              "new or empty folder (a run replaces its folder)")
        try:
            shutil.rmtree(out)
        except OSError as e:
            raise grade_error("PLC5051", f"--out {out}: cannot replace it ({e.strerror or e})"
                              ) from None
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / FEEDBACK_MARK).write_text("", encoding="utf-8")  # ours, even if this run stops
    except OSError as e:
        raise grade_error("PLC5051", f"--out {out}: cannot create it ({e.strerror or e})"
                          ) from None
    return out


def lab_new(ns: argparse.Namespace) -> int:
    from .scaffold import create_lab

    parent = Path(ns.dir) if ns.dir else (Path("labs") if Path("labs").is_dir() else Path("."))
    folder = create_lab(ns.id, parent)
    print(f"created {folder}: lab.toml, README.md, starter.st, solution/, mistakes/, checks.py")
    print(f"try it: plclab lab check {folder} {folder / 'solution' / 'solution.st'}")
    return 0
