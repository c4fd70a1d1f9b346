"""``plclab site build [--out DIR]`` and ``plclab site serve``: the web site with the course,
the labs, the diagnostic codes, the reference and the playground (see
``docs/adr/0028-site-and-playground.md``)."""

from __future__ import annotations

import argparse

from plclab.cli_registry import arg, command


@command("site")
@arg("action", choices=["build", "serve"], metavar="ACTION",
     help="build: build the site; serve: serve it on 127.0.0.1, built first unless the "
          "site in --out is up to date")
@arg("--out", metavar="DIR", default=None,
     help="where the site goes (default: plclab-site in the temporary directory); never the "
          "source tree")
@arg("--port", type=int, default=8000, help="serve: the port on 127.0.0.1 (default 8000)")
@arg("--no-playground", action="store_true",
     help="leave out the playground (no Pyodide download: the site is then 15 MB smaller)")
@arg("--no-figures", action="store_true", help="do not draw the course's figures (faster)")
@arg("--rebuild", action="store_true",
     help="serve: build even when the site in --out was built from the same sources")
@arg("--notebooks", action="store_true",
     help="run the lab notebooks (nbclient, minutes) so their pages show the outputs")
def cmd_site(ns: argparse.Namespace) -> int:
    from .build import build
    from .serve import serve_forever

    rep = build(ns.out, playground=not ns.no_playground, figures=not ns.no_figures,
                notebooks=ns.notebooks, reuse=ns.action == "serve" and not ns.rebuild)
    if rep.reused:
        print(f"site up to date in {rep.out} (built from the same sources; --rebuild builds "
              "it again)")
    for w in rep.warnings:
        print(w)
    for p in rep.course_problems:
        print(f"course: {p}")
    print(f"site built: {rep.pages} pages in {rep.out} (open {rep.out / 'index.html'})")
    if ns.action == "serve":
        serve_forever(rep.out, ns.port)
    return 0
