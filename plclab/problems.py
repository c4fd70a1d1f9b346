"""The catalogue of diagnostic codes: every code plclab can report, with what it means.

Codes are stable: a code is never reused for another problem. ``plclab explain CODE`` prints
an entry. PLC0xxx are compile-time diagnostics, PLC02xx warnings, PLC2xxx run-time faults,
PLC3xxx API/command-line misuse, PLC9xxx configuration of I/O modules and internal errors.
"""

from __future__ import annotations

PROBLEMS: dict[str, tuple[str, str]] = {
    "PLC0001": ("unexpected character", "A character that is not part of ST appeared outside a "
                "comment or string. Remove it."),
    "PLC0002": ("unclosed comment or pragma", "A '(*', '/*' or '{' is never closed. Comments "
                "nest in ST, so every '(*' needs its own '*)'."),
    "PLC0003": ("bad string", "A string is not closed on its line or has an unknown '$' escape."),
    "PLC0004": ("bad number", "A based literal has digits its base does not allow (2#102)."),
    "PLC0005": ("bad time or date literal", "Write durations as T#1h2m3s4ms and dates as "
                "D#2024-01-31, TOD#14:32:07, DT#2024-01-31-14:32:07."),
    "PLC0006": ("bad identifier", "Identifiers start with a letter or '_' and go on with letters, "
                "digits and '_', never two '_' in a row (IEC 61131-3; CODESYS keeps '__' for its "
                "own generated names). Rename it, e.g. __x -> _x or my__var -> my_var."),
    "PLC0010": ("syntax error", "The parser expected something else here; the message says what."),
    "PLC0011": ("misspelled keyword", "A word looks like a keyword (END_WHILLE, ELSEIF); the "
                "message suggests the right spelling."),
    "PLC0012": ("'==' or '!=' used", "ST compares with '=' and '<>'; ':=' assigns."),
    "PLC0013": ("'=' used to assign", "In ST, '=' compares. Assign with ':='."),
    "PLC0014": ("':=' in a condition", "A condition compares with '='; ':=' assigns."),
    "PLC0100": ("undeclared name", "Declare the variable in a VAR section (or fix its spelling)."),
    "PLC0101": ("declared twice", "Two declarations have the same name in one scope."),
    "PLC0102": ("unknown type", "The type name is not elementary, declared with TYPE, or a "
                "function block."),
    "PLC0103": ("type mismatch", "The value's type cannot be stored in the target."),
    "PLC0104": ("operator not defined for these types", "E.g. '+' on strings, AND on INT and "
                "BOOL, or comparing a TIME with an INT."),
    "PLC0105": ("cannot be written", "Constants, physical inputs (%I) and FB outputs seen from "
                "outside cannot be assigned."),
    "PLC0106": ("not callable", "Only functions, function block instances and (in tests) "
                "programs can be called."),
    "PLC0107": ("wrong arguments", "Unknown parameter name, too many arguments, an output passed "
                "with ':=' or an input with '=>', or a VAR_IN_OUT left unconnected."),
    "PLC0108": ("condition is not BOOL", "IF, WHILE and UNTIL need a BOOL condition."),
    "PLC0109": ("constant needed or out of range", "Array bounds, string lengths and subranges "
                "need constant integer expressions."),
    "PLC0110": ("recursion", "IEC 61131-3 forbids a POU calling itself, directly or not."),
    "PLC0111": ("literal out of range", "The literal does not fit the target type (INT is "
                "-32768..32767)."),
    "PLC0112": ("constant index out of bounds", "A constant array index is outside the declared "
                "range."),
    "PLC0113": ("bad FOR loop", "The FOR variable must be an integer not assigned in the body; "
                "the step must not be 0."),
    "PLC0114": ("EXIT or CONTINUE outside a loop", "They only make sense inside FOR, WHILE or "
                "REPEAT."),
    "PLC0115": ("bad CASE", "The selector must be an integer or enumeration; labels must be "
                "constants of its type and may not repeat."),
    "PLC0116": ("no such member", "The structure, function block or enumeration has no member "
                "with this name, or bit access is out of range."),
    "PLC0117": ("bad indexing", "Only arrays are indexed, with one integer index per dimension."),
    "PLC0118": ("narrowing conversion", "Storing a wider type in a narrower one needs an explicit "
                "*_TO_* conversion (e.g. DINT_TO_INT)."),
    "PLC0119": ("function result never assigned", "A function returns the value assigned to its "
                "name; without one it returns the default (0, FALSE, '')."),
    "PLC0120": ("bad located variable", "The AT address does not match the variable's size, or "
                "the variable is not in a PROGRAM or VAR_GLOBAL."),
    "PLC0121": ("internal variable of a function block", "From outside, only inputs and outputs "
                "of an instance are visible."),
    "PLC0122": ("defined in terms of itself", "Constants, enumeration values or types refer to "
                "each other in a circle (A := B; B := A); the message names the circle. Give one "
                "of them a value that does not depend on the others."),
    "PLC0123": ("an instance or structure contains itself", "A function block, program or "
                "structure holds an instance of itself, directly or through other blocks, "
                "structures or arrays; the message names the chain. Such data would be "
                "infinitely large: pass the other block as VAR_IN_OUT instead."),
    "PLC0124": ("data too large or nested too deeply", "The data of the program (globals, "
                "program instances and everything nested in them, counted as a PLC stores it) "
                "may take at most 16 MiB, and types may nest at most 32 levels; the message "
                "names the declarations that make it big. Use smaller arrays."),
    "PLC0125": ("number too large", "A REAL literal beyond LREAL's range (1.0E400), an integer "
                "literal of more than 100 digits, or a constant expression whose value no "
                "integer type holds. Use a smaller value."),
    "PLC0126": ("time or date out of range", "TIME holds -24d20h31m23s648ms..24d20h31m23s647ms "
                "(signed 32 bits of milliseconds; use LTIME for more), LTIME about +-106751 days, "
                "DATE and DT 1970-01-01..2106-02-07."),
    "PLC0127": ("address outside the process image", "The byte of a located variable or a direct "
                "address lies beyond the process image (1024 bytes by default, at most 65536), "
                "or a bit number is not 0..7. Use a smaller address or a larger image_size."),
    "PLC0128": ("too many errors", "A file gave more than 100 diagnostics; only the first are "
                "shown. Fix those (often the first error causes the others) and check again."),
    "PLC0129": ("bad task", "A TASK's INTERVAL must be a TIME constant between 0.1 ms and 1 day "
                "(e.g. T#10ms) and its PRIORITY an integer constant 0..31."),
    "PLC0130": ("unknown native block", "plclab's own library names a block that has no "
                "registered Python implementation (plclab/runtime/natives.py). This is a bug in "
                "plclab, not in your program: please report it."),
    "PLC0131": ("native pragma in a user file", "The {native ...} pragma binds a block to Python "
                "code and is reserved for plclab's own library. Remove it and write the body of "
                "your FUNCTION or FUNCTION_BLOCK in ST (or IL, LD)."),
    "PLC0140": ("IL current result type mismatch", "The operator cannot use the current result's "
                "type, or the store target has another type (e.g. ADD on BOOL, JMPC on INT)."),
    "PLC0141": ("unknown IL operator", "Not an IL operator or a function, or an ST statement "
                "inside an IL body."),
    "PLC0142": ("IL writes an input", "ST, S or R into a physical %I input or a VAR_INPUT of the "
                "POU itself."),
    "PLC0143": ("unbalanced deferred parentheses", "'AND(' never closed, ')' with nothing open, "
                "or JMP, CAL, RET or a label inside the parentheses."),
    "PLC0144": ("no current result", "Nothing is loaded here (at the start, or after CAL, JMP, "
                "RET or a label). Load a value with LD."),
    "PLC0145": ("unknown jump label", "A jump to a label that does not exist, or a jump or label "
                "not at the top level of the body."),
    "PLC0146": ("IL syntax", "Operand missing, extra or in parentheses; jump without a label."),
    "PLC0147": ("current result cannot reach label", "The ways into a label that uses the "
                "current result bring different or unknown types."),
    "PLC0160": ("broken wire", "A gap in the wire, a wire not connected on its left, a branch "
                "ending without a coil, or a junction that nothing feeds."),
    "PLC0161": ("coil not at the right rail", "An element after a coil, or a coil not wired to "
                "the drawn right rail."),
    "PLC0162": ("branch does not close", "A vertical line without '+' at one end, or a '|' "
                "crossing a wire."),
    "PLC0163": ("missing or misplaced variable name", "No name over a contact or coil, a name "
                "over nothing, or two names over one element."),
    "PLC0164": ("unknown ladder element", "[Q] or (Z), an unclosed '[' or '(', or a stray "
                "character on the wire."),
    "PLC0165": ("bad box", "Not a function block or function, an instance of another type, or a "
                "missing instance or operand."),
    "PLC0166": ("ladder layout", "Rails misaligned, tabs, rungs outside a POU body, or rungs "
                "mixed with ST."),
    "PLC0180": ("not a PLCopen XML project", "Malformed XML, the wrong root element or "
                "namespace (TC6 XML v2.01 expected), or a <!DOCTYPE>/<!ENTITY> declaration, "
                "which plclab refuses: remove it or export the project again."),
    "PLC0181": ("unsupported PLCopen element", "The message names the element and its localId "
                "(SFC, jumps, inOutVariable, negated or edge block pins, ...), or a network "
                "chains more than 100 function boxes: store an intermediate result in a "
                "variable."),
    "PLC0182": ("broken PLCopen connection", "A refLocalId to a missing element, a duplicate "
                "localId, a feedback loop, or a continuation without its connector."),
    "PLC0183": ("bad value in PLCopen XML", "Not an identifier, a missing type or returnType, a "
                "bad address or an unknown pouType."),
    "PLC0190": ("nested too deeply", "More than 2,000 levels of IF, CASE, FOR, WHILE or REPEAT "
                "inside each other, or an expression with more than 2,000 levels of parentheses, "
                "calls, indices or unary operators inside each other. Move inner blocks into a "
                "FUNCTION or FUNCTION_BLOCK, or compute parts of the expression into intermediate "
                "variables. Long chains (a + b + c + ..., AND/OR chains, CASE labels) have no "
                "limit."),
    "PLC0191": ("program too large to compile", "A part of the program is too large or too "
                "deeply nested for the compiler although it is within the documented limits "
                "(please report it with the program). Split the POU named in the message into "
                "smaller FUNCTIONs or FUNCTION_BLOCKs."),
    "PLC0200": ("unused variable", "A declared variable is never used (warning)."),
    "PLC0201": ("unreachable code", "Statements after RETURN, EXIT or CONTINUE never run "
                "(warning)."),
    "PLC0202": ("precision loss", "DINT/UDINT/LINT to REAL keeps only 24 bits (warning)."),
    "PLC0203": ("input written inside its block", "The caller overwrites inputs on every call "
                "(warning)."),
    "PLC0204": ("negating an unsigned value", "-x on USINT/UINT/... wraps around (warning)."),
    "PLC0205": ("a POU hides a library block", "A user POU has the name of a library block "
                "(e.g. RAMP); the program's own POU is used (warning)."),
    "PLC2001": ("division by zero", "Run time: check the divisor before dividing."),
    "PLC2002": ("index out of range", "Run time: an array index or MUX selector is outside the "
                "declared range."),
    "PLC2003": ("watchdog: scan overrun", "Run time: loops in one scan ran longer than the budget "
                "(like S7's 150 ms cycle limit). Inputs never change inside a scan, so a loop "
                "waiting for one never ends."),
    "PLC2004": ("subrange violation", "Run time: a value left its declared subrange."),
    "PLC2005": ("FOR step is zero", "Run time: FOR ... BY 0 never ends."),
    "PLC2006": ("invalid conversion", "Run time: NaN or infinity converted to an integer."),
    "PLC2007": ("calls nested too deeply", "Run time: the call depth exceeded the limit."),
    "PLC2008": ("numeric overflow", "Run time: a value became too large to represent."),
    "PLC2009": ("out of memory", "Run time: the program allocated too much memory."),
    "PLC2010": ("test assertion failed", "An ASSERT_* in a TEST block did not hold."),
    "PLC2020": ("negative shift count", "Run time: SHL, SHR, ROL and ROR shift by N >= 0 bits; "
                "check N before shifting (a count of the width or more gives 0 for SHL/SHR)."),
    "PLC3001": ("unknown variable path", "The name, member or index does not exist in the "
                "loaded program."),
    "PLC3002": ("bad value", "A value given from Python or the command line does not fit the "
                "variable's type."),
    "PLC3003": ("file problem", "A source file is missing, not UTF-8, or of an unknown kind."),
    "PLC3004": ("PLC in fault", "The PLC stopped on a fault; restart it."),
    "PLC3010": ("address beyond the process image", "A direct address (plc[\"%QX5000.0\"], a "
                "force, an AT declaration, a wiring row or a Modbus map) lies outside the process "
                "image (image_size bytes per area, default 1024: %IB0..%IB1023), or names bit 8 "
                "or more. Use a lower address or create the PLC with a larger image_size."),
    "PLC3011": ("bad cycle time or run length", "Cycle times and task intervals lie between "
                "0.1 ms and 1 day; run(seconds=...) needs a finite duration >= 0; scan(n) and "
                "run(cycles=n) a whole number; one call runs at most 100,000,000 scans (split "
                "longer runs)."),
    "PLC3012": ("bad PLC option", "image_size is 8..65536 bytes, watchdog a positive whole "
                "number, system_memory_byte and clock_memory_byte a %M byte inside the image."),
    "PLC4001": ("wiring or scenario file cannot be read",
                "The file is missing, is not UTF-8, or is not valid TOML. The message gives the "
                "parser's line and column."),
    "PLC4002": ("unknown plant signal",
                "A wiring row or a scenario names a signal the plant does not have. `plclab "
                "plants` lists every plant's signals."),
    "PLC4003": ("signal wired the wrong way",
                "Sensors and panel inputs go to PLC inputs (modules di, ai or direct to %I or a "
                "variable); actuators and lamps come from PLC outputs (do, ao or direct from %Q "
                "or a variable). A PLC output cannot drive a sensor or a panel input."),
    "PLC4004": ("bad PLC address or variable in a wiring row",
                "The address is not of the form %IX0.0 / %IW64 / %QX0.0 / %QW64, does not fit "
                "the module (bit modules need bits, analog modules words), lies beyond the "
                "process image, or the variable does not exist or has the wrong type."),
    "PLC4005": ("unknown I/O module or unknown key",
                "A wiring row needs plc, signal and module (di, do, ai, ao, direct); every other "
                "key must be a parameter of that module or description."),
    "PLC4006": ("bad value of a wiring parameter",
                "A module parameter has the wrong type or an impossible value (negative time, "
                "unknown signal range, lo == hi...)."),
    "PLC4007": ("wired twice",
                "Two rows write the same PLC input bits, or two rows drive the same plant "
                "actuator. Remove one of them."),
    "PLC4008": ("file made for another plant",
                "The wiring or scenario file says plant = '...' and that is not the plant being "
                "simulated."),
    "PLC4010": ("bad scenario action",
                "An action needs a time (at) and exactly one verb: press, set, ramp, var, force, "
                "unforce, fault, clear, io_fault, io_clear; the message lists the keys the verb "
                "takes."),
    "PLC4011": ("scenario target cannot be written",
                "The scenario may press or set panel inputs (buttons, switches, the environment) "
                "and PLC variables; sensors are computed by the plant and actuators are the "
                "PLC's."),
    "PLC4012": ("bad time or duration",
                "Write durations as 10ms, 1.5s, 90s, 10min, 1h, 2d, 1h30m, T#1m30s or a number of "
                "seconds; times must not be negative."),
    "PLC4013": ("bad condition",
                "Conditions are simple expressions on plant signals, PLC variables and t (the "
                "time in s): LEVEL > 1.9, RUN and SPEED >= 1400, not LS1 or t > 60. Python "
                "callables are accepted from Python."),
    "PLC4014": ("unknown fault",
                "The plant or the I/O module has no fault with that name; the message lists the "
                "valid ones."),
    "PLC4015": ("bad scenario value",
                "The value does not fit the signal (BOOL needs true/false, REAL a number) or the "
                "PLC variable."),
    "PLC4020": ("bad simulation set-up",
                "Unknown plant or plant parameter, a scan time that differs from the PLC's cycle, "
                "a dt that does not divide the scan into whole sub-steps, or a watch list naming "
                "something that cannot be recorded."),
    "PLC4021": ("unknown trace column or bad trace file",
                "The trace has no column of that name (trace.names lists them), or the file is "
                "not a trace saved by plclab."),
    "PLC4030": ("rerun recordings could not be joined",
                "Every scenario is written as its own recording and rerun's `rrd merge` joins "
                "them into one file; it failed (message attached). Write one scenario with "
                "--scenario NAME, or check that rerun-sdk's command line works (rerun --version)."),
    "PLC4031": ("inline rerun viewer not installed",
                "Showing the timeline inside a notebook needs rerun-notebook matching rerun-sdk: "
                "pip install 'rerun-notebook==0.41.*' (it serves its viewer from your machine, "
                "offline). Or write an .rrd file and open it with `rerun FILE`."),
    "PLC3005": ("optional part not installed", "The feature needs an extra: pip install "
                "'plclab[viz]' (rerun, matplotlib), 'plclab[modbus]' or 'plclab[sim]'."),
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
    # the grader's defences (untrusted submissions)
    "PLC5030": ("symbolic link in a submission", "The grader never follows a symbolic link "
                "(it could point at another student's work or a system file); the submission "
                "is not graded. Submit the files themselves."),
    "PLC5031": ("source file too large", "A source file is larger than the grader reads "
                "(4 MB; 8 MB a submission). It is rejected without being read: submit the "
                "program's text only."),
    "PLC5032": ("too many files", "A submission holds more source files, entries or folder "
                "levels than the grader accepts (64 sources, 2000 entries, 8 levels). Submit "
                "only the program's files."),
    "PLC5033": ("not a plain file", "A submission holds something that is not a plain file "
                "(a device, a pipe, a socket) or cannot be read. Submit plain source files."),
    "PLC5034": ("results rejected", "The grading process sent results the grader does not "
                "accept (wrong shape, a score out of range, an oversized text or picture); "
                "nothing it sent counts. Tell your instructor."),
    "PLC5035": ("CPU time limit exceeded", "The grading process used more CPU time than "
                "the limit (the wall-clock limit plus a margin) and was stopped by the "
                "operating system."),
    "PLC5036": ("diagnostics cut", "Only the first 50 compiler messages of a file are kept "
                "(the rest are counted); fix those first and check again."),
    "PLC9101": ("unknown signal range", "I/O module: use 0-10V, +-10V, 0-20mA, 4-20mA or 1-5V."),
    "PLC9102": ("unknown count convention", "I/O module: use book, full, s7 or logo."),
    "PLC9103": ("bad bit width", "I/O module: the ADC bit width is outside what the convention allows."),
    "PLC9104": ("bad measuring range", "I/O module: the engineering range is empty."),
    "PLC9105": ("negative parameter", "I/O module: times, noise and delays must be >= 0."),
    "PLC9106": ("unknown fault", "I/O module: the fault name is not one the module knows."),
    "PLC9107": ("unknown output kind", "I/O module: a digital output is 'transistor' or 'relay'."),
    "PLC9108": ("transmitter mismatch", "I/O module: the transmitter's signal differs from the input's range."),
    "PLC9109": ("time went backwards", "I/O module: sample times must not decrease."),
    "PLC9201": ("Modbus support not installed", "pip install 'plclab[modbus]' (pymodbus 3.16+)."),
    "PLC9202": ("cannot open the Modbus port", "Another program uses the port, or it needs "
                "privileges (ports below 1024); pick another with --port."),
    "PLC9203": ("bad Modbus option", "An --io URL, a host, a port or an address is malformed."),
    "PLC9204": ("Modbus exception response", "The server refused the request (illegal address, "
                "read-only area, illegal value)."),
    "PLC9205": ("no Modbus connection", "The server does not answer: is it running, on this "
                "host and port?"),
    "PLC9999": ("internal error", "A bug in plclab: please report it with the program."),
}


def explain(code: str) -> str:
    code = code.upper()
    if code not in PROBLEMS:
        raise KeyError(code)
    title, text = PROBLEMS[code]
    return f"{code}: {title}\n\n{text}"
