"""``plclab site build``: generate the pages, write mkdocs' configuration, add the playground
(Pyodide from npm and plclab's core as a zip) and run mkdocs with the material theme.

The sources are generated into a temporary folder; only the built site lands in ``--out``,
which must lie outside the source tree and be empty or a site built before (mkdocs empties it).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab import i18n
from plclab.errors import PlcError
from plclab.i18n import SOURCE, tr

from ..viz.highlight import fence_map
from . import pages
from .bundle import copy_pyodide, core_zip
from .freshness import fingerprint, precompress, record, recorded
from .links import LinkReport, relink, written_from

REPO = pages.REPO
SITE_SOURCES = REPO / "site"
MARKER = ".plclab-site"
EDITIONS = {"en": "English", "ru": "Русский"}
"""The site's editions (ADR 0071): English at the root, every other language under ``<lang>/``,
each with the same pages; the playground's Python and scripts are the English edition's."""
SEARCH_LANGUAGES = {"en": ["en"], "ru": ["ru", "en"]}
"""lunr's languages of each edition's search index (Russian pages name English blocks and
signals too); lunr-languages stems both."""
PLAYGROUND_SCRIPTS = ("playground.js", "editor.js", "worker.js")


def edition_dir(lang: str) -> str:
    """The edition's folder below the site's root: '' for English, ``ru/`` for Russian."""
    return "" if lang == SOURCE else f"{lang}/"


@contextmanager
def speaking(lang: str) -> Iterator[None]:
    """plclab's texts (i18n.tr, the problem catalogue) in ``lang`` while an edition is made."""
    before = i18n.chosen()
    i18n.set_language(lang)
    try:
        yield
    finally:
        i18n.set_language(before)


def default_out() -> Path:
    return Path(tempfile.gettempdir()) / "plclab-site"


@dataclass
class BuildReport:
    out: Path
    pages: int = 0
    warnings: list[str] = field(default_factory=list)
    course_problems: list[str] = field(default_factory=list)
    links: LinkReport = field(default_factory=LinkReport)
    playground: bool = True
    reused: bool = False
    compressed: int = 0


def check_out(out: Path) -> Path:
    """Refuse a folder in the source tree, or a non-empty folder that is not a built site."""
    out = out.resolve()
    if out.is_relative_to(REPO.resolve()):
        raise PlcError("PLC3040", f"--out {out}: the site is built outside the source tree "
                       f"({REPO}); choose another folder, e.g. {default_out()}")
    if out.exists() and (not out.is_dir() or (any(out.iterdir())
                                             and not (out / MARKER).exists())):
        raise PlcError("PLC3041", f"--out {out} is not empty and holds no site built by "
                       "plclab; the build empties its folder, so give a new or empty one")
    return out


def mkdocs_config(docs: Path, out: Path, nav: list[Any], lang: str = SOURCE) -> dict[str, Any]:
    """mkdocs.yml as data: material theme without web fonts (the site works offline) in the
    edition's language, the search (lunr, in the page) stemming the edition's languages, the
    language switch to the same page of every edition, pages not in the nav listed as such."""
    up = "../" * edition_dir(lang).count("/")  # from this edition's root to the site's
    editions = [{"name": name, "lang": code,
                 "link": "" if code == lang else up + edition_dir(code),
                 "current": code == lang} for code, name in EDITIONS.items()]
    with speaking(lang):
        description = tr("Learn PLC programming (IEC 61131-3) with a playground in the page")
    return {
        "site_name": "plclab",
        "site_description": description,
        "docs_dir": str(docs), "site_dir": str(out), "use_directory_urls": True,
        "theme": {"name": "material", "font": False, "language": lang,
                  "custom_dir": str(SITE_SOURCES / "overrides"),
                  "features": ["navigation.sections", "navigation.top", "search.highlight"],
                  "palette": {"primary": "indigo"}},
        # alternate: true makes the header show the switch (site/overrides/partials/
        # alternate.html), which lists extra.editions
        "extra": {"alternate": True, "editions": editions},
        "plugins": [{"search": {"lang": SEARCH_LANGUAGES.get(lang, [lang, SOURCE])}}],
        "extra_css": ["theme/accessibility.css", "playground/playground.css"],
        "extra_javascript": ["theme/accessibility.js"],
        "markdown_extensions": ["tables", "admonition", "attr_list", "md_in_html",
                                {"toc": {"permalink": True}},
                                {"pymdownx.highlight": {
                                    "use_pygments": True,
                                    "extend_pygments_lang": fence_map()}},
                                "pymdownx.superfences", "pymdownx.details"],
        "not_in_nav": "/problems/PLC*/\n/problems/PLC*/index.md\n/course/*/quiz.md\n",
        "validation": {"links": {"not_found": "warn", "absolute_links": "warn",
                                 "unrecognized_links": "warn"},
                       "nav": {"omitted_files": "info"}},
        "nav": nav,
    }


