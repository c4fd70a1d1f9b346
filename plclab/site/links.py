"""Links of the generated pages: a link written in a source file of the repository (a lab's
README to its chapter, a notebook to a lab) is rewritten to the page the site made from its
target; a link to a source file the site does not publish becomes code text naming the file;
a link whose target exists nowhere is an error of the source, and the build fails on it.

Each page knows the repository file it came from (:data:`SOURCES` is filled by
:func:`written_from`), so its links are read relative to that file, as on GitHub.

>>> site_page("course/09-structured-text/chapter.md")
'course/09-structured-text/index.md'
>>> site_page("labs/tank-two-position/")
'labs/tank-two-position/index.md'
>>> site_page("labs/tank-two-position/README.ru.md"), site_page("course/02-scan-cycle/chapter.ru.md")
('labs/tank-two-position/index.md', 'course/02-scan-cycle/index.md')
>>> site_page("plclab/cli.py") is None
True
"""

from __future__ import annotations

import posixpath
import re
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LINK = re.compile(r"(!?)\[([^\]]*)\]\(([^)\s]+)\)")
_FENCE = re.compile(r"^(`{3,}|~{3,}).*?^\1", re.S | re.M)

SOURCES: dict[Path, str] = {}
"""A generated page (its file) -> the repository file (relative path) it was made from."""


def written_from(page: Path, source: str) -> Path:
    """Record that the page file ``page`` shows the repository file ``source``; returns it."""
    SOURCES[page.resolve()] = source
    return page


def site_page(target: str) -> str | None:
    """The page (below ``docs``) the site makes of a repository path, or None when the site
    does not publish it."""
    t = target.rstrip("/")
    rules = [
        # a translated file (chapter.ru.md) is its edition's page of the same name
        (r"course/([\w-]+)/chapter(?:\.[a-z]{2})?\.md", r"course/\1/index.md"),
        (r"course(?:/README(?:\.[a-z]{2})?\.md)?", "course/index.md"),
        (r"labs/([\w-]+)(?:/README(?:\.[a-z]{2})?\.md)?", r"labs/\1/index.md"),
        (r"labs(?:/README(?:\.[a-z]{2})?\.md)?", "labs/index.md"),
        (r"notebooks/([\w-]+)\.ipynb", r"notebooks/\1.md"),
        (r"notebooks(?:/README\.md)?", "notebooks/index.md"),
        (r"docs/blocks\.md", "reference/blocks.md"),
        (r"docs/adr/(\d{4}-[\w.-]+\.md)", r"adr/\1"),
        (r"docs/adr", "adr/index.md"),
        (r"plants", "reference/plants/index.md"),
    ]
    for pattern, page in rules:
        if re.fullmatch(pattern, t):
            return re.sub(pattern, page, t)
    return None


@dataclass
class LinkReport:
    rewritten: int = 0
    as_text: int = 0
    broken: list[str] = field(default_factory=list)


def relink(docs: Path, figures: bool = True) -> LinkReport:
    """Rewrite the relative links of every page below ``docs`` (see the module's text);
    links inside code blocks are left alone. Without ``figures`` (a build that does not draw
    the course's figures) a picture of a chapter's ``figures/`` folder becomes its caption."""
    rep = LinkReport()
    for md in sorted(docs.rglob("*.md")):
        page = md.relative_to(docs).as_posix()
        text = md.read_text(encoding="utf-8")
        new = _outside_code(text, lambda part, page=page: LINK.sub(
            lambda m: _one(m, page, docs, rep, figures), part))
        if new != text:
            md.write_text(new, encoding="utf-8")
    return rep


def _outside_code(text: str, fix) -> str:
    out, last = [], 0
    for m in _FENCE.finditer(text):
        out += [fix(text[last:m.start()]), m.group(0)]
        last = m.end()
    return "".join(out + [fix(text[last:])])


def _one(m: re.Match[str], page: str, docs: Path, rep: LinkReport, figures: bool) -> str:
    bang, label, target = m.groups()
    path, _, anchor = target.partition("#")
    if not path or re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("/"):
        return m.group(0)
    here = posixpath.dirname(page)
    source = SOURCES.get((docs / page).resolve())
    if source is None:  # a page the build wrote itself: its links point into the site
        if (docs / here / path).exists():
            return m.group(0)
        rep.broken.append(f"{page}: {target}")
        return m.group(0)
    in_repo = posixpath.normpath(posixpath.join(posixpath.dirname(source), path))
    mapped = site_page(in_repo)
    if mapped is not None and (docs / mapped).exists():
        rep.rewritten += 1
        rel = posixpath.relpath(mapped, here or ".")
        return f"{bang}[{label}]({rel}{'#' + anchor if anchor else ''})"
    if (docs / here / path).exists():
        return m.group(0)  # an asset copied beside the page (a chapter's figures)
    if bang and not figures and path.startswith("figures/"):
        rep.as_text += 1
        return f"*({label})*"  # not drawn in this build
    if not in_repo.startswith("..") and (REPO / in_repo).exists():
        rep.as_text += 1  # a source file: named, not linked (the site does not publish it)
        return f"{label} (`{in_repo}`)" if label.strip("`") != in_repo else f"`{in_repo}`"
    rep.broken.append(f"{page} (from {source}): {target}")
    return m.group(0)
