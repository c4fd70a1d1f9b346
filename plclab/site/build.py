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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

from ..viz.highlight import fence_map
from . import pages
from .bundle import copy_pyodide, core_zip
from .freshness import fingerprint, precompress, record, recorded
from .links import LinkReport, relink, written_from

REPO = pages.REPO
SITE_SOURCES = REPO / "site"
MARKER = ".plclab-site"


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


def mkdocs_config(docs: Path, out: Path, nav: list[Any]) -> dict[str, Any]:
    """mkdocs.yml as data: material theme without web fonts (the site works offline),
    the built-in search (lunr, in the page), pages not in the nav listed as such."""
    return {
        "site_name": "plclab",
        "site_description": "Learn PLC programming (IEC 61131-3) with a playground in the page",
        "docs_dir": str(docs), "site_dir": str(out), "use_directory_urls": True,
        "theme": {"name": "material", "font": False,
                  "features": ["navigation.sections", "navigation.top", "search.highlight"],
                  "palette": {"primary": "indigo"}},
        "plugins": ["search"],
        "extra_css": ["theme/accessibility.css", "playground/playground.css"],
        "extra_javascript": ["theme/accessibility.js"],
        "markdown_extensions": ["tables", "admonition", "attr_list", "md_in_html",
                                {"toc": {"permalink": True}},
                                {"pymdownx.highlight": {
                                    "use_pygments": True,
                                    "extend_pygments_lang": fence_map()}},
                                "pymdownx.superfences"],
        "not_in_nav": "/problems/PLC*/\n/problems/PLC*/index.md\n",
        "validation": {"links": {"not_found": "warn", "absolute_links": "warn",
                                 "unrecognized_links": "warn"},
                       "nav": {"omitted_files": "info"}},
        "nav": nav,
    }


def generate(docs: Path, playground: bool = True, figures: bool = True,
             notebooks: bool = False) -> tuple[list[Any], list[str]]:
    """Write every page (and the playground's assets) into ``docs``; returns the nav and the
    course's problems."""
    written_from(pages.write(docs / "index.md", (SITE_SOURCES / "home.md").read_text("utf-8")),
                 "site/home.md")
    course_nav, problems = pages.course_pages(docs, figures=figures)
    pg = docs / "playground"
    written_from(pages.write(pg / "index.md",
                             (SITE_SOURCES / "playground.md").read_text("utf-8")),
                 "site/playground.md")
    for name in ("playground.js", "editor.js", "worker.js", "playground.css"):
        shutil.copyfile(SITE_SOURCES / "playground" / name, pg / name)
    shutil.copytree(SITE_SOURCES / "theme", docs / "theme")
    lab_nav = pages.lab_pages(docs, pg)
    if playground:
        core_zip(pg / "plclab-core.zip")
        copy_pyodide(docs / "pyodide")
    nav = [{"Home": "index.md"}, {"Course": course_nav}, {"Playground": "playground/index.md"},
           {"Labs": lab_nav}, {"Notebooks": pages.notebook_pages(docs, execute=notebooks)},
           {"Diagnostic codes": pages.problem_pages(docs)},
           {"Reference": pages.reference_pages(docs)}, {"Decisions": pages.adr_pages(docs)}]
    return nav, problems


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

    print_ = fingerprint({"playground": playground, "figures": figures,
                          "notebooks": notebooks, "pygments": version("pygments")})
    if reuse and recorded(out_dir / MARKER) == print_ and (out_dir / "index.html").exists():
        rep.reused = True
        rep.pages = sum(1 for _ in out_dir.rglob("index.html"))
        return rep
    with tempfile.TemporaryDirectory(prefix="plclab-site-src-") as tmp:
        docs = Path(tmp) / "docs"
        nav, rep.course_problems = generate(docs, playground, figures, notebooks)
        rep.links = relink(docs, figures)
        if rep.links.broken:
            raise PlcError("PLC3046", f"{len(rep.links.broken)} link(s) of the sources point "
                           "to nothing; mend them in the file named (or remove the link):\n  "
                           + "\n  ".join(rep.links.broken[:20]))
        cfg = Path(tmp) / "mkdocs.yml"
        cfg.write_text(json.dumps(mkdocs_config(docs, out_dir, nav), indent=1), "utf-8")
        done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--clean", "-f",
                               str(cfg)], capture_output=True, text=True)
        log = (done.stdout + done.stderr).splitlines()
        if done.returncode != 0:
            raise PlcError("PLC3043", "mkdocs could not build the site:\n" +
                           "\n".join(log[-15:]))
        rep.warnings = [line for line in log if line.startswith("WARNING")]
        rep.pages = sum(1 for _ in docs.rglob("*.md"))
    rep.compressed = precompress(out_dir)
    record(out_dir / MARKER, print_)
    return rep
