"""Labs: ``labs/<id>/lab.toml`` read, checked strictly, and found by id.

A lab folder holds ``lab.toml`` (the spec: plant, wiring, I/O table, scenarios, criteria),
``README.md`` (the task as a student reads it), ``starter.<ext>``, ``solution/`` and
``mistakes/``. See ``docs/labs.md`` for every key.

Every problem of a lab file is a :class:`~plclab.errors.PlcError` with a code PLC5001..PLC5011,
a message that names the key and says what to write, and the ``lab.toml:line:col`` where the key
is.

For example::

    lab = load_lab("tank-two-position")
    lab.title, [s.name for s in lab.scenarios]
"""
from __future__ import annotations

import hashlib
import os
import re
import tomllib
from collections.abc import Iterable
from pathlib import Path

from plclab.errors import Location, PlcError

from .errors import did_you_mean, grade_error
from .lab_reader import LabReader, parse_memory
from .lab_spec import (
    LANGUAGES,
    LEVELS,
    SOURCE_EXTS,
    CriterionSpec,
    IoRow,
    Lab,
    MistakeSpec,
    ScenarioSpec,
)

__all__ = [  # the model (lab_spec) and parse_memory (lab_reader) are read from here too
    "LANGUAGES", "LEVELS", "SOURCE_EXTS", "CriterionSpec", "IoRow", "Lab", "MistakeSpec",
    "ScenarioSpec", "find_lab", "get_lab_files", "hidden_note", "lab_dirs", "lacks", "list_labs",
    "load_lab", "parse_memory", "repo_labs_dir", "require_hidden", "stub_program", "validate_deep",
]


def repo_labs_dir() -> Path:
    """The labs that come with plclab: the installed student copy (``plclab/courseware/labs``)
    or, in a source checkout, the repository's ``labs/`` folder."""
    from .courseware import courseware_root

    return courseware_root() / "labs"


# ---------------------------------------------------------------------------- finding labs


def lab_dirs(extra: Iterable[str | os.PathLike] = ()) -> list[Path]:
    """Where labs are looked up: ``extra`` (``--labs``), ``PLCLAB_LABS``, plclab's own labs."""
    out = [Path(p) for p in extra if p]
    env = os.environ.get("PLCLAB_LABS", "")
    out += [Path(p) for p in env.split(os.pathsep) if p]
    out.append(repo_labs_dir())
    return out


def list_labs(extra: Iterable[str | os.PathLike] = ()) -> list[Path]:
    """Every lab folder (one holding a lab.toml) in the lookup path; first one of an id wins."""
    seen: dict[str, Path] = {}
    for d in lab_dirs(extra):
        if not d.is_dir():
            continue
        for sub in sorted(d.iterdir()):
            if (sub / "lab.toml").is_file() and sub.name not in seen:
                seen[sub.name] = sub
    return list(seen.values())


def find_lab(lab: str | os.PathLike, extra: Iterable[str | os.PathLike] = ()) -> Path:
    """The folder of a lab given by id or path (PLC5020 when there is none)."""
    p = Path(lab)
    if p.is_file() and p.name == "lab.toml":
        return p.parent
    if p.is_dir() and (p / "lab.toml").is_file():
        return p
    for d in lab_dirs(extra):  # an id first: `plclab lab get` made a folder of that name
        cand = d / str(lab)
        if p.name == str(lab) and (cand / "lab.toml").is_file():
            return cand
    if p.is_dir():
        raise grade_error("PLC5001", f"{p} has no lab.toml; a lab folder holds lab.toml, "
                          "README.md, a starter, solution/ and mistakes/")
    known = [x.name for x in list_labs(extra)]
    raise grade_error("PLC5020", f"no lab '{lab}'.{did_you_mean(str(lab), known)} Labs: "
                      f"{', '.join(known) or '(none)'}; give a lab id, a lab folder, or "
                      "--labs DIR")


def get_lab_files(lab: str | os.PathLike, dest: Path, extra: Iterable[str | os.PathLike] = (),
                  force: bool = False) -> list[Path]:
    """Copy a lab's student files (``README.md``, ``starter.*``, its notebook) into *dest*;
    never a solution, a mistake or a hidden scenario. PLC5050 when a file is there already
    (unless *force*)."""
    import shutil

    from plclab.i18n import SOURCE, language

    from .courseware import courseware_root

    folder = find_lab(lab, extra)
    lang = language()
    own = [] if lang == SOURCE else [f"README.{lang}.md"]  # the task in the language too
    files = [folder / n for n in ["README.md", *own] if (folder / n).is_file()]
    files += sorted(p for p in folder.glob("starter.*") if p.suffix.lower() in SOURCE_EXTS)
    for nb in (folder.parent.parent / "notebooks", courseware_root() / "notebooks"):
        if (nb / f"{folder.name}.ipynb").is_file():
            files.append(nb / f"{folder.name}.ipynb")
            if lang != SOURCE and (nb / f"{folder.name}.{lang}.ipynb").is_file():
                files.append(nb / f"{folder.name}.{lang}.ipynb")
            break
    there = [dest / f.name for f in files if (dest / f.name).exists()]
    if there and not force:
        raise grade_error("PLC5050", f"{there[0]} exists already: give another folder "
                          "(plclab lab get LAB DIR) or --force to overwrite it")
    try:
        dest.mkdir(parents=True, exist_ok=True)
        return [Path(shutil.copyfile(f, dest / f.name)) for f in files]
    except OSError as e:
        raise grade_error("PLC5050", f"cannot write into {dest}: {e.strerror or e}") from None


