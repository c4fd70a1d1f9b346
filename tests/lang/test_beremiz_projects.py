"""A PLCopen XML file is read in the dialect of the tool that wrote it (issue 33): Beremiz and
OpenPLC Editor compile with MATIEC, so their files are ``matiec`` without an option; a pragma or
``--dialect`` still wins; names that a Beremiz extension declares are PLC0246 naming it."""

import pytest

from plclab.cli import main
from plclab.lang.dialect import explain_choice, origin
from plclab.project import check_sources

PLC_XML = """<?xml version='1.0' encoding='utf-8'?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
  <fileHeader companyName="{company}" productName="{product}" productVersion="1"
              creationDateTime="2018-07-27T13:19:12"/>
  <contentHeader name="Unnamed" modificationDateTime="2022-07-21T11:39:43"/>
  <types>
    <dataTypes/>
    <pous>
      <pou name="Main" pouType="program">
        <interface>
          <localVars>
            <variable name="level" address="%QD0.2"><type><DINT/></type></variable>
          </localVars>
          {externals}
        </interface>
        <body><ST><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml"><![CDATA[
level := level + 1;
]]></xhtml:p></ST></body>
      </pou>
    </pous>
  </types>
  <instances>
    <configurations>
      <configuration name="Config0">
        <resource name="Res0">
          <task name="T" interval="T#20ms" priority="0"><pouInstance name="M" typeName="Main"/></task>
        </resource>
      </configuration>
    </configurations>
  </instances>
</project>
"""
PYVAR = ('<externalVars><variable name="PyVar0"><type><INT/></type></variable></externalVars>')


def write(folder, company="Beremiz", product="Beremiz", externals="", beremiz=False):
    folder.mkdir(parents=True, exist_ok=True)
    f = folder / "plc.xml"
    f.write_text(PLC_XML.format(company=company, product=product, externals=externals),
                 encoding="utf-8")
    if beremiz:
        (folder / "beremiz.xml").write_text("<BeremizRoot/>", encoding="utf-8")
    return f


def errors(f, dialect=None):
    _, diags = check_sources([(f.read_text(encoding="utf-8"), str(f))], dialect)
    return [d for d in diags if d.severity == "error"]


@pytest.mark.parametrize("company,product", [("Beremiz", "Beremiz"), ("beremiz", "beremiz"),
                                             ("Unknown", "Unnamed"), ("", "Beremiz"),
                                             ("Unknown", "OpenPLC")])
def test_beremiz_and_openplc_files_are_read_as_matiec(tmp_path, company, product):
    f = write(tmp_path, company, product)
    assert origin(f.read_text(), str(f))[0] == "matiec"
    assert errors(f) == []


def test_a_beremiz_project_file_beside_it_is_enough(tmp_path):
    f = write(tmp_path, "SMARTEH d.o.o.", "LHC2", beremiz=True)
    assert explain_choice(f.read_text(), None, str(f)) == (
        "matiec", "a Beremiz project file (beremiz.xml) lies beside it")
    assert errors(f) == []


def test_other_tools_keep_the_default_and_an_option_wins(tmp_path):
    other = write(tmp_path / "codesys", "CODESYS", "CODESYS V3.5")
    assert origin(other.read_text(), str(other)) is None
    assert [d.code for d in errors(other)]  # %QD0.2 has no bit part in codesys
    beremiz = write(tmp_path / "bz")
    assert [d.code for d in errors(beremiz, "codesys")]  # --dialect codesys wins
    text = beremiz.read_text().replace("level := level + 1;", "{dialect 'codesys'}\nlevel := 1;")
    assert explain_choice(text, None, str(beremiz))[1] == "its {dialect} pragma"


def test_a_name_from_an_extension_is_plc0246_naming_it(tmp_path):
    f = write(tmp_path, externals=PYVAR, beremiz=True)
    (tmp_path / "py_ext_0@py_ext").mkdir()
    (diag,) = errors(f)
    assert diag.code == "PLC0246"
    assert "PYVAR0" in diag.message and "Python (py_ext)" in diag.message
    # the same file outside a Beremiz project: the ordinary error
    plain = write(tmp_path / "plain", "CODESYS", "CODESYS", externals=PYVAR)
    assert [d.code for d in errors(plain)] != ["PLC0246"]


def test_extension_names_follow_the_chosen_dialect_not_the_mere_option(tmp_path):
    f = write(tmp_path, externals=PYVAR, beremiz=True)
    (tmp_path / "py_ext_0@py_ext").mkdir()
    # --dialect matiec (what the origin would choose anyway): still the extension's name
    assert [d.code for d in errors(f, "matiec")] == ["PLC0246"]
    # read as another dialect on purpose: the ordinary error of that dialect
    assert "PLC0246" not in [d.code for d in errors(f, "iec")]


def test_check_verbose_says_which_dialect_and_why(tmp_path, capsys):
    f = write(tmp_path)
    assert main(["check", "-v", str(f)]) == 0
    assert "dialect matiec (its PLCopen fileHeader names Beremiz)" in capsys.readouterr().out


