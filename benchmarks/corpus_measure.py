"""The real-world corpus of issue 40: build it from repository mirrors, then measure plclab on it.

``python benchmarks/corpus_measure.py build OUT MIRROR [MIRROR ...]`` copies the files of the
sources below out of git mirrors (a folder holding a bare or normal repository, e.g. the
``/work/.mirror/owner+name/repo`` that a fetch leaves, or a ``git clone``) into ``OUT/<source>/``
(MATIEC's ``.txt`` files become ``.st``), one ``DIALECT`` file per source, and ``OUT/SOURCES.txt``
naming repository, commit and path of every file. A file whose text another file already has is
left out (OpenPLC v3 carries MATIEC's tests). Third-party files never go into this repository:
keep OUT outside it (``/work/corpus``, ``/tmp/corpus``).

``python benchmarks/corpus_measure.py measure OUT`` (or ``measure MIRROR ...``, which builds into
a temporary folder first) reads every file in its own process, with a time limit, and prints:

* accepted as is: ``plclab check FILE`` with no option (its pragma, the tool that wrote it, or
  the default dialect);
* accepted in the source's native dialect (``--dialect`` of its ``DIALECT`` file, or the
  per-path dialect of the source table);
* of the accepted files holding a program: ``plclab run FILE --cycles 100`` without a fault;
* Python tracebacks (an exception that is not a ``PlcError``, or PLC9990/PLC9999) and hangs
  (no answer within ``--timeout`` seconds): both must be 0.

**Valid and self-contained** (the issue's rate). A file is left out of it, with the reason, when

1. it is invalid on purpose: its path says so (``bad``, ``error``, ``fail``, ``invalid``), or
   it is a fragment (no POU, TYPE or CONFIGURATION header: a body alone);
2. it needs vendor project context: a Beremiz extension folder (``@c_ext``, ``@py_ext``,
   ``@svghmi``, ``@wxglade_hmi``...) or C code / external declarations in pragmas
   (``{external}``, ``{{``, ``@EXTERNAL``), which only the vendor's build completes;
3. it needs a missing library: in its native dialect every error is an undeclared name, type or
   function (PLC0100, PLC0102, PLC0106) that the file itself does not declare and that is not
   a standard IEC 61131-3 name (a standard name plclab lacks stays plclab's fault);
4. it is on the reviewed list ``REVIEWED``, each entry with the rule the file breaks (read one
   by one: a name declared twice, an undeclared variable, a type error, Annex F pseudo-code).

Everything else counts. ``--list`` prints each file's outcome and reason; the table of first
error codes in the native dialect, most files first, is what to work on next.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import io
import json
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CYCLES = 100


@dataclass(frozen=True)
class Source:
    """One repository of the corpus: which files, and the dialect of the tool it was written for."""

    name: str
    repo: str
    dialect: str
    include: str  # regex on the path in the repository
    exclude: str = r"^$"
    dialects: tuple[tuple[str, str], ...] = ()  # (path regex, dialect) overrides


SOURCES = [
    Source("matiec", "beremiz/matiec", "matiec",
           r"^(AnnexF/[^/]+\.txt|lib/[^/]+\.txt|tests/.+\.(txt|st|xml))$"),
    Source("ironplc", "ironplc/ironplc", "iec",
           r"^(compiler/.*resources/.+\.(st|xml)|examples/.+\.st|tests/e2e/.+\.st)$",
           # the TwinCAT libraries, and the tests of IronPLC's CODESYS extensions
           dialects=((r"/libs/Tc2_|/(reference_to|sizeof)(_rendered)?\.st$", "codesys"),)),
    Source("oscat-openplc", "wonka929/OSCAT_OpenPLC", "matiec", r"(^|/)(plc\.xml|build/plc\.st)$"),
    Source("plclang-oscat", "PLC-lang/oscat", "codesys", r"\.st$"),
    Source("plclang-stdfun", "PLC-lang/StandardFunctions", "codesys", r"\.st$"),
    Source("openplc-samples", "gracesrm/OpenPLC_Sample_Programs", "matiec",
           r"(\.st|(^|/)plc\.xml)$", r"(^|/)build/generated_plc\.st$"),
    Source("openplc-v3", "thiagoralves/OpenPLC_v3", "matiec",
           r"^(utils/matiec_src/(tests|lib|AnnexF)/.+\.(xml|txt|st)|webserver/st_files/.+\.st)$"),
    Source("beremiz", "beremiz/beremiz", "matiec",
           r"^(exemples|tests)/.*(^|/)plc\.xml$|^plcopen/[^/]+\.xml$"),
    Source("iec-checker", "jubnzv/iec-checker", "iec", r"^test/(.+\.st|plcopen/.+\.xml)$"),
    Source("blark", "klauer/blark", "codesys", r"^blark/tests/source/.+\.st$"),
    Source("strucpp", "Autonomy-Logic/STruCpp", "codesys", r"^(libs/sources/.+|examples/.+)\.st$"),
]

INVALID_PATH = re.compile(r"(^|[/_.-])(bad|errors?|fail\w*|invalid)([/_.-]|$)", re.IGNORECASE)
VENDOR_FOLDER = re.compile(r"@(c_ext|py_ext|svghmi|wxglade_hmi|modbus|canfestival|bacnet|"
                           r"opcua|ethercat|\w+_ext)\b")
VENDOR_TEXT = re.compile(r"\{\s*external\s*\}|\{\{|@EXTERNAL|\{\s*attribute\s+'extern",
                         re.IGNORECASE)
HEADER = re.compile(r"^\s*(PROGRAM|FUNCTION_BLOCK|FUNCTION|TYPE|CONFIGURATION|CLASS|INTERFACE|"
                    r"VAR_GLOBAL|NAMESPACE)\b|<project\b", re.IGNORECASE | re.MULTILINE)
MISSING = {"PLC0100", "PLC0102", "PLC0106"}
EXTENSION = "PLC0246"  # a name that a Beremiz extension (SVG HMI, Python, MQTT...) declares
NOT_A_BLOCK = "PLC0165"  # a PLCopen box whose type is not a function block (when undeclared)
TRACEBACK_CODES = {"PLC9990", "PLC9999"}

# The standard names (IEC 61131-3 ed.2 Tables 22-35, ed.3 Tables 22-46): a file calling one
# that plclab lacks is plclab's gap, not a missing library.
STANDARD = set("""
ABS SQRT LN LOG EXP SIN COS TAN ASIN ACOS ATAN ATAN2 ADD MUL SUB DIV MOD EXPT MOVE SHL SHR ROR ROL
AND OR XOR NOT SEL MAX MIN LIMIT MUX GT GE EQ LE LT NE LEN LEFT RIGHT MID CONCAT INSERT DELETE
REPLACE FIND TRUNC ADD_TIME SUB_TIME MUL_TIME DIV_TIME MULTIME DIVTIME ADD_TOD_TIME ADD_DT_TIME
SUB_DATE_DATE SUB_TOD_TIME SUB_TOD_TOD SUB_DT_TIME SUB_DT_DT CONCAT_DATE_TOD CONCAT_DATE
CONCAT_TOD CONCAT_DT SPLIT_DATE SPLIT_TOD SPLIT_DT DAY_OF_WEEK LOWER_BOUND UPPER_BOUND SR RS
R_TRIG F_TRIG CTU CTD CTUD TP TON TOF RTC SEMA CTU_INT CTU_DINT CTU_LINT CTU_UDINT CTU_ULINT
CTD_INT CTD_DINT CTD_LINT CTD_UDINT CTD_ULINT CTUD_INT CTUD_DINT CTUD_LINT CTUD_UDINT CTUD_ULINT
REF ADR SIZEOF
""".split())
CONVERSION = re.compile(r"^(\w+_TO_\w+|TO_\w+|TRUNC_\w+|BCD_TO_\w+|\w+_TO_BCD)$")
# Files read one by one whose rejection is right: each with the rule it breaks. Reviewed by
# reading the file against the standard or the tool's manual (ADR 0060); a file plclab
# rejects for a reason not shown here stays counted.
_TWICE = "invalid: a name declared twice in one scope (IEC 61131-3 ed.3 6.5.2.2)"
_UNDECLARED = "invalid: uses a variable it declares nowhere (a parser test)"
_TYPES = "invalid: a type error every IEC compiler reports (a checker's defect sample)"
_SIZE = "invalid: a located variable whose type does not fit the address size (ed.3 6.5.5)"
_NEEDS = "needs a missing library: names declared in another file of its project"
_SEMI = "invalid in its dialect: ';' after END_STRUCT/type is required by the IEC grammar"
_ANNEX = "invalid: Annex F pseudo-code as printed in the 1998 draft, no compiler takes it"
_RUSTY = "vendor dialect: RuSTy's own extensions (address arithmetic), no plclab dialect"
REVIEWED = {
    "iec-checker/test/plcopen/example.xml": "invalid: an array initial value for a BOOL",
    "iec-checker/test/st/dead-code.st": _TYPES,
    "iec-checker/test/st/good/generic-types.st": "invalid: generic types (ANY_INT...) in a "
    "user POU (ed.3 6.4.2: for standard functions only)",
    "iec-checker/test/st/declaration-analysis.st": _TYPES,
    "iec-checker/test/st/good/array-in-loop.st": _SIZE,
    "iec-checker/test/st/good/control-statements.st": _TYPES,
    "iec-checker/test/st/good/direct-variables.st": _SIZE,
    "iec-checker/test/st/good/function-declaration.st": _TWICE,
    "iec-checker/test/st/good/literals.st": _TWICE,
    "iec-checker/test/st/good/multiple-variables.st": _UNDECLARED,
    "iec-checker/test/st/good/references.st": _UNDECLARED,
    "iec-checker/test/st/good/simple.st": _NEEDS,
    "iec-checker/test/st/good/struct-declaration.st": _SEMI,
    "iec-checker/test/st/good/types.st": _TWICE,
    "iec-checker/test/st/good/user3.st": _NEEDS,
    "iec-checker/test/st/good/variables-declaration.st": _TWICE,
    "iec-checker/test/st/merge-1.st": _SEMI,
    "iec-checker/test/st/plcopen-cp1.st": "invalid: %B0 is no address (I, Q or M is needed)",
    "iec-checker/test/st/plcopen-cp13.st": "invalid: the recursion PLCopen rule CP13 flags",
    "iec-checker/test/st/plcopen-cp16.st": "invalid: a FUNCTION_BLOCK run as a PROGRAM instance "
    "of a RESOURCE (what CP16 flags)",
    "iec-checker/test/st/plcopen-cp25.st": "invalid: the implicit REAL->INT CP25 flags",
    "iec-checker/test/st/plcopen-cp28.st": "invalid: TIME + DINT, which CP28 flags",
    "iec-checker/test/st/plcopen-cp3.st": _TYPES,
    "iec-checker/test/st/plcopen-cp4.st": _SIZE,
    "iec-checker/test/st/plcopen-cp6.st": _NEEDS,
    "iec-checker/test/st/plcopen-cp9.st": _UNDECLARED,
    "iec-checker/test/st/plcopen-l10.st": _TYPES,
    "iec-checker/test/st/plcopen-l22.st": "invalid: the FOR variable assigned in its loop (L22)",
    "ironplc/compiler/resources/test/expressions.st": _UNDECLARED,
    "ironplc/compiler/plc2plc/resources/test/expressions_rendered.st": _UNDECLARED,
    "ironplc/compiler/resources/test/inout_var_decl.st": _UNDECLARED,
    "ironplc/compiler/plc2plc/resources/test/inout_var_decl_rendered.st": _UNDECLARED,
    "ironplc/compiler/resources/test/textual.st": _UNDECLARED,
    "ironplc/compiler/plc2plc/resources/test/textual_rendered.st": _UNDECLARED,
    "ironplc/compiler/resources/test/type_decl.st": "invalid: an array of a type declared nowhere",
    "ironplc/compiler/plc2plc/resources/test/type_decl_rendered.st":
        "invalid: an array of a type declared nowhere",
    "ironplc/compiler/resources/test/input_var_decl.st":
        "invalid: R_EDGE input of a FUNCTION (ed.3 6.5.1.2: FB and PROGRAM only)",
    "ironplc/compiler/plc2plc/resources/test/input_var_decl_rendered.st":
        "invalid: R_EDGE input of a FUNCTION (ed.3 6.5.1.2: FB and PROGRAM only)",
    "ironplc/compiler/resources/test/literal.st": "invalid: LREAL#11.0 stored in a REAL",
    "ironplc/compiler/plc2plc/resources/test/literal_rendered.st":
        "invalid: LREAL#11.0 stored in a REAL",
    "ironplc/compiler/plc2plc/resources/test/strings_rendered.st": _TYPES,
    "ironplc/compiler/resources/test/var_decl.st": _SIZE,
    "ironplc/compiler/plc2plc/resources/test/var_decl_rendered.st": _SIZE,
    "ironplc/compiler/resources/test/if.st": "invalid: assigns the FUNCTION_BLOCK's own name",
    "ironplc/compiler/sources/resources/libs/Tc2_Math/1.0.0/Tc2_Math.st":
        "vendor project context: TwinCAT library stubs naming the reserved __ operators",
    "ironplc/compiler/sources/resources/libs/Tc2_Utilities/1.0.0/Tc2_Utilities.st":
        "vendor project context: TwinCAT library stubs naming the reserved __ operators",
    "matiec/AnnexF/delay_st.st": _ANNEX,
    "matiec/AnnexF/diffeq_st.st": _ANNEX,
    "matiec/AnnexF/gravel_st.st": _ANNEX + " (%B6, INT_TO_BCD into a BYTE)",
    "matiec/AnnexF/stack_int_il.st": _ANNEX + " (CAL of the function LIMIT)",
    "matiec/AnnexF/fwd_rev_mon_il.st": _NEEDS + " (cmd_monitor_il)",
    "matiec/lib/standard_functions.st":
        "vendor project context: MATIEC's own overloaded declarations of the built-ins",
    "openplc-v3/utils/matiec_src/lib/standard_functions.st":
        "vendor project context: MATIEC's own overloaded declarations of the built-ins",
    "matiec/tests/STD_TEST.xml": "invalid: MUX of INT and BOOL inputs, STRING AT %QB0",
    "openplc-samples/Vet_snippet/plc.xml": _SIZE,
    "beremiz/tests/projects/mqtt_ssl/plc.xml": "vendor project context: the located variables "
    "of structured types and the VAR_EXTERNALs of Beremiz's MQTT extension",
    "openplc-samples/Gate_Controller/plc.xml": "invalid: a STRING initialised with the WSTRING "
    "literal \"1234\"",
    "openplc-samples/RobotStudio/Estun/plc.xml": _NEEDS + " (the SFUN_ blocks of Estun's robot "
    "library; <varList> sections of an unnamed type)",
    "openplc-samples/RobotStudio/RobotStudio/PLCPython/plc.xml":
        "invalid: a statement ending in a full-width '\uff1b' and stray words",
    "openplc-samples/successed_ST/Code_13.st": "invalid: UINT stored in USINT (narrowing)",
    "openplc-samples/successed_ST/symbextest.st": "invalid: BOOL stored in INT",
    "oscat-openplc/OSCAT BASIC 3.33/OSCAT BASIC 3.33-13 String Functions/plc.xml":
        "invalid: BYTE_TO_STRING with two arguments (the port's own error)",
    "oscat-openplc/OSCAT BASIC 3.33/OSCAT BASIC 3.33-17 Latches Flipflop and Shift Registers/"
    "plc.xml": "invalid: a comment '(*' closed by '*]' (the port's own error)",
    "plclang-oscat/oscat.st": _RUSTY,
    "plclang-stdfun/iec61131-st/bit_conversion.st": _RUSTY,
    "plclang-stdfun/iec61131-st/num_conversion.st": _RUSTY,
    "blark/blark/tests/source/array_initializer.st": _NEEDS + " (FB_Runner, RunnerTasks)",
    "blark/blark/tests/source/repeated_declaration.st": _NEEDS + " (library.TPUDO)",
    "blark/blark/tests/source/array_of_addresses.st": _NEEDS + " (g_c_someConstant)",
    "blark/blark/tests/source/enum_with_function_calls.st": _NEEDS + " (someColor)",
    "blark/blark/tests/source/extended_union.st": _NEEDS + " (THING_BASE)",
    "blark/blark/tests/source/fb_initializer.st": _NEEDS + " (FB_Sample)",
    "blark/blark/tests/source/var_declarations_var_attrib.st":
        "invalid in its dialect: CODESYS requires a constant's value (ADR 0035)",
}
NAME_IN_MESSAGE = re.compile(r"^(?:unknown type |PROGRAM |VAR_EXTERNAL |)([A-Za-z_][\w.]*)")


def _git(mirror: Path, *args: str) -> bytes:
    return subprocess.run(["git", "-C", str(mirror), *args], check=True,
                          capture_output=True).stdout


def mirror_repo(mirror: Path) -> str:
    """``owner/name`` of a mirror: its folder name ``owner+name`` (a fetch's), else its origin."""
    for part in (mirror.name, mirror.parent.name):
        if "+" in part:
            return part.replace("+", "/", 1)
    url = _git(mirror, "config", "--get", "remote.origin.url").decode().strip()
    return "/".join(url.removesuffix(".git").split("/")[-2:])


def is_plcopen(data: bytes) -> bool:
    head = data[:4000].decode("utf-8", "replace")
    return "plcopen.org" in head and "<project" in head


def build(out: Path, mirrors: list[Path]) -> int:
    """Copy the sources' files out of the mirrors into ``out``; return how many were written."""
    by_repo = {s.repo.lower(): s for s in SOURCES}
    seen: set[str] = set()
    lines = []
    written = 0
    for mirror in mirrors:
        source = by_repo.get(mirror_repo(mirror).lower())
        if source is None:
            print(f"{mirror}: not a corpus source ({', '.join(by_repo)})", file=sys.stderr)
            continue
        commit = _git(mirror, "rev-parse", "HEAD").decode().strip()
        folder = out / source.name
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "DIALECT").write_text(source.dialect + "\n")
        overrides = []
        for path in _git(mirror, "ls-tree", "-r", "--name-only", "-z", "HEAD").decode().split("\0"):
            if not path or not re.search(source.include, path) or re.search(source.exclude, path):
                continue
            data = _git(mirror, "show", f"HEAD:{path}")
            if path.lower().endswith(".xml") and not is_plcopen(data):
                continue  # a project or extension file of the tool, not a program
            digest = hashlib.sha256(data).hexdigest()
            if digest in seen:
                continue
            seen.add(digest)
            target = folder / (path[:-4] + ".st" if path.lower().endswith(".txt") else path)
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
            written += 1
            lines.append(f"{source.name}/{target.relative_to(folder).as_posix()}\t"
                         f"github:{source.repo}@{commit}:{path}")
            for pattern, dialect in source.dialects:
                if re.search(pattern, path):
                    overrides.append(f"{target.relative_to(folder).as_posix()}\t{dialect}")
        if overrides:
            (folder / "DIALECTS.tsv").write_text("\n".join(overrides) + "\n")
    with open(out / "SOURCES.txt", "a", encoding="utf-8") as f:
        f.write("".join(line + "\n" for line in lines))
    return written