def require_hidden(lab: Lab, visible_only: bool = False, use: str = "grade") -> None:
    """PLC5072 when ``lab`` is the student copy shipped with plclab (no hidden scenarios) and
    ``use`` needs them: ``grade`` and the worker (unless ``visible_only``), ``grade-bundle``
    and ``lab audit`` (always). The one place this check and its message live (ADR 0040)."""
    if not lab.student_copy or visible_only:
        return
    how = {"grade": f"plclab grade path/to/labs/{lab.id} SUBMISSIONS (or --labs DIR), or pass "
                    "--visible-only to grade on the visible scenarios alone",
           "grade-bundle": f"plclab grade-bundle path/to/labs/{lab.id}",
           "lab audit": f"plclab lab audit path/to/labs/{lab.id}"}[use]
    raise grade_error("PLC5072", f"{lab.path} is the student copy of {lab.id} that ships with "
                      f"plclab: {lacks(lab)}. Use the instructor's lab folder (labs/{lab.id} of "
                      f"the plclab repository, or your own): {how}")


def lacks(lab: Lab) -> str:
    """What the student copy of a lab lacks, counted: "its 2 hidden scenarios, solutions and
    mistakes are not in it" ("" for an instructor's lab)."""
    if lab.withheld is None:
        return ""
    n = lab.withheld
    what = (f"its {n} hidden scenario{'s' if n != 1 else ''}, solutions and mistakes are"
            if n else "it has no hidden scenario, but its solutions and mistakes are")
    return f"{what} not in it"


def hidden_note(lab: Lab) -> str | None:
    """``lab check --hidden`` with the student copy of a lab: the line saying that it runs
    without the hidden scenarios this copy lacks (None when nothing is missing)."""
    if not lab.withheld:
        return None
    from plclab.i18n import tr

    if lab.withheld == 1:
        return tr("note: {path} is the student copy of {lab} that ships with plclab: its {n} "
                  "hidden scenario is not in it, so --hidden runs the visible ones only. For "
                  "every scenario use the instructor's lab folder (labs/{lab} of the plclab "
                  "repository, or your own; --labs DIR)", path=lab.path, lab=lab.id, n=1)
    return tr("note: {path} is the student copy of {lab} that ships with plclab: its {n} "
              "hidden scenarios are not in it, so --hidden runs the visible ones only. For "
              "every scenario use the instructor's lab folder (labs/{lab} of the plclab "
              "repository, or your own; --labs DIR)", path=lab.path, lab=lab.id,
              n=lab.withheld)

# ---------------------------------------------------------------------------- loading


def load_lab(lab: str | os.PathLike, extra: Iterable[str | os.PathLike] = (),
             deep: bool = False) -> Lab:
    """Read and check a lab (by id or path). ``deep=True`` also binds every scenario to a
    simulation (wiring against the plant, actions and faults), which costs a compile."""
    folder = find_lab(lab, extra)
    path = folder / "lab.toml"
    try:
        raw = path.read_bytes()
        text = raw.decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as e:
        raise grade_error("PLC5001", f"{path}: cannot be read ({e}); save it as UTF-8") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        m = re.search(r"line (\d+), column (\d+)", str(e))
        loc = Location(str(path), int(m.group(1)), int(m.group(2))) if m else Location(str(path))
        raise grade_error("PLC5001", f"not valid TOML: {e}", loc) from None
    lab_obj = LabReader(folder, path, text, data).build()
    h = hashlib.sha256(raw)
    for extra_file in sorted(folder.glob("*.py")):
        h.update(extra_file.read_bytes())
    if lab_obj.wiring_source and Path(lab_obj.wiring_source).is_file():
        h.update(Path(lab_obj.wiring_source).read_bytes())
    lab_obj.hash = h.hexdigest()[:16]
    if deep:
        validate_deep(lab_obj)
    return lab_obj


# ---------------------------------------------------------------------------- deep check


def stub_program(lab: Lab) -> str:
    """An ST program that declares every I/O table address (to bind scenarios without a
    student program)."""
    lines = ["PROGRAM LabIoCheck", "VAR"]
    for i, r in enumerate(lab.io):
        lines.append(f"    io{i} AT {r.address} : {r.type};")
    lines += ["END_VAR", "END_PROGRAM"]
    return "\n".join(lines)


def validate_deep(lab: Lab) -> None:
    """Bind every scenario to a simulation of a stub program: checks the wiring against the
    plant and the program's addresses, the actions' targets and faults (PLC5006/PLC5008)."""
    import plclab
    from plclab.sim import Simulation

    try:
        plc_text = stub_program(lab)
        plclab.loads(plc_text, "labcheck.st", cycle_time=lab.scan)
    except PlcError as e:
        raise grade_error("PLC5007", f"{lab.id}: the I/O table does not make a valid program: "
                          f"{e}", Location(str(lab.path / "lab.toml"))) from None
    for sc in lab.scenarios:
        plc = plclab.loads(plc_text, "labcheck.st", cycle_time=lab.scan,
                           task_intervals=sc.task_intervals)
        acts = [a for a in sc.actions if not any(k in a for k in ("var", "force", "unforce"))]
        spec = ScenarioSpec(sc.name, sc.duration, sc.description, sc.seed, sc.visible,
                            sc.plant_params, acts, sc.until, [])
        watch = [w for w in lab.all_watch(sc) if w.startswith("%")]
        try:
            Simulation(plc, lab.plant, lab.wiring, seed=sc.seed, scenario=spec.scenario(),
                       watch=watch, plant_params={**lab.plant_params, **sc.plant_params})
        except PlcError as e:
            code = "PLC5006" if e.code in ("PLC4002", "PLC4003", "PLC4004", "PLC4005", "PLC4006",
                                           "PLC4007", "PLC4008") else "PLC5008"
            raise grade_error(code, f"scenario '{sc.name}': {e.message} ({e.code})",
                              Location(str(lab.path / "lab.toml"))) from None
