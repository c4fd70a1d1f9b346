"""What the playground loads in the browser: Pyodide from the npm ``pyodide`` package, and a zip
of plclab's pure-Python core with the ``tank`` and ``motor`` plants, the language server's
feature functions and the highlighting lexers (with Pygments' lexer core).

Pyodide is installed with ``npm install`` into a cache outside the source tree
(``$PLCLAB_CACHE`` or ``~/.cache/plclab``, folder ``npm/``) the first time a site is built, then
copied into the built site: the site needs no CDN and works offline. ``PLCLAB_PYODIDE_DIR``
names a ready folder instead (an offline machine, a pinned copy).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import zipfile
from pathlib import Path

from plclab.errors import PlcError

PYODIDE_VERSION = "0.27.8"
AXE_VERSION = "4.11.0"
"""axe-core (MPL-2.0), the accessibility checker the browser tests inject into each page."""
PYODIDE_FILES = ("pyodide.js", "pyodide.mjs", "pyodide.asm.js", "pyodide.asm.wasm",
                 "python_stdlib.zip", "pyodide-lock.json", "package.json")
REPO = Path(__file__).resolve().parents[2]
# Packages of plclab that the page never imports (they need NumPy, pymunk, rerun, sockets...).
NOT_IN_BROWSER = ("sim", "viz", "grade", "modbus", "course", "courseware")
BROWSER_PLANTS = ("base.py", "tank.py", "motor.py")
# The editor's highlighting is the course's (plclab/viz/highlight.py): that module, and the lexer
# core of Pygments (pure Python, BSD licence; not its lexers, formatters or styles).
BROWSER_VIZ = ("__init__.py", "highlight.py")
PYGMENTS_MODULES = ("__init__.py", "filter.py", "filters/__init__.py", "lexer.py", "plugin.py",
                    "regexopt.py", "token.py", "util.py")
PLANTS_INIT = ('"""The plants of the playground (the site ships only the pure-Python tank and '
               'motor)."""\n\nfrom .base import Plant, PlantError\n\n'
               '__all__ = ["Plant", "PlantError"]\n')


def cache_dir() -> Path:
    """Where npm installs Pyodide: ``$PLCLAB_CACHE/npm`` or ``~/.cache/plclab/npm``."""
    root = os.environ.get("PLCLAB_CACHE") or Path.home() / ".cache" / "plclab"
    return Path(root) / "npm"


def pyodide_dir(install: bool = True) -> Path:
    """The folder of the npm ``pyodide`` package, installing it into the cache if needed."""
    given = os.environ.get("PLCLAB_PYODIDE_DIR")
    if given:
        folder = Path(given)
        if not (folder / "pyodide.asm.wasm").exists():
            raise PlcError("PLC3042", f"PLCLAB_PYODIDE_DIR={given} holds no Pyodide "
                           "(pyodide.asm.wasm); point it at node_modules/pyodide")
        return folder
    folder = cache_dir() / "node_modules" / "pyodide"
    if (folder / "pyodide.asm.wasm").exists() or not install:
        return folder
    return npm_package("pyodide", PYODIDE_VERSION, "pyodide.asm.wasm",
                       "or set PLCLAB_PYODIDE_DIR, or build with --no-playground")


def npm_package(name: str, version: str, probe: str, other: str = "") -> Path:
    """The folder of the npm package ``name@version`` in the cache, installed with npm when
    the file ``probe`` is not in it yet."""
    folder = cache_dir() / "node_modules" / name
    if (folder / probe).exists() and _installed_version(folder) == version:
        return folder
    npm = shutil.which("npm")
    if npm is None:
        raise PlcError("PLC3042", f"{name} comes from npm, and npm is not installed: install "
                       f"Node.js and npm (apt-get install npm){', ' + other if other else ''}")
    cache_dir().mkdir(parents=True, exist_ok=True)
    done = subprocess.run([npm, "install", "--no-audit", "--no-fund", "--prefix",
                           str(cache_dir()), f"{name}@{version}"],
                          capture_output=True, text=True)
    if done.returncode != 0 or not (folder / probe).exists():
        tail = (done.stderr or done.stdout).strip().splitlines()[-3:]
        raise PlcError("PLC3042", f"npm install {name}@{version} failed "
                       f"({' / '.join(tail)}); check the network{', ' + other if other else ''}")
    return folder


def _installed_version(folder: Path) -> str | None:
    import json

    try:
        return json.loads((folder / "package.json").read_text("utf-8")).get("version")
    except (OSError, ValueError):
        return None


def axe_script() -> Path:
    """``axe.min.js`` of axe-core ``AXE_VERSION`` (npm, into the cache): the browser tests
    inject it into a page and run ``axe.run()`` (WCAG 2.1 A and AA rules)."""
    return npm_package("axe-core", AXE_VERSION, "axe.min.js") / "axe.min.js"


def copy_pyodide(dest: Path) -> Path:
    """Copy the files of Pyodide the page needs into ``dest`` (the site's ``pyodide/``)."""
    src = pyodide_dir()
    dest.mkdir(parents=True, exist_ok=True)
    for name in PYODIDE_FILES:
        shutil.copyfile(src / name, dest / name)
    return dest


def _core_files() -> list[tuple[Path, str]]:
    """(file, name in the zip) of plclab's core and the browser plants."""
    pkg = REPO / "plclab"
    out = []
    for path in sorted(pkg.rglob("*")):
        rel = path.relative_to(pkg)
        if not path.is_file() or "__pycache__" in rel.parts or rel.parts[0] in NOT_IN_BROWSER:
            continue
        if path.suffix in (".py", ".st", ".toml"):
            out.append((path, f"plclab/{rel.as_posix()}"))
    out += [(pkg / "viz" / n, f"plclab/viz/{n}") for n in BROWSER_VIZ]
    out += [(REPO / "plants" / n, f"plants/{n}") for n in BROWSER_PLANTS]
    import pygments

    src = Path(pygments.__file__).parent
    out += [(src / n, f"pygments/{n}") for n in PYGMENTS_MODULES]
    from importlib.metadata import distribution

    for f in distribution("pygments").files or []:  # its licence travels with it
        if f.name == "LICENSE":
            out.append((Path(str(f.locate())), "pygments/LICENSE"))
    return out


def core_zip(dest: Path) -> Path:
    """Write ``plclab-core.zip``: what the page unpacks into Pyodide's file system."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(dest, "w", zipfile.ZIP_DEFLATED) as z:
        for path, name in _core_files():
            z.write(path, name)
        z.writestr("plants/__init__.py", PLANTS_INIT)
    return dest
