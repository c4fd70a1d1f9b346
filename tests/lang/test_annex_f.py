"""When a project gets the Annex F blocks (ADR 0029): a file in the matiec dialect gets all
five, PID and RAMP being the Annex's; any other project gets INTEGRAL, DERIVATIVE and
HYSTERESIS when it declares one, and keeps plclab's own PID and RAMP; a project that uses
none compiles no more code than before."""

import plclab
from plclab.project import check_sources, parse_sources

USES_INTEGRAL = """PROGRAM Main
VAR i : INTEGRAL; p : PID; END_VAR
i(RUN := TRUE, XIN := 1.0, CYCLE := T#1s);
p(ACTUAL := 1.0, SETPOINT := 2.0);
END_PROGRAM
"""


def library_blocks(src: str) -> set[str]:
    files, _ = parse_sources([(src, "main.st")])
    return {p.name for f in files if f.file.startswith("<plclab>/") for p in f.pous}


def test_a_codesys_project_gets_the_annex_blocks_it_declares_and_keeps_plclabs_pid() -> None:
    plc = plclab.loads(USES_INTEGRAL)
    plc.scan(2)
    assert plc["Main.i.XOUT"] == 2.0
    assert plc["Main.p.Y"] > 0  # plclab's PID: ACTUAL, SETPOINT, Y
    assert {"INTEGRAL", "DERIVATIVE", "HYSTERESIS", "PID"} <= library_blocks(USES_INTEGRAL)


def test_a_matiec_file_gets_the_annex_pid_and_ramp() -> None:
    src = "{dialect 'matiec'}\n" + USES_INTEGRAL
    _, diags = check_sources([(src, "main.st")])
    errors = [d for d in diags if d.severity == "error"]
    assert [d.code for d in errors] == ["PLC0107", "PLC0107"]  # no ACTUAL, no SETPOINT
    assert "AUTO" in errors[0].message  # the Annex's pins are listed instead


def test_a_project_without_them_compiles_no_annex_block() -> None:
    blocks = library_blocks("PROGRAM Main VAR t : TON; END_VAR t(IN := TRUE); END_PROGRAM")
    assert not blocks & {"INTEGRAL", "DERIVATIVE", "HYSTERESIS"}
    assert {"PID", "RAMP"} <= blocks


def test_annex_f_blocks_are_found_in_any_case_and_only_when_named():
    """The text pre-filter of add_annex_f (ADR 0057) must not miss a block written in lower
    case, nor add the Annex when its names appear only inside longer identifiers."""
    from plclab.project import parse_sources

    def annex_in(text: str) -> bool:
        files, _ = parse_sources([(text, "a.st")])
        return any(f.file.endswith("annexf.st") for f in files)

    use = "PROGRAM P VAR h : {}; END_VAR END_PROGRAM"
    assert annex_in(use.format("hysteresis"))
    assert annex_in(use.format("Integral"))
    assert not annex_in("PROGRAM P VAR myintegral : INT; END_VAR END_PROGRAM")
    assert not annex_in("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM")
