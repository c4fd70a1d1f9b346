"""The parts of ``plclab opcua`` that need no client: type mapping, access rules, the tag tree,
and the command line's refusals (each a PlcError with its code, never a traceback)."""

from __future__ import annotations

import math
import re
import socket

import pytest

import plclab
from plclab.cli import main
from plclab.errors import PlcError
from plclab.lang import types as T
from plclab.opcua.access import Access, load_access
from plclab.opcua.quality import OUT_OF_SERVICE, SENSOR_FAILURE, tag_status
from plclab.opcua.tags import apply_rules, build_tree
from plclab.opcua.typemap import KINDS, from_ua, kind_of, to_ua

PROGRAM = """\
TYPE Pair : STRUCT lo : INT; hi : REAL; END_STRUCT; END_TYPE
PROGRAM Main
VAR
  raw AT %IW2 : INT;
  sp : REAL := 50.0;
  sp1 : LREAL; sp2 : LREAL;
  pump AT %QX0.0 : BOOL;
  pair : Pair;
  t1 : TON;
  tmp_not_shown : INT;
END_VAR
VAR CONSTANT K : INT := 3; END_VAR
pump := raw > 100; pair.lo := raw; t1(IN := pump, PT := T#1s); tmp_not_shown := K;
END_PROGRAM
"""


@pytest.fixture
def plc():
    return plclab.loads(PROGRAM)


# ---------------------------------------------------------------------- types


@pytest.mark.parametrize("iec, ua", [
    ("BOOL", "Boolean"), ("SINT", "SByte"), ("INT", "Int16"), ("DINT", "Int32"),
    ("LINT", "Int64"), ("USINT", "Byte"), ("UINT", "UInt16"), ("UDINT", "UInt32"),
    ("ULINT", "UInt64"), ("BYTE", "Byte"), ("WORD", "UInt16"), ("DWORD", "UInt32"),
    ("LWORD", "UInt64"), ("REAL", "Float"), ("LREAL", "Double"), ("TIME", "Duration"),
    ("LTIME", "Duration"), ("DATE", "DateTime"), ("DT", "DateTime"), ("TOD", "Duration"),
])
def test_every_elementary_type_has_its_opc_ua_type(iec, ua):
    assert kind_of(iec) == ua
    assert set(KINDS) >= {iec}


def test_strings_and_aggregates():
    assert kind_of(T.STRING) == "String" and kind_of(T.WSTRING) == "String"
    assert kind_of(T.ArrayType([(1, 3)], T.INT)) is None


@pytest.mark.parametrize("iec, plc_value", [
    ("TIME", 1500), ("LTIME", 2_000_000), ("TOD", 43_201_000), ("DATE", 1_704_153_600),
    ("DT", 1_704_164_645_000), ("INT", -7), ("REAL", 2.5), ("BOOL", True),
])
def test_values_go_there_and_back(iec, plc_value):
    ty = T.lookup_elementary(iec)
    assert from_ua(to_ua(plc_value, ty), ty) == plc_value


def test_time_is_milliseconds_whatever_the_plc_keeps():
    assert to_ua(1500, T.TIME) == 1500.0            # TIME: ms
    assert to_ua(2_000_000, T.LTIME) == 2.0          # LTIME: ns
    assert to_ua(0, T.DT).year == 1970


@pytest.mark.parametrize("iec, value", [
    ("INT", 40000), ("INT", True), ("INT", 1.5), ("USINT", -1), ("BOOL", 1),
    ("REAL", math.nan), ("REAL", math.inf), ("REAL", "1"), ("TIME", math.nan),
    ("DATE", 5), ("LINT", 2**63),
])
def test_values_a_client_may_not_write(iec, value):
    with pytest.raises(ValueError):
        from_ua(value, T.lookup_elementary(iec))


def test_a_string_longer_than_declared_is_refused():
    ty = T.StringType(False, 4)
    assert from_ua("abcd", ty) == "abcd"
    with pytest.raises(ValueError):
        from_ua("abcde", ty)


# ---------------------------------------------------------------------- the tree


def test_tree_by_pou_and_instance(plc):
    tree = build_tree(plc)
    paths = {t.path: t for t in tree.tags}
    assert {"Main.raw", "Main.sp", "Main.pair.lo", "Main.pair.hi", "Main.t1.ET",
            "Main.t1.Q", "Main.K"} <= set(paths)
    assert paths["Main.t1.ET"].browse == ("Programs", "Main", "t1", "ET")
    assert ("Programs", "Main", "pair") in tree.folders
    assert paths["Main.raw"].address == "%IW2" and paths["Main.pump"].kind == "Boolean"
    assert not any(p.startswith("__") or ".__" in p for p in paths)


def test_every_tag_reads_through_the_plc(plc):
    plc.scan()
    for tag in build_tree(plc).tags:
        assert tag.var.get() == plc[tag.path]


# ---------------------------------------------------------------------- access rules


def rules(*writable: str) -> Access:
    return load_access(writable=list(writable))


def test_default_is_read_only(plc):
    tree = build_tree(plc)
    assert apply_rules(tree, Access()) == []
    assert not any(t.writable for t in tree.tags)
    assert Access().role(None) == "read"


def test_patterns_name_set_points(plc):
    tree = build_tree(plc)
    marked = apply_rules(tree, rules("Main.sp?", "main.RAW"))
    assert sorted(t.path for t in marked) == ["Main.raw", "Main.sp1", "Main.sp2"]
    assert not tree.by_path()["MAIN.SP"].writable


