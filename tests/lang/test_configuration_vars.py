"""VAR_CONFIG and VAR_ACCESS (IEC 61131-3 ed.3 6.8.2, Table 62; the example configuration of
Figure 21 gives block instances deep inside program instances their addresses and initial
values, and publishes variables and addresses under access names). The CODESYS form, a
VAR_CONFIG list outside any CONFIGURATION, is accepted too (CODESYS online help, "VAR_CONFIG")."""

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.unparse import unparse
from plclab.project import check_sources, parse_sources

STATION = """
FUNCTION_BLOCK Station
VAR_INPUT sensor AT %I* : BOOL; END_VAR
VAR_OUTPUT lamp AT %Q* : BOOL; END_VAR
VAR count : INT; limit : INT := 3; END_VAR
IF sensor THEN count := count + 1; END_IF
lamp := count >= limit;
END_FUNCTION_BLOCK

PROGRAM Line
VAR s1 : Station; s2 : Station; level AT %I* : INT; copy : INT; END_VAR
s1();
s2();
copy := level;
END_PROGRAM
"""

CONFIG = STATION + """
CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms);
        PROGRAM P1 WITH Fast : Line;
    END_RESOURCE
    VAR_CONFIG
        Cpu.P1.s1.sensor AT %IX0.0 : BOOL;
        P1.s1.lamp AT %QX0.0 : BOOL;
        P1.s2.sensor AT %IX0.1 : BOOL;
        P1.s2.lamp AT %QX0.1 : BOOL;
        P1.s2.limit : INT := 10;
        P1.level AT %IW2 : INT;
    END_VAR
    VAR_ACCESS
        LAMP1 : Cpu.P1.s1.lamp : BOOL READ_ONLY;
        LIMIT2 : P1.s2.limit : INT READ_WRITE;
        RAW : Cpu.%IW2 : INT READ_ONLY;
    END_VAR
END_CONFIGURATION
"""


def test_each_block_instance_gets_its_own_address_and_initial_value() -> None:
    plc = plclab.loads(CONFIG)
    located = {v.path: v.address for v in plc.project.symbols.located_vars()}
    assert located == {"P1.level": "%IW2", "P1.s1.sensor": "%IX0.0", "P1.s1.lamp": "%QX0.0",
                       "P1.s2.sensor": "%IX0.1", "P1.s2.lamp": "%QX0.1"}
    assert (plc["P1.s1.limit"], plc["P1.s2.limit"]) == (3, 10)
    plc["%IX0.0"] = True  # only s1's sensor
    plc["%IW2"] = 1234
    plc.scan(3)
    assert (plc["P1.s1.count"], plc["P1.s2.count"]) == (3, 0)
    assert (plc["%QX0.0"], plc["%QX0.1"], plc["P1.copy"]) == (True, False, 1234)
    plc.cold_restart()  # the configuration's initial values come back with the instances
    assert (plc["P1.s2.limit"], plc["P1.s1.count"]) == (10, 0)


def test_access_paths_read_the_variable_and_read_only_refuses_writes() -> None:
    plc = plclab.loads(CONFIG)
    plc["%IX0.0"] = True
    plc["%IW2"] = 77
    plc.scan(3)
    assert (plc["LAMP1"], plc["LIMIT2"], plc["RAW"]) == (True, 10, 77)
    plc["LIMIT2"] = 2
    assert plc["P1.s2.limit"] == 2
    with pytest.raises(PlcError) as err:
        plc["LAMP1"] = False
    assert err.value.code == "PLC3013" and "READ_WRITE" in str(err.value)


def test_a_codesys_var_config_list_outside_a_configuration() -> None:
    src = STATION + """
VAR_CONFIG
    Line.s1.sensor AT %IX1.0 : BOOL;
    Line.s1.limit : INT := 1;
END_VAR
"""
    plc = plclab.loads(src)
    plc["%IX1.0"] = True
    plc.scan()
    assert (plc["Line.s1.count"], plc["Line.s1.lamp"]) == (1, True)


def test_the_printed_configuration_reads_back_the_same() -> None:
    files, diags = parse_sources([(CONFIG, "plant.st")])
    assert not [d for d in diags if d.severity == "error"]
    again = plclab.loads(unparse(next(f for f in files if f.file == "plant.st")))
    assert set(again.project.symbols.access_paths) == {"LAMP1", "LIMIT2", "RAW"}
    assert len(again.project.symbols.config_bindings) == 6


def configured(lines: str, access: str = "") -> str:
    return STATION + f"""
CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        PROGRAM P1 : Line;
    END_RESOURCE
    VAR_CONFIG
{lines}
    END_VAR
    {access}
END_CONFIGURATION
"""


