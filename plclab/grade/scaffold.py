"""``plclab lab new ID``: a new lab folder with a working example to edit.

The example is a small tank lab: the I/O table, two scenarios (one hidden), criteria from the
library and one Python check (``checks.py``), a starter, a reference solution and a typical
mistake. ``plclab lab check <folder> <folder>/solution/solution.st`` scores 100 % right away.
"""

from __future__ import annotations

import re
from pathlib import Path

from .errors import grade_error

LAB_TOML = '''# {id}: a new lab. Every key is explained in docs/labs.md.
title = "{title}"
summary = """Keep the level of the tank between the low switch LS1 and the high switch LS2."""
goals = ["read switches", "write a hysteresis with a seal-in"]
plant = "tank"                              # plclab plants: the plants and their signals
plant_params = {{ area = 0.2 }}               # a small tank: fast scenarios
scan = "10ms"
languages = ["st", "il", "ld", "xml"]
time_limit = "30s"                          # wall clock per submission
memory_limit = "1.5GB"
wiring = [
  {{ plc = "%IX0.0", signal = "LS1", module = "di", filter_ms = 3.0, description = "low level switch" }},
  {{ plc = "%IX0.1", signal = "LS2", module = "di", filter_ms = 3.0, description = "high level switch" }},
  {{ plc = "%QX0.0", signal = "PUMP", module = "do", kind = "relay", description = "pump contactor" }},
]
diagram = {{ signals = ["LEVEL", "LS1", "LS2", "PUMP"], window = "60s" }}

[[io]]
name = "LS1"
address = "%IX0.0"
type = "BOOL"
description = "low level switch: TRUE while the liquid is at or above it"

[[io]]
name = "LS2"
address = "%IX0.1"
type = "BOOL"
description = "high level switch: TRUE while the liquid is at or above it"

[[io]]
name = "PUMP"
address = "%QX0.0"
type = "BOOL"
description = "pump contactor: TRUE = the pump runs"

[[scenario]]
name = "normal"
description = "an almost empty tank, full demand"
duration = "4min"
seed = 1

[[scenario]]
name = "half-valve"
description = "the consumers close the valve to 50 %"
duration = "4min"
seed = 2
visible = false
actions = [ {{ at = "30s", set = "VALVE", value = 50 }} ]

[[criterion]]
name = "pump starts below LS1"
scenarios = ["normal", "half-valve"]
check = "within"
trigger = "not LS1"
response = "PUMP"
time = "1s"
points = 1
message = "the pump does not start below LS1"

[[criterion]]
name = "no overflow"
scenarios = ["normal", "half-valve"]
requires = ["pump starts below LS1"]
check = "never"
condition = "LEVEL >= 1.75"
points = 2
message = "the tank overflows"

[[criterion]]
name = "no chatter"
scenarios = ["normal", "half-valve"]
requires = ["pump starts below LS1"]
check = "no_chatter"
signal = "PUMP"
window = "20s"
points = 2
message = "the pump chatters"
hint = "Keep the pump on from LS1 up to LS2 (hysteresis)."

[[criterion]]
name = "full cycles"
scenarios = ["normal"]
requires = ["pump starts below LS1"]
python = "checks:full_cycles"
params = {{ min_cycles = 1 }}
points = 2
message = "the pump never runs a full cycle from LS1 to LS2"
'''

CHECKS_PY = '''"""Python checks of this lab: ``python = "checks:full_cycles"`` in lab.toml.

A check takes the trace (plclab.trace.Trace) and the criterion's params, and returns a bool,
(passed, message[, t_fail[, signals]]) or a plclab.grade.criteria.Verdict.
"""


def full_cycles(trace, min_cycles=1):
    """The pump ran from below LS1 up to LS2 at least ``min_cycles`` times."""
    pump = trace["PUMP"]
    level = trace["LEVEL"]
    cycles = 0
    start_level = None
    for i in range(1, len(pump)):
        if pump[i] and not pump[i - 1]:
            start_level = level[i]
        elif not pump[i] and pump[i - 1] and start_level is not None:
            if start_level <= 0.55 and level[i] >= 1.45:
                cycles += 1
            start_level = None
    ok = cycles >= min_cycles
    return ok, f"{cycles} full pump cycle(s) from LS1 to LS2 (at least {min_cycles})", None, [
        "LEVEL", "PUMP"]
'''

SOLUTION = '''(* Reference solution: two-position control with hysteresis LS1..LS2. *)
PROGRAM TankLevel
VAR
    LS1  AT %IX0.0 : BOOL;
    LS2  AT %IX0.1 : BOOL;
    PUMP AT %QX0.0 : BOOL;
END_VAR
PUMP := ((NOT LS1) OR PUMP) AND (NOT LS2);
END_PROGRAM
'''

MISTAKE = '''(* expect: chatter *)
(* Typical mistake: the pump follows LS1 alone and chatters around the low switch. *)
PROGRAM TankLevel
VAR
    LS1  AT %IX0.0 : BOOL;
    LS2  AT %IX0.1 : BOOL;
    PUMP AT %QX0.0 : BOOL;
END_VAR
PUMP := NOT LS1;
END_PROGRAM
'''

STARTER = '''(* Write the logic that drives PUMP from LS1 and LS2. *)
PROGRAM TankLevel
VAR
    LS1  AT %IX0.0 : BOOL;   (* low level switch *)
    LS2  AT %IX0.1 : BOOL;   (* high level switch *)
    PUMP AT %QX0.0 : BOOL;   (* pump contactor *)
END_VAR
(* your code here *)
END_PROGRAM
'''

README = '''# {title}

The task as students read it. Describe the plant, what the program must do, and how it is
graded. The I/O table below is generated from lab.toml: `plclab lab show {id} --update-readme`.

## I/O table

{table}
'''


def create_lab(lab_id: str, parent: str | Path) -> Path:
    """Create ``parent/lab_id`` with the example lab; returns the folder."""
    if not re.match(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$", lab_id):
        raise grade_error("PLC5027", f"'{lab_id}' is not a lab id: use lower-case words joined "
                          "by dashes, e.g. tank-two-position")
    folder = Path(parent) / lab_id
    if folder.exists():
        raise grade_error("PLC5027", f"{folder} exists already; choose another id or remove it")
    title = lab_id.replace("-", " ").capitalize()
    (folder / "solution").mkdir(parents=True)
    (folder / "mistakes").mkdir()
    (folder / "lab.toml").write_text(LAB_TOML.format(id=lab_id, title=title), encoding="utf-8")
    (folder / "checks.py").write_text(CHECKS_PY, encoding="utf-8")
    (folder / "solution" / "solution.st").write_text(SOLUTION, encoding="utf-8")
    (folder / "mistakes" / "follows_ls1.st").write_text(MISTAKE, encoding="utf-8")
    (folder / "starter.st").write_text(STARTER, encoding="utf-8")
    from .commands import README_END, README_START
    from .lab import load_lab

    lab = load_lab(folder)
    table = f"{README_START}\n{lab.io_table_markdown()}\n{README_END}"
    (folder / "README.md").write_text(README.format(title=title, id=lab_id, table=table),
                                      encoding="utf-8")
    return folder