def generate(docs: Path, playground: bool = True, figures: bool = True,
             notebooks: bool = False, lang: str = SOURCE,
             english: Path | None = None) -> tuple[list[Any], list[str]]:
    """Write every page of the ``lang`` edition (and the playground's assets) into ``docs``;
    returns the nav and the course's problems. A translated edition is made after the English
    one, whose ``docs`` (``english``) lends it the course's figures; its playground page loads
    the English edition's Python and scripts, and the texts of the scripts in its language."""
    if lang != SOURCE and english is None:
        raise ValueError("a translated edition is made from the English one's docs")
    with speaking(lang):
        return _generate(docs, playground, figures, notebooks, lang, english)


def _generate(docs: Path, playground: bool, figures: bool, notebooks: bool, lang: str,
              english: Path | None) -> tuple[list[Any], list[str]]:
    home = pages.localized(SITE_SOURCES / "home.md")
    written_from(pages.write(docs / "index.md", home.read_text("utf-8")),
                 home.relative_to(REPO).as_posix())
    course_nav, problems = pages.course_pages(docs, figures=figures, english=english)
    pg = docs / "playground"
    page = pages.localized(SITE_SOURCES / "playground.md")
    written_from(pages.write(pg / "index.md", page.read_text("utf-8")),
                 page.relative_to(REPO).as_posix())
    shutil.copyfile(SITE_SOURCES / "playground" / "playground.css", pg / "playground.css")
    if lang == SOURCE:
        for name in PLAYGROUND_SCRIPTS:
            shutil.copyfile(SITE_SOURCES / "playground" / name, pg / name)
    else:
        pages.write(pg / "ui.js", playground_texts_script(lang))
    shutil.copytree(SITE_SOURCES / "theme", docs / "theme")
    lab_nav = pages.lab_pages(docs, pg)
    if playground and lang == SOURCE:
        core_zip(pg / "plclab-core.zip")
        copy_pyodide(docs / "pyodide")
    notebook_nav = pages.notebook_pages(docs, execute=notebooks and lang == SOURCE)
    if notebooks and english is not None:  # run once: the English pages with their outputs
        shutil.copytree(english / "notebooks", docs / "notebooks", dirs_exist_ok=True)
    reference_nav, adr_nav = pages.reference_pages(docs), pages.adr_pages(docs)
    if lang != SOURCE:
        for folder in ("notebooks", "reference", "adr"):
            for md in (docs / folder).rglob("*.md"):
                md.write_text(pages.english_only(md.read_text("utf-8")), "utf-8")
    nav = [{tr("Home"): "index.md"}, {tr("Course"): course_nav},
           {tr("Playground"): "playground/index.md"}, {tr("Labs"): lab_nav},
           {tr("Notebooks"): notebook_nav}, {tr("Diagnostic codes"): pages.problem_pages(docs)},
           {tr("Reference"): reference_nav}, {tr("Decisions"): adr_nav}]
    return nav, problems


def playground_texts(lang: str) -> dict[str, str]:
    """The texts of the playground's scripts (every ``t("...")`` of playground.js and
    editor.js) in ``lang``, from ``plclab/locale/<lang>/ui.toml``; a missing one stays out
    (the script shows the English)."""
    ui = i18n.catalogue(lang, "ui")
    return {key: ui[key] for key in playground_keys() if isinstance(ui.get(key), str)}


def playground_keys() -> list[str]:
    """Every literal text the playground's scripts pass to ``t()``."""
    import re

    keys: list[str] = []
    for name in ("playground.js", "editor.js"):
        text = (SITE_SOURCES / "playground" / name).read_text("utf-8")
        for m in re.finditer(r'\bt\(\s*("(?:[^"\\]|\\.)*"(?:\s*\+\s*"(?:[^"\\]|\\.)*")*)',
                             text):  # t("a" + "b"): the literals joined
            key = "".join(json.loads(part) for part in re.findall(r'"(?:[^"\\]|\\.)*"',
                                                                   m.group(1)))
            if key not in keys:
                keys.append(key)
    return keys