# --- one file, in a child process ---------------------------------------------------------

def _check(text: str, name: str, dialect: str | None) -> dict:
    from plclab.errors import PlcError
    from plclab.project import check_sources

    try:
        project, diags = check_sources([(text, name)], dialect)
    except PlcError as exc:
        return {"ok": False, "code": exc.code, "message": str(exc).splitlines()[0], "errors": [
            (exc.code, exc.message)]}
    errors = [d for d in diags if d.severity == "error"]
    if errors or project is None:
        return {"ok": False, "code": errors[0].code if errors else "?",
                "message": f"{errors[0].location}: {errors[0].message}" if errors else "",
                "errors": [(d.code, d.message) for d in errors]}
    return {"ok": True, "program": bool(project.programs)}


def _run(path: Path, dialect: str | None) -> dict:
    from plclab.cli import main

    err = io.StringIO()
    args = ["run", str(path), "--cycles", str(CYCLES)] + (["--dialect", dialect] if dialect else [])
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        rc = main(args)
    message = err.getvalue().strip().splitlines()
    code = next(iter(re.findall(r"PLC\d{4}", err.getvalue())), "")
    return {"ok": rc == 0, "code": code, "message": message[0] if message else ""}


def judge_one(path: Path, native: str) -> dict:
    """The outcome of one file: as is, in its native dialect, and its run."""
    raw = path.read_bytes()
    text = raw.decode("utf-8-sig", errors="replace") if raw else ""
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    out: dict = {"as_is": _check(text, path.name, None), "native": _check(text, path.name, native)}
    if out["native"]["ok"] and out["native"].get("program"):
        out["run"] = _run(path, native)
    return out


