"""The web site: ``plclab site build`` (mkdocs pages from the course, labs, catalogue, plants,
ADRs) and the playground, whose Python side (:mod:`plclab.site.playground_api`,
:mod:`plclab.site.lab_check`) runs in the browser under Pyodide. See
``docs/adr/0028-site-and-playground.md``.

Importing this package imports nothing: the playground loads only the modules it needs.
"""

__all__ = ["build", "commands", "lab_check", "pages", "playground_api", "plant_svg", "serve",
           "bundle"]