def playground_texts_script(lang: str) -> str:
    """``ui.js`` of an edition's playground: its language and its texts, read by
    playground.js before it writes a word."""
    return ("// plclab's playground texts (generated from plclab/locale/" + lang +
            "/ui.toml by plclab site build)\nwindow.PLCLAB_UI = " +
            json.dumps({"lang": lang, "texts": playground_texts(lang)}, ensure_ascii=False,
                       indent=0) + ";\n")


def build(out: str | Path | None = None, playground: bool = True,
          figures: bool = True, notebooks: bool = False, reuse: bool = False) -> BuildReport:
    """Build the site into ``out`` (default: ``plclab-site`` in the temporary directory);
    ``notebooks=True`` runs the lab notebooks to show their outputs (minutes). With ``reuse``
    a site built before from the same sources and options is kept as it is
    (:mod:`plclab.site.freshness`)."""
    try:
        import material  # noqa: F401
        import mkdocs  # noqa: F401
    except ImportError:
        raise PlcError("PLC3043", "the site needs mkdocs and its material theme: pip install "
                       "'plclab[site]' (or pip install mkdocs-material)") from None
    out_dir = check_out(Path(out) if out is not None else default_out())
    rep = BuildReport(out_dir, playground=playground)
    from importlib.metadata import version

    print_ = fingerprint({"editions": list(EDITIONS), "playground": playground, "figures": figures,
                          "notebooks": notebooks, "pygments": version("pygments")})
    if reuse and recorded(out_dir / MARKER) == print_ and (out_dir / "index.html").exists():
        rep.reused = True
        rep.pages = sum(1 for _ in out_dir.rglob("index.html"))
        return rep
    with tempfile.TemporaryDirectory(prefix="plclab-site-src-") as tmp:
        runs = []
        for lang in EDITIONS:  # English first: the others take its figures
            docs = Path(tmp) / lang / "docs"
            nav, problems = generate(docs, playground, figures, notebooks, lang,
                                     None if lang == SOURCE else Path(tmp) / SOURCE / "docs")
            if lang == SOURCE:
                rep.course_problems = problems
            links = relink(docs, figures)
            rep.links.rewritten += links.rewritten
            rep.links.as_text += links.as_text
            rep.links.broken += [f"{edition_dir(lang)}{b}" for b in links.broken]
            rep.pages += sum(1 for _ in docs.rglob("*.md"))
            # English into --out (mkdocs empties it), the others beside, then under it
            site = out_dir if lang == SOURCE else Path(tmp) / lang / "site"
            cfg = Path(tmp) / lang / "mkdocs.yml"
            cfg.write_text(json.dumps(mkdocs_config(docs, site, nav, lang), indent=1), "utf-8")
            runs.append((lang, site, cfg))
        if rep.links.broken:
            raise PlcError("PLC3046", f"{len(rep.links.broken)} link(s) of the sources point "
                           "to nothing; mend them in the file named (or remove the link):\n  "
                           + "\n  ".join(rep.links.broken[:20]))
        # the editions are built side by side (two processes: mkdocs is single-threaded)
        procs = [(lang, site, subprocess.Popen(
            [sys.executable, "-m", "mkdocs", "build", "--clean", "-f", str(cfg)],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True))
            for lang, site, cfg in runs]
        failed = []
        for lang, _, proc in procs:
            log = proc.communicate()[0].splitlines()
            if proc.returncode != 0:
                failed.append(f"[{lang}] " + "\n".join(log[-15:]))
            rep.warnings += [line if lang == SOURCE else f"{line} [{lang}]" for line in log
                             if line.startswith("WARNING")]
        if failed:
            raise PlcError("PLC3043", "mkdocs could not build the site:\n" + "\n".join(failed))
        for lang, site, _ in runs:
            if lang != SOURCE:
                shutil.move(str(site), str(out_dir / edition_dir(lang)))
    rep.compressed = precompress(out_dir)
    record(out_dir / MARKER, print_)
    return rep