STRUCT_XML = """<?xml version='1.0' encoding='utf-8'?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
  <fileHeader companyName="Beremiz" productName="Beremiz" productVersion="1"
              creationDateTime="2024-01-02T10:00:00"/>
  <contentHeader name="Topics" modificationDateTime="2024-01-02T10:00:00"/>
  <types>
    <dataTypes>
      <dataType name="Reading">
        <baseType><struct>
          <variable name="a"><type><DINT/></type></variable>
          <variable name="b"><type><DINT/></type></variable>
        </struct></baseType>
      </dataType>
    </dataTypes>
    <pous>
      <pou name="Main" pouType="program">
        <interface>
          <localVars>
            <variable name="topic" address="%I{channel}.0"><type><derived name="Reading"/></type>
              <initialValue><structValue>
                <value member="a"><simpleValue value="4"/></value>
                <value member="b"><simpleValue value="5"/></value>
              </structValue></initialValue></variable>
            <variable name="sum" address="%QD0.1"><type><DINT/></type></variable>
          </localVars>
        </interface>
        <body><ST><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml"><![CDATA[
sum := topic.a * 10 + topic.b;
]]></xhtml:p></ST></body>
      </pou>
    </pous>
  </types>
  <instances>
    <configurations>
      <configuration name="Config0">
        <resource name="Res0">
          <task name="T" interval="T#20ms" priority="0"><pouInstance name="M" typeName="Main"/></task>
        </resource>
      </configuration>
    </configurations>
  </instances>
</project>
"""


def struct_project(folder, channel="3", extension=True):
    folder.mkdir(parents=True, exist_ok=True)
    f = folder / "plc.xml"
    f.write_text(STRUCT_XML.format(channel=channel), encoding="utf-8")
    if extension:
        (folder / "beremiz.xml").write_text("<BeremizRoot/>", encoding="utf-8")
        ext = folder / "mqtt_0@mqtt"
        ext.mkdir()
        (ext / "baseconfnode.xml").write_text(
            '<BaseParams IEC_Channel="3" Name="mqtt_0"/>', encoding="utf-8")
        other = folder / "modbus_0@modbus"
        other.mkdir()
        (other / "baseconfnode.xml").write_text(
            '<BaseParams IEC_Channel="1" Name="modbus_0"/>', encoding="utf-8")
    return f


def test_a_structured_located_variable_of_an_extension_compiles_as_matiec_does(tmp_path):
    """MATIEC accepts ``topic AT %I3.0 : Reading`` (an MQTT topic read as a whole, ADR 0059):
    plclab compiles it with PLC0340 naming the extension of channel 3, keeps the variable out
    of the process image, and the program reads its value."""
    import plclab

    f = struct_project(tmp_path / "p")
    _, diags = check_sources([(f.read_text(encoding="utf-8"), str(f))])
    assert not [d for d in diags if d.severity == "error"]
    warned = [d for d in diags if d.code == "PLC0340"]
    assert len(warned) == 1 and warned[0].severity == "warning"
    assert "MQTT (mqtt_0@mqtt)" in warned[0].message and "channel 3" in warned[0].message
    assert "modbus" not in warned[0].message.lower()
    plc = plclab.load(str(f))
    plc.scan()
    assert plc.get("M.sum") == 45


def test_the_extension_is_named_by_its_channel_and_other_dialects_refuse(tmp_path):
    f = struct_project(tmp_path / "p", channel="1")  # the Modbus extension's channel
    _, diags = check_sources([(f.read_text(encoding="utf-8"), str(f))])
    (w,) = [d for d in diags if d.code == "PLC0340"]
    assert "Modbus (modbus_0@modbus)" in w.message and "MQTT" not in w.message
    g = struct_project(tmp_path / "q", extension=False)  # no project folder: the channel only
    _, diags = check_sources([(g.read_text(encoding="utf-8"), str(g))])
    (w,) = [d for d in diags if d.code == "PLC0340"]
    assert "IEC channel 3" in w.message and "MQTT" not in w.message
    assert "PLC0120" in [d.code for d in errors(f, "codesys")]
    assert "PLC0120" in [d.code for d in errors(f, "iec")]


@pytest.mark.parametrize("hmi, base", [("HMI_NODE", "BOOL"), ("HMI_INT", "INT")])
def test_an_svg_hmi_type_names_its_base_type_as_beremiz_declares_it(tmp_path, hmi, base):
    f = write(tmp_path / "p", beremiz=True, externals=(
        f'<localVars><variable name="n"><type><derived name="{hmi}"/></type></variable>'
        '</localVars>'))
    (e,) = [d for d in errors(f) if d.code == "PLC0246"]
    assert f"TYPE {hmi} : {base}; END_TYPE" in e.message


def test_explain_dialect_lists_the_structured_located_variable(tmp_path, capsys):
    f = struct_project(tmp_path / "p")
    assert main(["check", "--explain-dialect", str(f)]) == 0
    out = capsys.readouterr().out
    assert "PLC0340 (matiec)" in out and "iec: PLC0120" in out
    assert "without a warning" not in out
