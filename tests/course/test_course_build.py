"""``plclab course build`` regenerates every figure from real runs, into the folder asked for."""

from plclab.cli import main
from plclab.course.model import chapters


def test_build_writes_every_chapter_and_figure(tmp_path, capsys):
    out = tmp_path / "built"
    assert main(["course", "build", "--out", str(out)]) == 0, capsys.readouterr().err
    for c in chapters():
        dest = out / c.slug
        assert (dest / "chapter.md").read_text(encoding="utf-8") == c.text
        for ref in c.figure_refs:
            pic = dest / ref
            assert pic.exists(), pic
            head = pic.read_bytes()[:200]
            assert head.startswith(b"\x89PNG") or b"<svg" in head or b"<?xml" in head
    index = (out / "README.md").read_text(encoding="utf-8")
    assert "| **total** |" in index


def test_build_refuses_to_write_into_the_course_sources(capsys):
    src = chapters()[0].folder.parent
    assert main(["course", "build", "--out", str(src / "built")]) != 0
    assert "outside the course sources" in capsys.readouterr().err
    assert not (src / "built").exists()
