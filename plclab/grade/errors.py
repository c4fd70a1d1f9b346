"""Error codes of the labs and the autograder (PLC5001-PLC5099).

Every problem in a lab file is a :class:`~plclab.errors.PlcError` whose message names the key
and says what to write; every problem of a submission (no source, a language the lab does not
allow, a time or memory limit, a crash of the worker) becomes feedback with one of these codes.

>>> str(grade_error("PLC5002", "unknown key 'titel'"))
'error PLC5002: unknown key \\'titel\\''
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

from plclab.errors import Location, PlcError

CODES: dict[str, tuple[str, str]] = {
    # lab files
    "PLC5001": ("lab file cannot be read", "The lab folder has no lab.toml, or it is not valid "
                "TOML (the message gives the line), or a file it names is missing."),
    "PLC5002": ("unknown key", "A key of lab.toml is not one the lab format knows (see "
                "docs/labs.md); the message suggests the closest."),
    "PLC5003": ("missing key", "A required key of lab.toml is missing (title, plant, io, "
                "scenario, criterion...)."),
    "PLC5004": ("bad value", "A key of lab.toml has the wrong type or an impossible value "
                "(points must be > 0, a duration like \"30s\", languages from st/il/ld/xml...)."),
    "PLC5005": ("unknown plant or parameter", "The plant is not one of `plclab plants`, or a "
                "plant parameter is unknown."),
    "PLC5006": ("bad wiring", "The lab's wiring (inline rows or a wiring file) has a problem; "
                "the message repeats the wiring error (PLC400x)."),
    "PLC5007": ("I/O table and wiring disagree", "Every wiring row must appear in the [[io]] "
                "table with the same address, and every %I/%Q address of the table must be "
                "wired."),
    "PLC5008": ("bad scenario", "A [[scenario]] has a bad action, time, fault or signal."),
    "PLC5009": ("bad criterion", "A [[criterion]] names an unknown check, misses a parameter, "
                "has a bad condition or refers to an unknown scenario or signal."),
    "PLC5010": ("python check not found or failing", "`python = \"module:function\"` names a "
                "file module.py in the lab folder and a function in it taking the trace."),
    "PLC5011": ("duplicate name", "Two scenarios or two criteria have the same name."),
    # finding things
    "PLC5020": ("unknown lab", "No lab with that id in the repository's labs/ folder, in "
                "--labs DIR or in PLCLAB_LABS; `plclab lab list` lists them."),
    "PLC5021": ("no source files", "A submission (a file or a folder) holds no .st, .il, .ld "
                "or .xml file."),
    "PLC5022": ("language not allowed", "The lab allows only some languages (lab.toml "
                "`languages`)."),
    "PLC5023": ("time limit exceeded", "The submission ran longer than the wall-clock limit "
                "and was stopped. A loop that never ends inside one scan is caught by the "
                "watchdog (PLC2003); a scan that is merely very slow is caught here."),
    "PLC5024": ("memory limit exceeded", "The submission needed more memory than allowed "
                "(huge arrays?)."),
    "PLC5025": ("grading process crashed", "The process grading this submission ended "
                "without a result; the submission scores what it earned before."),
    "PLC5026": ("bad grading option", "A command-line option or argument of `plclab grade` / "
                "`plclab lab` is wrong."),
    "PLC5027": ("cannot create the lab", "`plclab lab new ID`: the id is not a lower-case "
                "name with dashes, or the folder exists."),
    "PLC5028": ("scenario cannot run", "The program and the lab's wiring do not fit (e.g. an "
                "address declared with another type), or the scenario failed to start."),
}
"""Code -> (title, explanation)."""


def grade_error(code: str, message: str, location: Location | None = None) -> PlcError:
    """A :class:`PlcError` with a code from :data:`CODES`."""
    assert code in CODES, code
    return PlcError(code, message, location)


def did_you_mean(name: str, options: Iterable[str]) -> str:
    """`` Did you mean 'x'?`` or an empty string."""
    close = difflib.get_close_matches(str(name), list(options), n=1, cutoff=0.6)
    return f" Did you mean '{close[0]}'?" if close else ""


def explain(code: str) -> str:
    """``PLC5001: title`` and the explanation (KeyError for other codes)."""
    title, text = CODES[code.upper()]
    return f"{code.upper()}: {title}\n\n{text}"
