"""The pages the site is built from: every source is there, nothing private is."""

import base64
import re
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.problems import catalogue
from plclab.site import build as site_build
from plclab.site import pages
from plclab.site.links import relink

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def docs(tmp_path_factory):
    d = tmp_path_factory.mktemp("site-src") / "docs"
    site_build.generate(d, playground=False, figures=False)
    rep = relink(d, figures=False)
    assert not rep.broken, rep.broken
    return d


def test_one_page_per_code_with_its_wrong_and_right_program(docs):
    codes = catalogue()
    assert {p.name for p in (docs / "problems").iterdir() if p.is_dir()} == set(codes)
    page = (docs / "problems" / "PLC0013" / "index.md").read_text()
    assert "## Wrong" in page and "## Right" in page
    assert codes["PLC0013"].wrong.strip().splitlines()[0] in page


def test_every_chapter_is_a_page_and_its_examples_open_in_the_playground(docs):
    for ch in (REPO / "course").glob("[0-9][0-9]-*/chapter.md"):
        page = (docs / "course" / ch.parent.name / "index.md").read_text()
        links = re.findall(r'href="\.\./\.\./playground/#lang=(\w+)&code=([\w-]+)'
                           r'(?:&expect=(PLC\d{4}))?"', page)
        fences = re.findall(r"^```(st|il|ld)\b(.*)$", ch.read_text(), re.M)
        assert len(links) == len(fences) > 0, ch
        # a deliberate mistake's link says which code the page should expect
        assert [x[2] for x in links] == [(re.findall(r"error=(PLC\d{4})", f[1]) or [""])[0]
                                         for f in fences], ch
        lang, code, _ = links[0]
        fences = [f[0] for f in fences]
        text = base64.urlsafe_b64decode(code + "=" * (-len(code) % 4)).decode()
        assert text.strip() in ch.read_text() and lang == fences[0]


def test_the_glossary_is_a_page_linked_from_the_course(docs):
    page = (docs / "course" / "glossary.md").read_text(encoding="utf-8")
    assert "| **PLC** | программируемый логический контроллер (ПЛК) |" in page
    assert "## Index" in page and "](02-scan-cycle/index.md)" in page
    assert "](glossary.md)" in (docs / "course" / "index.md").read_text(encoding="utf-8")


def test_lab_pages_show_the_io_table_and_nothing_private(docs):
    page = (docs / "labs" / "tank-two-position" / "index.md").read_text()
    assert page.count("| `LS1` | `%IX0.0` | BOOL |") == 1  # the README's table, not twice
    assert page.count("| Criterion |") == 1 and "## Criteria" not in page
    listed = page.split("## Scenarios your program runs in")[1]
    assert "**normal**" in listed and "start-full" not in listed  # the hidden scenario
    assert "](../../course/" in page  # its links to the course lead to the chapters' pages
    for lab in (REPO / "labs").iterdir():
        if not (lab / "lab.toml").exists():
            continue
        text = (docs / "labs" / lab.name / "index.md").read_text()
        for private in list(lab.glob("solution/*")) + list(lab.glob("mistakes/*")):
            body = [ln for ln in private.read_text().splitlines()
                    if len(ln.strip()) > 25 and not ln.strip().startswith(("(*", "VAR", "END"))]
            public = "".join(p.read_text() for p in [*lab.glob("starter.*"), lab / "README.md"])
            leaked = [ln for ln in body if ln.strip() in text and ln.strip() not in public]
            assert not leaked, (private, leaked)
    labs_json = (docs / "playground" / "labs.json").read_text()
    assert "start-full" not in labs_json and '"tank-two-position"' in labs_json


def test_plants_have_a_picture_each(docs):
    import plants

    for name in plants.list_plants():
        svg = (docs / "reference" / "plants" / f"{name}.svg").read_text()
        assert svg.startswith("<svg") and svg.count("<") > 3
        assert f"]({name}.svg)" in (docs / "reference" / "plants" / f"{name}.md").read_text()


def test_compliance_list_blocks_and_adrs(docs):
    assert "Dialects" in (docs / "reference" / "compliance.md").read_text()
    assert "PID" in (docs / "reference" / "blocks.md").read_text()
    assert len(list((docs / "adr").glob("0*.md"))) == len(list((REPO / "docs/adr").glob("0*.md")))


def test_no_relative_link_points_nowhere(docs):
    for md in docs.rglob("*.md"):
        for target in re.findall(r"\]\(([^)\s#]+)[^)]*\)", md.read_text()):
            if not re.match(r"^[a-z]+:", target):
                assert (md.parent / target).exists(), (md, target)


def test_out_must_be_outside_the_source_tree_and_not_a_foreign_folder(tmp_path):
    with pytest.raises(PlcError) as e:
        site_build.check_out(REPO / "site-out")
    assert e.value.code == "PLC3040"
    (tmp_path / "notes.txt").write_text("mine")
    with pytest.raises(PlcError) as e:
        site_build.check_out(tmp_path)
    assert e.value.code == "PLC3041"
    (tmp_path / site_build.MARKER).write_text("")
    assert site_build.check_out(tmp_path) == tmp_path.resolve()


def test_notebooks_are_pages_with_their_code(docs):
    nbs = sorted((REPO / "notebooks").glob("*.ipynb"))
    assert nbs
    for nb in nbs:
        page = (docs / "notebooks" / f"{nb.stem}.md").read_text()
        assert "```python" in page and "PROGRAM" in page


def test_a_notebook_output_becomes_text_an_image_or_a_note(tmp_path):
    png = base64.b64encode(b"\x89PNG fake").decode()
    assert pages._output_md({"output_type": "stream", "text": ["12 of 12 points\n"]},
                            tmp_path, "nb", 1) == ["```text", "12 of 12 points", "```"]
    assert pages._output_md({"output_type": "display_data", "data": {"image/png": png}},
                            tmp_path, "nb", 2) == ["![output 2](nb-2.png)"]
    assert (tmp_path / "nb-2.png").read_bytes() == b"\x89PNG fake"
    widget = {"output_type": "display_data",
              "data": {"application/vnd.jupyter.widget-view+json": {}, "text/plain": "W"}}
    assert "interactive output" in pages._output_md(widget, tmp_path, "nb", 3)[0]
    md = {"output_type": "display_data", "data": {"text/markdown": "**12/18**",
                                                  "text/plain": "<Markdown object>"}}
    assert pages._output_md(md, tmp_path, "nb", 4) == ["**12/18**"]