def child_main(path: str, native: str) -> int:
    sys.path.insert(0, str(ROOT))
    try:
        result = judge_one(Path(path), native)
    except Exception:  # noqa: BLE001 - exactly what the measure counts
        import traceback

        result = {"traceback": traceback.format_exc()}
    print("@@RESULT@@" + json.dumps(result))
    return 0


# --- the measure ------------------------------------------------------------------------------

@dataclass
class Outcome:
    path: Path
    source: str
    native_dialect: str
    result: dict = field(default_factory=dict)
    excluded: str = ""  # the reason it is not "valid and self-contained", or ""

    @property
    def as_is(self) -> bool:
        return bool(self.result.get("as_is", {}).get("ok"))

    @property
    def native(self) -> bool:
        return bool(self.result.get("native", {}).get("ok"))

    @property
    def traceback(self) -> bool:
        if "traceback" in self.result:
            return True
        return any(self.result.get(k, {}).get("code") in TRACEBACK_CODES
                   for k in ("as_is", "native", "run"))


def corpus_files(root: Path) -> list[tuple[Path, str, str]]:
    """(file, source, native dialect) of every .st/.xml file under root."""
    out = []
    for folder in sorted(p for p in root.iterdir() if p.is_dir()):
        dialect = (folder / "DIALECT").read_text().strip() if (folder / "DIALECT").exists() \
            else "codesys"
        overrides = {}
        if (folder / "DIALECTS.tsv").exists():
            for line in (folder / "DIALECTS.tsv").read_text().splitlines():
                rel, _, d = line.partition("\t")
                overrides[rel] = d
        for p in sorted(folder.rglob("*")):
            if p.suffix.lower() in (".st", ".xml") and p.is_file():
                rel = p.relative_to(folder).as_posix()
                out.append((p, folder.name, overrides.get(rel, dialect)))
    return out


