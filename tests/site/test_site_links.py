"""The site's link rewriting (plclab/site/links.py): a link is read relative to the source
file its page came from; a target the site publishes is linked to its page, a source file the
site does not publish is named as text, and a target that exists nowhere is reported."""

from __future__ import annotations

from plclab.site.links import relink, written_from


def page(docs, rel, text, source=None):
    path = docs / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    if source:
        written_from(path, source)
    return path


def test_links_follow_their_targets_to_the_sites_pages(tmp_path):
    docs = tmp_path / "docs"
    page(docs, "course/09-structured-text/index.md", "# ST\n")
    page(docs, "labs/tank-two-position/index.md", "# Tank\n")
    lab = page(docs, "labs/motor-start-stop/index.md",
               "[ch. 9](../../course/09-structured-text/chapter.md#loops) and "
               "[the tank](../tank-two-position/README.md), "
               "[the CLI](../../plclab/cli.py), [site](https://example.org/x.md)\n"
               "```st\n(* [not a link](../../nowhere.md) *)\n```\n",
               source="labs/motor-start-stop/README.md")
    nb = page(docs, "notebooks/tank.md", "[the lab](../labs/tank-two-position/)\n",
              source="notebooks/tank.ipynb")
    rep = relink(docs)
    assert not rep.broken
    text = lab.read_text()
    assert "[ch. 9](../../course/09-structured-text/index.md#loops)" in text
    assert "[the tank](../tank-two-position/index.md)" in text
    assert "the CLI (`plclab/cli.py`)" in text  # named, not a dead link
    assert "(https://example.org/x.md)" in text
    assert "[not a link](../../nowhere.md)" in text  # code is left alone
    assert nb.read_text() == "[the lab](../labs/tank-two-position/index.md)\n"
    assert (rep.rewritten, rep.as_text) == (3, 1)


def test_a_link_to_nothing_is_reported_with_its_source(tmp_path):
    docs = tmp_path / "docs"
    page(docs, "course/01-what-is-a-plc/index.md",
         "[next](../02-scan/chapter.md) ![f](figures/x.svg)\n",
         source="course/01-what-is-a-plc/chapter.md")
    page(docs, "index.md", "[gone](labs/none/index.md)\n")  # a page the build wrote itself
    rep = relink(docs)
    assert sorted(rep.broken) == [
        "course/01-what-is-a-plc/index.md (from course/01-what-is-a-plc/chapter.md): "
        "../02-scan/chapter.md",
        "course/01-what-is-a-plc/index.md (from course/01-what-is-a-plc/chapter.md): "
        "figures/x.svg",
        "index.md: labs/none/index.md"]
    # a build that does not draw figures shows a missing figure's caption instead
    assert len(relink(docs, figures=False).broken) == 2