BAD = {
    "unknown instance": (configured("P2.s1.sensor AT %IX0.0 : BOOL;"), "PLC0100", "P1"),
    "unknown member, with a hint": (configured("P1.s1.sensr AT %IX0.0 : BOOL;"), "PLC0100",
                                    "SENSOR"),
    "a path through a plain variable": (configured("P1.copy.x : INT := 1;"), "PLC0116",
                                        "no members"),
    "only a program instance": (configured("P1 : Line;"), "PLC0100", "P1.x"),
    "no wildcard to complete": (configured("P1.s1.count AT %MW4 : INT;"), "PLC0120",
                                "wildcard"),
    "an output given an input address": (configured("P1.s1.lamp AT %IX0.0 : BOOL;"),
                                         "PLC0120", "%Q"),
    "the wrong type": (configured("P1.s1.limit : DINT := 5;"), "PLC0103", "INT"),
    "configured twice": (configured("P1.s1.limit : INT := 5;\nP1.s1.limit : INT := 6;"),
                         "PLC0101", "twice"),
    "an access name taken": (configured("", "VAR_ACCESS P1 : P1.copy : INT; END_VAR"),
                             "PLC0101", "another name"),
    "an access path of the wrong type": (
        configured("", "VAR_ACCESS C : P1.copy : BOOL READ_ONLY; END_VAR"), "PLC0103", "INT"),
}


@pytest.mark.parametrize("name", list(BAD))
def test_a_wrong_configuration_line_is_reported_where_it_is(name: str) -> None:
    src, code, words = BAD[name]
    _, diags = check_sources([(src, "plant.st")])
    errors = [d for d in diags if d.severity == "error"]
    assert errors and errors[0].code == code, errors
    assert words in errors[0].message
    assert errors[0].location is not None and errors[0].location.line > STATION.count("\n")


COUNTER = """
VAR_GLOBAL total : INT; enable : BOOL := TRUE; END_VAR
PROGRAM Counter
VAR_INPUT pulse : BOOL; run : BOOL; step : INT; END_VAR
VAR_OUTPUT count : INT; busy : BOOL; END_VAR
IF run AND pulse THEN count := count + step; END_IF
busy := count > 0;
END_PROGRAM
CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms);
        {instances}
    END_RESOURCE
END_CONFIGURATION
"""


def test_program_instances_take_inputs_and_hand_on_outputs_through_their_connections() -> None:
    plc = plclab.loads(COUNTER.format(instances="""
        PROGRAM C1 WITH Fast : Counter(pulse := %IX0.0, run := enable, step := 2,
                                        count => total, busy => %QX0.0);
        PROGRAM C2 WITH Fast : Counter(pulse := %IX0.1, run := TRUE, step := 5,
                                        busy => %QX0.1);"""))
    plc.scan()
    assert (plc["total"], plc["%QX0.0"], plc["C2.count"]) == (0, False, 0)
    plc["%IX0.0"] = True
    plc["%IX0.1"] = True
    plc.scan(2)
    assert (plc["total"], plc["%QX0.0"], plc["C2.count"], plc["%QX0.1"]) == (4, True, 10, True)
    plc["enable"] = False  # a global connected to an input is read at every call
    plc.scan(2)
    assert (plc["total"], plc["C1.count"]) == (4, 4)


@pytest.mark.parametrize("connections, code, words", [
    ("Counter(pulse := %IX0.0, speed := 3)", "PLC0107", "SPEED"),
    ("Counter(count => 5)", "PLC0105", "must be a variable"),
    ("Counter(run := 7)", "PLC0118", "BOOL"),
])
def test_a_wrong_connection_is_reported(connections: str, code: str, words: str) -> None:
    src = COUNTER.format(instances=f"PROGRAM C1 WITH Fast : {connections};")
    _, diags = check_sources([(src, "plant.st")])
    errors = [d for d in diags if d.severity == "error"]
    assert errors and errors[0].code == code, errors
    assert words in errors[0].message and errors[0].location.line == 12


def test_var_config_reaches_inherited_wildcards_of_a_derived_block() -> None:
    """Issue 14: located variables inside derived FBs -- an AT %I* declared in the base block is
    a member of every derived instance, and VAR_CONFIG completes it there."""
    src = """
FUNCTION_BLOCK Base
VAR_INPUT sensor AT %I* : BOOL; END_VAR
VAR_OUTPUT lamp AT %Q* : BOOL; END_VAR
lamp := sensor;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Derived EXTENDS Base
VAR count : INT; END_VAR
SUPER^();
IF sensor THEN count := count + 1; END_IF
END_FUNCTION_BLOCK
PROGRAM Main
VAR d : Derived; END_VAR
d();
END_PROGRAM
VAR_CONFIG
    Main.d.sensor AT %IX0.2 : BOOL;
    Main.d.lamp AT %QX0.5 : BOOL;
END_VAR
"""
    plc = plclab.loads(src)
    plc["%IX0.2"] = True
    plc.scan(2)
    assert (plc["%QX0.5"], plc["Main.d.count"]) == (True, 2)