def declared_names(text: str) -> set[str]:
    names = set(m.upper() for m in re.findall(
        r"\b(?:FUNCTION_BLOCK|FUNCTION|PROGRAM|CLASS|INTERFACE)\s+(?:\w+\s+)*?(\w+)", text,
        re.IGNORECASE))
    names |= set(m.upper() for m in re.findall(r"\b(\w+)\s*:\s*(?:STRUCT|\()", text))
    names |= set(m.upper() for m in re.findall(r'<pou\s+name="(\w+)"', text))
    names |= set(m.upper() for m in re.findall(r'<dataType\s+name="(\w+)"', text))
    return names


def classify(o: Outcome, text: str) -> str:
    """Why a file is not valid and self-contained ('' when it counts); the module's rule."""
    rel = o.path.as_posix()
    for key, reason in REVIEWED.items():
        if rel.endswith("/" + key):
            return reason
    if INVALID_PATH.search(o.path.name) or re.search(r"/(bad|errors?|invalid)/", rel, re.I):
        return "invalid on purpose (its name says so)"
    if VENDOR_FOLDER.search(rel):
        return "vendor project context (Beremiz extension folder)"
    if VENDOR_TEXT.search(text):
        return "vendor project context (C code or external declarations)"
    if not HEADER.search(text):
        return "fragment (no POU, TYPE or CONFIGURATION)"
    native = o.result.get("native", {})
    errors = native.get("errors") or []
    if not native.get("ok") and errors:
        own = declared_names(text)
        missing = set()
        for code, message in errors:
            m = NAME_IN_MESSAGE.match(message)
            name = m.group(1).split(".")[0].upper() if m else ""
            if code == EXTENSION or code == NOT_A_BLOCK and name in missing:
                continue  # a Beremiz extension's name; a box of a missing block
            if code not in MISSING or not name or name in own or name in STANDARD \
                    or CONVERSION.match(name):
                return ""
            missing.add(name)
        if not missing:
            return "vendor project context (a Beremiz extension's types or variables)"
        if any(code == "PLC0100" for code, _ in errors):
            return ("needs project context (or is a parser test): variables or programs "
                    "declared in no file of it: " + ", ".join(sorted(missing)[:4]))
        return "needs a missing library: " + ", ".join(sorted(missing)[:4])
    return ""


