"""The process image sized from the program's addresses (issue 40 item 10, ADR 0053): the
default image grows to hold the highest located variable, bounded at 65536 bytes; an explicit
size smaller than needed, or beyond the bound, is refused with its code; run and sim take
--image-size."""

import pytest

import plclab
from plclab.cli import main
from plclab.errors import PlcError
from plclab.project import check_sources
from plclab.runtime.plc import auto_image_size

LINT = """PROGRAM Main
VAR c AT %ML1025 : LINT; w AT %MW2000 : WORD; q AT %QX3.1 : BOOL; END_VAR
c := c + 1; w := 16#ABCD; q := TRUE;
END_PROGRAM
"""


@pytest.mark.parametrize("need,size", [(0, 1024), (1, 1024), (1024, 1024), (1025, 2048),
                                       (1033, 2048), (4002, 4096), (65536, 65536)])
def test_auto_size_is_the_next_kib(need, size):
    assert auto_image_size(need) == size


def test_a_program_beyond_1024_bytes_runs_without_an_option():
    """%ML1025 ends at byte 1033 (the issue's example), %MW2000 at 2002: 2048 bytes."""
    plc = plclab.loads(LINT, "big.st")
    assert plc.image_size == 2048 == len(plc.inputs) == len(plc.outputs) == len(plc.memory)
    plc.scan(3)
    assert plc["Main.c"] == 3 and plc["%ML1025"] == 3 and plc["%MW2000"] == 0xABCD


def test_a_small_program_keeps_the_1024_byte_image():
    plc = plclab.loads(LINT.replace("%ML1025", "%ML8").replace("%MW2000", "%MW16"), "s.st")
    assert plc.image_size == 1024


def test_an_explicit_size_too_small_is_plc0127_naming_the_need():
    with pytest.raises(PlcError) as ei:
        plclab.loads(LINT, "big.st", image_size=1024)
    assert ei.value.code == "PLC0127" and "2002" in ei.value.message
    assert "--image-size" in ei.value.message and ei.value.location.line == 2


@pytest.mark.parametrize("decl", ["x AT %MB65536 : BYTE;", "x AT %MW65535 : WORD;",
                                  "x AT %ML65530 : LINT;"])
def test_beyond_the_bound_is_refused_by_the_checker(decl):
    src = f"PROGRAM Main VAR {decl} END_VAR\nx := x; END_PROGRAM"
    errs = [d for d in check_sources([(src, "b.st")])[1] if d.severity == "error"]
    assert errs and errs[0].code == "PLC0127" and "65,536" in errs[0].message


def test_the_last_bytes_of_the_bound_work():
    src = "PROGRAM Main VAR x AT %MW65534 : WORD; END_VAR\nx := 7; END_PROGRAM"
    plc = plclab.loads(src, "top.st")
    plc.scan()
    assert plc.image_size == 65536 and plc["%MW65534"] == 7


def test_run_sizes_the_image_and_takes_image_size(tmp_path, capsys):
    f = tmp_path / "big.st"
    f.write_text(LINT)
    assert main(["run", str(f), "--cycles", "2", "--print", "Main.c"]) == 0
    assert "2" in capsys.readouterr().out
    assert main(["run", str(f), "--cycles", "1", "--image-size", "8192", "--print",
                 "Main.c"]) == 0
    capsys.readouterr()
    rc = main(["run", str(f), "--cycles", "1", "--image-size", "1024"])
    err = capsys.readouterr().err
    assert rc != 0 and "PLC0127" in err and "Traceback" not in err
    rc = main(["run", str(f), "--cycles", "1", "--image-size", "70000"])
    err = capsys.readouterr().err
    assert rc != 0 and "PLC3012" in err and "Traceback" not in err


def test_sim_takes_image_size():
    from plclab.sim.runner import load_plc

    assert load_plc(LINT).image_size == 2048
    assert load_plc(LINT, image_size=16384).image_size == 16384
    with pytest.raises(PlcError) as ei:
        load_plc(LINT, image_size=1024)
    assert ei.value.code == "PLC0127"


TANK = """PROGRAM TankLevel
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; log AT %MW3000 : WORD;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); log := log + 1;
END_PROGRAM
"""


def test_sim_command_sizes_the_image_and_takes_image_size(tmp_path, capsys):
    f = tmp_path / "tank.st"
    f.write_text(TANK)
    assert main(["sim", "tank", str(f), "--duration", "1s"]) == 0
    capsys.readouterr()
    assert main(["sim", "tank", str(f), "--duration", "1s", "--image-size", "8192"]) == 0
    capsys.readouterr()
    rc = main(["sim", "tank", str(f), "--duration", "1s", "--image-size", "2048"])
    err = capsys.readouterr().err
    assert rc != 0 and "PLC0127" in err and "Traceback" not in err