@pytest.mark.parametrize("rule, words", [
    ("Main.spp", "did you mean Main.sp"),           # a typo
    ("Main.pump", "output (%QX0.0)"),               # an output
    ("Main.K", "CONSTANT"),                          # a constant
    ("Main.t1.Q", "VAR_OUTPUT of a block"),          # the block writes it
    ("Other.*", "names no variable"),                # a pattern that matches nothing
])
def test_rules_that_name_nothing_writable_are_refused(plc, rule, words):
    with pytest.raises(PlcError) as e:
        apply_rules(build_tree(plc), rules(rule))
    assert e.value.code == "PLC7053" and words in e.value.message


def test_an_input_the_plant_drives_is_refused(plc):
    with pytest.raises(PlcError) as e:
        apply_rules(build_tree(plc), rules("Main.raw"), {"%IW2": "LEVEL"})
    assert e.value.code == "PLC7053" and "LEVEL" in e.value.message


CONFIG = """\
anonymous = "none"
writable = ["Main.sp"]
[[user]]
name = "op"
password = "pw"
[[user]]
name = "look"
password_sha256 = "{sha}"
role = "read"
"""


def test_config_file_users_and_logins(tmp_path):
    import hashlib

    f = tmp_path / "opcua.toml"
    f.write_text(CONFIG.format(sha=hashlib.sha256(b"eyes").hexdigest()), encoding="utf-8")
    acc = load_access(str(f))
    assert acc.writable == ["Main.sp"] and acc.anonymous == "none"
    assert acc.login("op", "pw") == "op" and acc.login("look", "eyes") == "look"
    for name, pw in [("op", "wrong"), ("look", "pw"), ("nobody", "pw"), (None, None)]:
        with pytest.raises(KeyError):
            acc.login(name, pw)
    assert acc.role("op") == "write" and acc.role("look") == "read"


@pytest.mark.parametrize("text, words", [
    ("anonymous = 'readonly'", "anonymous"),
    ("port = '4840'", "port is a whole number"),
    ("colour = 1", "unknown key"),
    ("writable = 'Main.sp'", "list of variables"),
    ("[[user]]\nname = 'a'", "needs a password"),
    ("[[user]]\nname = 'a'\npassword = 'p'\n[[user]]\nname = 'a'\npassword = 'q'", "twice"),
    ("[[user]]\nname = 'a'\npassword_sha256 = 'abc'", "64 hex digits"),
    ("[[user]]\nname = 'a'\npassword = 'p'\nrole = 'admin'", "role"),
    ("[[user]]\nname = 'a'\npasword = 'p'", "unknown key"),
    ("this is not toml", "not valid TOML"),
])
def test_bad_config_files(tmp_path, text, words):
    f = tmp_path / "opcua.toml"
    f.write_text(text, encoding="utf-8")
    with pytest.raises(PlcError) as e:
        load_access(str(f))
    assert e.value.code in ("PLC7053", "PLC7054") and words in e.value.message, e.value.message


def test_user_from_the_command_line_needs_the_environment(monkeypatch):
    monkeypatch.delenv("PLCLAB_OPCUA_PASSWORD", raising=False)
    with pytest.raises(PlcError) as e:
        load_access(user="op")
    assert e.value.code == "PLC7054" and "PLCLAB_OPCUA_PASSWORD" in e.value.message
    monkeypatch.setenv("PLCLAB_OPCUA_PASSWORD", "pw")
    assert load_access(user="op").login("op", "pw") == "op"


# ---------------------------------------------------------------------- quality


def test_status_of_a_tag(plc):
    tags = build_tree(plc).by_path()
    raw, sp = tags["MAIN.RAW"], tags["MAIN.SP"]
    assert tag_status(raw, True, set()) == "Good"
    assert tag_status(raw, True, {"%IW2"}) == SENSOR_FAILURE
    assert tag_status(sp, True, {"%IW2"}) == "Good"
    assert tag_status(sp, False, set()) == OUT_OF_SERVICE


# ---------------------------------------------------------------------- the command line


@pytest.fixture
def prog(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "main.st").write_text(PROGRAM, encoding="utf-8")
    return "main.st"


@pytest.mark.parametrize("args, code, words", [
    (["--host", "0.0.0.0"], "PLC7052", "--allow-remote"),
    (["--host", "192.168.1.20"], "PLC7052", "127.0.0.1"),
    (["--port", "70000"], "PLC7055", "1..65535"),
    (["--period", "0"], "PLC7055", "--period"),
    (["--speed", "-1"], "PLC7055", "--speed"),
    (["--writable", "Main.pumpp"], "PLC7053", "did you mean Main.pump"),
    (["--scenario", "break.toml"], "PLC7055", "need a plant"),
    (["--lab", "water-boiler", "--scenario", "no-such"], "PLC7055", "has no scenario"),
    (["--config", "missing.toml"], "PLC7054", "cannot read"),
])
def test_command_line_refusals(prog, capsys, args, code, words):
    assert main(["opcua", prog, *args, "--list"]) == 1
    err = capsys.readouterr().err
    assert code in err and words in err and "Traceback" not in err, err


def test_allow_remote_and_list(prog, capsys):
    assert main(["opcua", prog, "--host", "0.0.0.0", "--allow-remote", "--writable",
                 "Main.sp", "--list"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"ns=2;s=Main.sp +Float +writable", out), out
    assert re.search(r"ns=2;s=Main.pump +Boolean +read-only  %QX0.0", out), out


def test_a_port_in_use_is_plc7051(prog, capsys):
    pytest.importorskip("asyncua")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        assert main(["opcua", prog, "--port", str(port), "--duration", "1"]) == 1
    err = capsys.readouterr().err
    assert "PLC7051" in err and "--port" in err and "Traceback" not in err, err
