"""Resource-scoped globals (IEC 61131-3 ed.3 6.8; ADR 0037): in a configuration of two or more
resources each resource's VAR_GLOBAL is seen by its own programs only, two resources may
declare a global of one name, and their program instances are named RESOURCE.INSTANCE; with one
resource nothing changes."""

import pytest

import plclab
from plclab.lang.plcopen_export import export_plcopen
from plclab.lang.unparse import unparse
from plclab.project import check_sources, parse_sources

POUS = """FUNCTION_BLOCK Adder
VAR_EXTERNAL level : DINT; END_VAR
level := level + 1;
END_FUNCTION_BLOCK

PROGRAM Count
VAR_EXTERNAL level : DINT; shared : INT; END_VAR
VAR a : Adder; seen : DINT; END_VAR
a();
shared := shared + 1;
seen := level;
END_PROGRAM
"""

TWO = POUS + """
CONFIGURATION Plant
VAR_GLOBAL shared : INT; END_VAR
RESOURCE ResA ON PLC
  VAR_GLOBAL level : DINT := 100; END_VAR
  TASK fast (INTERVAL := T#10ms, PRIORITY := 1);
  PROGRAM main WITH fast : Count;
END_RESOURCE
RESOURCE ResB ON PLC
  VAR_GLOBAL level : DINT := 200; END_VAR
  TASK slow (INTERVAL := T#20ms, PRIORITY := 2);
  PROGRAM main WITH slow : Count;
END_RESOURCE
END_CONFIGURATION
"""


def errors(src: str, name: str = "plant.st") -> list[tuple[str, str]]:
    _, diags = check_sources([(src, name)])
    return [(d.code, d.message) for d in diags if d.severity == "error"]


def check_two(plc) -> None:
    plc.scan(4)  # ResA runs at 0, 10, 20, 30 ms; ResB at 0 and 20 ms
    assert plc["ResA.main.seen"] == 104 and plc["ResB.main.seen"] == 202
    assert plc["ResA.level"] == 104 and plc["resb.LEVEL"] == 202
    assert plc["ResB.main.level"] == 202  # the VAR_EXTERNAL of an instance: its resource's
    assert plc["shared"] == 6  # the configuration's global: seen by both
    plc["ResB.level"] = 0
    plc.scan(1)
    assert plc["ResB.main.seen"] == 1 and plc["ResA.main.seen"] == 105


def test_two_resources_each_with_a_global_of_one_name() -> None:
    assert errors(TWO) == []
    plc = plclab.loads(TWO)
    assert [n for n, _, _ in plc.project.programs] == ["RESA.MAIN", "RESB.MAIN"]
    check_two(plc)


def test_the_st_and_plcopen_forms_write_each_resource_and_read_back_the_same() -> None:
    files, _ = parse_sources([(TWO, "plant.st")])
    own = [f for f in files if f.file == "plant.st"]
    check_two(plclab.loads(unparse(own[0])))
    xml = export_plcopen(own)
    assert xml.count("<resource ") == 2 and xml.count("<globalVars>") == 3
    check_two(plclab.loads(xml, filename="plant.xml"))


def test_a_global_of_another_resource_is_plc0285() -> None:
    src = TWO.replace("  VAR_GLOBAL level : DINT := 200; END_VAR\n", "")
    found = errors(src)
    assert [c for c, _ in found] == ["PLC0132", "PLC0132"]  # in Count and in its Adder
    assert "RESB.MAIN" in found[0][1] and "RESA" in found[0][1]


def test_a_global_of_another_type_in_one_resource_is_plc0103() -> None:
    src = TWO.replace("level : DINT := 200", "level : INT := 200")
    assert [c for c, _ in errors(src)] == ["PLC0103", "PLC0103"]


@pytest.mark.parametrize("twice", [
    "  VAR_GLOBAL level : DINT := 200; level : DINT; END_VAR\n",  # twice in one resource
    "  VAR_GLOBAL level : DINT := 200; shared : INT; END_VAR\n",  # also the configuration's
])
def test_a_name_twice_in_one_scope_is_plc0101(twice: str) -> None:
    src = TWO.replace("  VAR_GLOBAL level : DINT := 200; END_VAR\n", twice)
    assert [c for c, _ in errors(src)] == ["PLC0101"]


def test_one_resource_keeps_its_globals_and_paths_as_before() -> None:
    src = POUS + """
CONFIGURATION Plant
VAR_GLOBAL shared : INT; END_VAR
RESOURCE ResA ON PLC
  VAR_GLOBAL level : DINT := 100; END_VAR
  TASK fast (INTERVAL := T#10ms, PRIORITY := 1);
  PROGRAM main WITH fast : Count;
END_RESOURCE
END_CONFIGURATION
"""
    plc = plclab.loads(src)
    assert [n for n, _, _ in plc.project.programs] == ["MAIN"]
    plc.scan(2)
    assert plc["main.seen"] == 102 and plc["level"] == 102 and plc["shared"] == 2


def test_var_config_names_an_instance_by_its_resource() -> None:
    src = TWO.replace("END_CONFIGURATION", """VAR_CONFIG
  ResB.main.seen : DINT := 7;
END_VAR
END_CONFIGURATION""")
    plc = plclab.loads(src)
    assert plc["ResB.main.seen"] == 7 and plc["ResA.main.seen"] == 0
    files, _ = parse_sources([(src, "plant.st")])
    again = plclab.loads(unparse(next(f for f in files if f.file == "plant.st")))
    assert again["ResB.main.seen"] == 7 and again["ResA.main.seen"] == 0


def test_two_resources_may_each_have_a_task_of_one_name_and_retain_their_globals() -> None:
    src = TWO.replace("TASK slow (INTERVAL := T#20ms", "TASK fast (INTERVAL := T#20ms").replace(
        "WITH slow", "WITH fast").replace("VAR_GLOBAL level : DINT := 200;",
                                          "VAR_GLOBAL RETAIN level : DINT := 200;")
    assert errors(src) == []
    plc = plclab.loads(src)
    assert sorted(t.name for t in plc.tasks) == ["RESA.FAST", "RESB.FAST"]
    check_two(plc)
    assert "RESB.level" in plc.variables()
    plc.warm_restart()
    assert plc["ResB.level"] == 1 and plc["ResA.level"] == 100  # RETAIN kept, the other not