def measure(root: Path, jobs: int, timeout: float) -> list[Outcome]:
    files = corpus_files(root)
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))

    def one(item: tuple[Path, str, str]) -> Outcome:
        path, source, dialect = item
        o = Outcome(path, source, dialect)
        try:
            proc = subprocess.run([sys.executable, __file__, "_one", str(path), dialect],
                                  capture_output=True, text=True, timeout=timeout, env=env)
            tail = proc.stdout.rpartition("@@RESULT@@")[2]
            o.result = json.loads(tail) if tail else {"traceback": proc.stderr[-2000:]}
        except subprocess.TimeoutExpired:
            o.result = {"hang": True}
        o.excluded = classify(o, path.read_bytes().decode("latin-1"))
        return o

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return list(pool.map(one, files))


def pct(a: int, b: int) -> str:
    return f"{a} of {b} ({100 * a / b:.1f} %)" if b else "0 of 0"


def report(root: Path, outcomes: list[Outcome], listing: bool) -> None:
    n = len(outcomes)
    counted = [o for o in outcomes if not o.excluded]
    programs = [o for o in outcomes if "run" in o.result]
    ran = sum(o.result["run"]["ok"] for o in programs)
    print(f"corpus {root}: {n} files from {len({o.source for o in outcomes})} sources")
    print("| figure | value |\n|---|---|")
    print(f"| accepted as is (default dialect) | {pct(sum(o.as_is for o in outcomes), n)} |")
    print(f"| accepted in each source's native dialect | "
          f"{pct(sum(o.native for o in outcomes), n)} |")
    print(f"| valid and self-contained files accepted as is | "
          f"{pct(sum(o.as_is for o in counted), len(counted))} |")
    print(f"| valid and self-contained files accepted in the native dialect | "
          f"{pct(sum(o.native for o in counted), len(counted))} |")
    print(f"| accepted programs that scan {CYCLES} times without a fault | "
          f"{pct(ran, len(programs))} |")
    print(f"| Python tracebacks / hangs | {sum(o.traceback for o in outcomes)} / "
          f"{sum('hang' in o.result for o in outcomes)} |")
    print("\nper source (counted: native accepted / counted, as is; excluded):")
    for source in sorted({o.source for o in outcomes}):
        mine = [o for o in outcomes if o.source == source]
        c = [o for o in mine if not o.excluded]
        print(f"  {source:16s} {sum(o.native for o in c):4d} / {len(c):4d}, as is "
              f"{sum(o.as_is for o in c):4d}; excluded {len(mine) - len(c)}")
    reasons = Counter(o.excluded.split(":")[0] for o in outcomes if o.excluded)
    print("\nexcluded:", ", ".join(f"{k} {v}" for k, v in reasons.most_common()))
    bad = [o for o in counted if not o.native]
    codes = Counter(o.result.get("native", {}).get("code", "hang/traceback") for o in bad)
    print("\nrejected valid files, by first error in the native dialect:")
    for code, count in codes.most_common(15):
        ex = [o for o in bad if o.result.get("native", {}).get("code") == code][:2]
        for i, e in enumerate(ex):
            print(f"  {f'{count:4d} x {code}' if not i else ' ' * (7 + len(code))}  "
                  f"{e.path.relative_to(root)}: "
                  f"{e.result.get('native', {}).get('message', '')[:110]}")
    faults = [o for o in programs if not o.result["run"]["ok"]]
    for o in faults:
        print(f"  fault {o.path.relative_to(root)}: {o.result['run']['message'][:120]}")
    for o in outcomes:
        if o.traceback or "hang" in o.result:
            print(f"  TRACEBACK/HANG {o.path.relative_to(root)}: "
                  f"{str(o.result)[-300:]}")
    if listing:
        for o in outcomes:
            print(f"  {'as-is' if o.as_is else '-----'} {'native' if o.native else '------'} "
                  f"{o.result.get('native', {}).get('code', ''):8s} {o.path.relative_to(root)}"
                  f"{'  [' + o.excluded + ']' if o.excluded else ''}")


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["_one"]:
        return child_main(argv[1], argv[2])
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    b = sub.add_parser("build", help="copy the corpus out of mirrors")
    b.add_argument("out", type=Path)
    b.add_argument("mirrors", nargs="+", type=Path)
    m = sub.add_parser("measure", help="measure a built corpus, or mirrors")
    m.add_argument("paths", nargs="+", type=Path, help="a built corpus folder, or mirrors")
    m.add_argument("--jobs", type=int, default=2)
    m.add_argument("--timeout", type=float, default=120.0, help="seconds before a hang")
    m.add_argument("--list", action="store_true", help="print each file's outcome")
    m.add_argument("--json", type=Path, help="also write each file's outcome here")
    m.add_argument("--reuse", type=Path, help="classify and report the outcomes of an earlier "
                   "--json instead of running the files again")
    args = ap.parse_args(argv)
    if args.cmd == "build":
        print(f"{build(args.out, args.mirrors)} files written to {args.out}")
        return 0
    if len(args.paths) == 1 and (args.paths[0] / "SOURCES.txt").exists():
        root = args.paths[0]
        tmp = None
    else:
        tmp = tempfile.TemporaryDirectory()
        root = Path(tmp.name)
        build(root, args.paths)
    if args.reuse:
        outcomes = []
        for r in json.loads(args.reuse.read_text()):
            o = Outcome(root / r.pop("path"), r.pop("source"), r.pop("dialect"))
            r.pop("excluded", None)
            o.result = r
            o.excluded = classify(o, o.path.read_bytes().decode("latin-1"))
            outcomes.append(o)
    else:
        outcomes = measure(root, args.jobs, args.timeout)
    report(root, outcomes, args.list)
    if args.json:
        args.json.write_text(json.dumps([
            {"path": str(o.path.relative_to(root)), "source": o.source, "dialect": o.native_dialect,
             "excluded": o.excluded, **o.result} for o in outcomes], indent=1))
    if tmp:
        tmp.cleanup()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
