"""docs/labs.md lists every lab of the repository, generated from the labs' lab.toml."""

from __future__ import annotations

from pathlib import Path

import pytest

from plclab.grade.labs_doc import END, START, labs_table, updated

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "labs.md"


def test_docs_labs_md_holds_the_generated_table_of_every_lab():
    text = DOC.read_text(encoding="utf-8")
    table = labs_table(ROOT / "labs")
    assert updated(text, table) == text, (
        "docs/labs.md's table of labs is out of date: run python -m plclab.grade.labs_doc")
    ids = sorted(p.name for p in (ROOT / "labs").iterdir() if (p / "lab.toml").is_file())
    block = text.split(START, 1)[1].split(END, 1)[0]
    assert len(ids) >= 8
    for lab_id in ids:
        assert f"| `{lab_id}` |" in block, lab_id


def test_a_new_lab_appears_in_the_table(tmp_path):
    import shutil

    shutil.copytree(ROOT / "labs" / "tank-two-position", tmp_path / "tank-copy")
    table = labs_table(tmp_path)
    assert table.count("\n| `") == 1 and "| `tank-copy` |" in table
    with pytest.raises(ValueError):
        updated("no markers here", table)
