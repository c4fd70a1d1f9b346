"""The real-time clock RTC (IEC 61131-3 ed.1 Table 35, MATIEC lib/rtc.txt; ADR 0037): which
project keeps it (a file in the iec or matiec dialect that names it, no RTC of its own), and
that it reads the virtual clock."""

import plclab
from plclab.project import check_sources, parse_sources

USES_RTC = """PROGRAM Main
VAR c : RTC; set : BOOL; now : DT; END_VAR
c(IN := set, PDT := DT#2024-01-01-12:00:00);
now := c.CDT;
END_PROGRAM
"""

OWN_RTC = """FUNCTION_BLOCK RTC
VAR_INPUT IN : BOOL; END_VAR
VAR_OUTPUT N : INT; END_VAR
IF IN THEN N := N + 1; END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR c : RTC; n : INT; END_VAR
c(IN := TRUE);
n := c.N;
END_PROGRAM
"""


def library_blocks(src: str) -> set[str]:
    files, _ = parse_sources([(src, "main.st")])
    return {p.name for f in files if f.file.startswith("<plclab>/") for p in f.pous}


def test_rtc_in_matiec_and_iec_reads_the_virtual_clock() -> None:
    for dialect in ("matiec", "iec"):
        plc = plclab.loads(f"{{dialect '{dialect}'}}\n" + USES_RTC)
        plc.scan(3)  # 0, 10, 20 ms: the clock of a PLC started at DT#1970-01-01-00:00:00
        assert plc["Main.now"] == 20
        plc["Main.set"] = True
        plc.scan(1)
        assert plc["Main.now"] == 1_704_110_400_000  # DT#2024-01-01-12:00:00 in ms
        plc.scan(5)
        assert plc["Main.now"] == 1_704_110_400_050
        assert plc["Main.c.Q"] is True


def test_codesys_and_s7_have_no_rtc() -> None:
    for dialect in ("codesys", "s7"):
        _, diags = check_sources([(f"{{dialect '{dialect}'}}\n" + USES_RTC, "main.st")])
        assert "PLC0102" in {d.code for d in diags if d.severity == "error"}, dialect


def test_a_users_own_rtc_wins_without_a_warning() -> None:
    src = "{dialect 'matiec'}\n" + OWN_RTC
    _, diags = check_sources([(src, "main.st")])
    assert not [d for d in diags if d.code in ("PLC0205", "PLC0101")]
    plc = plclab.loads(src)
    plc.scan(2)
    assert plc["Main.n"] == 2


def test_a_project_without_rtc_compiles_no_rtc() -> None:
    assert "RTC" not in library_blocks("{dialect 'matiec'}\nPROGRAM Main END_PROGRAM")
    assert "RTC" in library_blocks("{dialect 'matiec'}\n" + USES_RTC)


def test_sub_of_two_dates_is_the_time_between_them_and_date_minus_date_is_refused() -> None:
    ok = "PROGRAM Main VAR a, b : DT; t : TIME; END_VAR t := SUB(a, b); END_PROGRAM"
    assert not [d for d in check_sources([(ok, "m.st")])[1] if d.severity == "error"]
    bad = "PROGRAM Main VAR a, b : DATE; t : TIME; END_VAR t := SUB(a, b); END_PROGRAM"
    errors = [d for d in check_sources([(bad, "m.st")])[1] if d.severity == "error"]
    assert errors[0].code == "PLC0107" and "SUB_DATE_DATE" in errors[0].message
