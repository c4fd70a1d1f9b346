"""The Markdown pages of the site, generated from the sources into mkdocs' ``docs`` folder:
the course chapters (with "try it" links and their figures), the labs' student parts, one page
per diagnostic code, the blocks, the plants with a picture each, the compliance list and the
ADRs. Every function writes below ``docs`` and returns the nav entries it made."""

from __future__ import annotations

import base64
import json
import re
import shutil
import tomllib
from pathlib import Path
from typing import Any

from .links import written_from

REPO = Path(__file__).resolve().parents[2]
PLAYGROUND_LANGUAGES = ("st", "il", "ld")


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def try_link(code: str, language: str, depth: int) -> str:
    """A relative link that opens ``code`` in the playground (the code travels in the URL's
    fragment, so nothing reaches a server)."""
    data = base64.urlsafe_b64encode(code.encode("utf-8")).decode("ascii").rstrip("=")
    return f"{'../' * depth}playground/#lang={language}&code={data}"


def _with_try_links(text: str, depth: int) -> str:
    """Put a "try it" link under every ST, IL or LD block of a chapter."""
    out: list[str] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.match(r"^(`{3,})(\w+)(.*)$", line)
        if not m:
            out.append(line)
            i += 1
            continue
        fence, lang = m.group(1), m.group(2)
        j = i + 1
        while j < len(lines) and not lines[j].startswith(fence):
            j += 1
        out.append(fence + lang)  # mkdocs reads no attributes after the language
        out.extend(lines[i + 1:j + 1])
        error = re.search(r"\berror=(PLC\d{4})", m.group(3))
        if error:
            out += ["", f"*A deliberate mistake: plclab reports "
                    f"[{error.group(1)}]({'../' * depth}problems/{error.group(1)}/index.md).*"]
        if lang in PLAYGROUND_LANGUAGES:
            code = "\n".join(lines[i + 1:j]) + "\n"
            expect = f"&expect={error.group(1)}" if error else ""  # the page announces it
            out += ["", f'<a class="try-it" href="{try_link(code, lang, depth)}{expect}">'
                    "Try it in the playground</a>"]
        i = j + 1
    return "\n".join(out) + "\n"


def course_pages(docs: Path, figures: bool = True) -> tuple[list[Any], list[str]]:
    """Every chapter under ``docs/course/<slug>/index.md`` with its figures drawn from real
    runs; returns the nav and the problems the course build reported."""
    from plclab.course.build import build_chapter
    from plclab.course.model import chapters

    nav: list[Any] = ["course/index.md"]
    problems: list[str] = []
    rows = ["# The course", "", "Read the chapters in this order; each ends with the labs that "
            "practise it. Every figure was drawn from a real run when this site was built.", "",
            "| # | chapter | labs |", "|---|---|---|"]
    for ch in chapters():
        rep = build_chapter(ch, docs / "course", figures=figures)
        problems += rep.problems
        dest = docs / "course" / ch.slug
        (dest / "chapter.md").unlink()
        for extra in ("quiz.toml", "figures.toml"):
            (dest / extra).unlink(missing_ok=True)
        written_from(write(dest / "index.md", _with_try_links(ch.text, depth=2)),
                     f"course/{ch.slug}/chapter.md")
        labs = ", ".join(f"[{lab}](../labs/{lab}/index.md)" for lab in ch.lab_refs) or "-"
        rows.append(f"| {ch.number} | [{ch.title}]({ch.slug}/index.md) | {labs} |")
        nav.append(f"course/{ch.slug}/index.md")
    from plclab.course.glossary import glossary_markdown, glossary_path, terms

    if glossary_path().exists():  # the glossary and its index (course/glossary.toml)
        page = glossary_markdown(terms(), chapters(), link=lambda c: f"{c.slug}/index.md")
        written_from(write(docs / "course" / "glossary.md", page), "course/glossary.toml")
        rows += ["", "[Glossary and index](glossary.md): every term in English and Russian, "
                 "and the chapters that use it."]
        nav.append("course/glossary.md")
    write(docs / "course" / "index.md", "\n".join(rows) + "\n")
    return nav, problems


# ------------------------------------------------------------------------------ labs


def _lab_wiring(lab_dir: Path, data: dict[str, Any]) -> list[dict[str, Any]]:
    w = data.get("wiring", [])
    if isinstance(w, str):
        with open(lab_dir / w, "rb") as fh:
            return tomllib.load(fh).get("wiring", [])
    return w


def _md_cell(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def lab_pages(docs: Path, site_assets: Path) -> list[Any]:
    """One page per lab: its task, I/O table, starter program and visible scenarios and
    criteria (never the solutions, the mistakes or the hidden scenarios). Writes the JSON of
    the labs the playground can check into ``site_assets/labs.json``."""
    from plclab.grade.courseware import PRIVATE_DIRS, student_lab_data

    from .lab_check import BROWSER_LABS, lab_json_from_dict

    nav: list[Any] = ["labs/index.md"]
    rows = ["# Labs", "", "Each lab is a task on a simulated plant. Write the program, then run "
            "`plclab lab check LAB FILE` (or, for the first labs, the playground's *Check "
            "against the lab*).", "", "| lab | plant | languages |", "|---|---|---|"]
    browser: dict[str, Any] = {}
    for lab_dir in sorted(p for p in (REPO / "labs").iterdir() if (p / "lab.toml").exists()):
        with open(lab_dir / "lab.toml", "rb") as fh:
            data = student_lab_data(tomllib.load(fh))
        lab = lab_dir.name
        readme = (lab_dir / "README.md").read_text(encoding="utf-8") \
            if (lab_dir / "README.md").exists() else f"# {data.get('title', lab)}\n"
        parts = [readme.rstrip()]
        if not re.search(r"^## I/O table", readme, re.M):  # the README's own, else lab.toml's
            parts += ["", "## I/O table of lab.toml", "",
                      "| name | address | type | description |", "|---|---|---|---|"]
            parts += [f"| `{io['name']}` | `{io.get('address', '')}` | {io.get('type', '')} | "
                      f"{_md_cell(io.get('description', ''))} |" for io in data.get("io", [])]
        starters = sorted(p for p in lab_dir.glob("starter.*"))
        for st in starters:
            lang = st.suffix[1:]
            code = st.read_text(encoding="utf-8")
            parts += ["", f"## Starter program (`{st.name}`)", "", f"```{lang}", code.rstrip(),
                      "```"]
            if lang in PLAYGROUND_LANGUAGES:
                query = f"&lab={lab}" if lab in BROWSER_LABS else ""
                parts += ["", f'<a class="try-it" href="{try_link(code, lang, 2)}{query}">'
                          "Open the starter in the playground</a>"]
        parts += ["", "## Scenarios your program runs in", ""]
        parts += [f"- **{s['name']}** ({s.get('duration', '')}): {s.get('description', '')}"
                  for s in data.get("scenario", [])]
        parts += ["", "Further scenarios stay hidden until grading."]
        if "criteria-table:start" not in readme:  # the README's generated table, else this
            parts += ["", "## Criteria", "", "| criterion | points | what is checked |",
                      "|---|---:|---|"]
            parts += [f"| {_md_cell(c['name'])} | {c.get('points', 1)} | "
                      f"{_md_cell(c.get('description', c.get('message', '')))} |"
                      for c in data.get("criterion", [])]
        written_from(write(docs / "labs" / lab / "index.md", "\n".join(parts) + "\n"),
                     f"labs/{lab}/README.md")
        assert not any((docs / "labs" / lab / d).exists() for d in PRIVATE_DIRS)
        rows.append(f"| [{_md_cell(data.get('title', lab))}]({lab}/index.md) | "
                    f"{data.get('plant', '')} | {', '.join(data.get('languages', []))} |")
        nav.append(f"labs/{lab}/index.md")
        if lab in BROWSER_LABS:
            browser[lab] = lab_json_from_dict(lab, data, _lab_wiring(lab_dir, data))
    write(docs / "labs" / "index.md", "\n".join(rows) + "\n")
    write(site_assets / "labs.json", json.dumps(browser, indent=1))
    return nav


# ------------------------------------------------------------------------------ problems


def problem_pages(docs: Path) -> list[Any]:
    """``problems/index.md`` (every code) and one page per code with its wrong and right
    example."""
    from plclab.problems import catalogue

    rows = ["# Diagnostic codes", "", "Every message plclab prints carries a code. Each page "
            "says what it means and, for a mistake in a program, shows a wrong program and "
            "its fix (`plclab explain CODE` prints the same).", "",
            "| code | title |", "|---|---|"]
    for code, p in catalogue().items():
        page = [f"# {code}: {p.title}", "", p.explanation.strip(), ""]
        if p.reserved:
            page += [f"*Reserved*: {p.reserved_why or 'no module raises it yet.'}", ""]
        lang = p.language or "st"
        if p.wrong:
            page += ["## Wrong", "", f"```{lang}", p.wrong.strip("\n"), "```", ""]
            if lang in PLAYGROUND_LANGUAGES:
                page += [f'<a class="try-it" href="{try_link(p.wrong, lang, 2)}'
                         f'&expect={code}">Try the wrong program</a>', ""]
        if p.fix:
            page += ["## Right", "", f"```{lang}", p.fix.strip("\n"), "```", ""]
            if lang in PLAYGROUND_LANGUAGES:
                page += [f'<a class="try-it" href="{try_link(p.fix, lang, 2)}">'
                         "Try the fix</a>", ""]
        if p.example:
            page += ["## Example", "", "```text", p.example.strip("\n"), "```", ""]
        if p.no_example:
            page += [f"*No example program*: {p.no_example}", ""]
        write(docs / "problems" / code / "index.md", "\n".join(page))
        rows.append(f"| [{code}]({code}/index.md) | {_md_cell(p.title)} |")
    write(docs / "problems" / "index.md", "\n".join(rows) + "\n")
    return ["problems/index.md"]


# ------------------------------------------------------------------------------ reference


def reference_pages(docs: Path) -> list[Any]:
    """The block reference, the compliance list (the README's section) and the plants."""
    import plants

    from .plant_svg import plant_svg

    written_from(write(docs / "reference" / "blocks.md",
                       (REPO / "docs" / "blocks.md").read_text("utf-8")), "docs/blocks.md")
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    m = re.search(r"^## Language reference \(compliance list\)\n(.*?)(?=^## )", readme,
                  re.S | re.M)
    body = m.group(1) if m else "The compliance list is in the README.\n"
    written_from(write(docs / "reference" / "compliance.md",
                       "# Language compliance list\n" + body), "README.md")
    rows = ["# Plants", "", "The simulated machines a program drives (`plclab plants`). The "
            "playground runs the tank and the motor in the page.", ""]
    nav: list[Any] = ["reference/plants/index.md"]
    for name in plants.list_plants():
        p = plants.get_plant(name)
        write(docs / "reference" / "plants" / f"{name}.svg", plant_svg(p))
        doc = (type(p).__doc__ or "").strip().split("\n\n")[0]
        page = [f"# {name}: {p.title}", "", doc, "",
                f"![The {name} plant after reset]({name}.svg)", "", "## Signals", "",
                plants.signal_table(p), ""]
        if getattr(p, "FAULTS", None):
            page += ["## Faults a scenario can inject", ""]
            page += [f"- `{k}`: {v}" for k, v in p.FAULTS.items()]
        write(docs / "reference" / "plants" / f"{name}.md", "\n".join(page) + "\n")
        rows.append(f"- [{name}]({name}.md): {p.title}")
        nav.append(f"reference/plants/{name}.md")
    write(docs / "reference" / "plants" / "index.md", "\n".join(rows) + "\n")
    return ["reference/blocks.md", "reference/compliance.md", {"Plants": nav}]


def adr_pages(docs: Path) -> list[Any]:
    """The architecture decision records, as they are (links to source files become text)."""
    nav: list[Any] = ["adr/index.md"]
    rows = ["# Decisions (ADRs)", "", "Why plclab is built the way it is.", ""]
    for path in sorted((REPO / "docs" / "adr").glob("[0-9]*.md")):
        text = path.read_text(encoding="utf-8")
        written_from(write(docs / "adr" / path.name, text), f"docs/adr/{path.name}")
        title = text.splitlines()[0].lstrip("# ").strip() if text else path.stem
        rows.append(f"- [{title}]({path.name})")
        nav.append(f"adr/{path.name}")
    write(docs / "adr" / "index.md", "\n".join(rows) + "\n")
    return nav


def copy_tree(src: Path, dest: Path) -> None:
    shutil.copytree(src, dest, dirs_exist_ok=True)


# ------------------------------------------------------------------------------ notebooks


def _output_md(out: dict[str, Any], folder: Path, stem: str, n: int) -> list[str]:
    """One cell output as Markdown: text as a text block, a PNG as an image file; rich HTML
    and widgets (rerun's viewer) are left out with a line saying so."""
    kind = out.get("output_type")
    if kind == "stream":
        return ["```text", "".join(out.get("text", "")).rstrip(), "```"]
    if kind == "error":
        return ["```text", f"{out.get('ename')}: {out.get('evalue')}", "```"]
    data = out.get("data", {})
    if "image/png" in data:
        name = f"{stem}-{n}.png"
        (folder / name).write_bytes(base64.b64decode(data["image/png"]))
        return [f"![output {n}]({name})"]
    if "image/svg+xml" in data:
        name = f"{stem}-{n}.svg"
        (folder / name).write_text("".join(data["image/svg+xml"]), encoding="utf-8")
        return [f"![output {n}]({name})"]
    if "text/markdown" in data:
        return ["".join(data["text/markdown"]).rstrip()]
    if "text/plain" in data and not any(k.startswith("application/vnd") for k in data):
        return ["```text", "".join(data["text/plain"]).rstrip(), "```"]
    return ["*(an interactive output, shown only when the notebook runs in Jupyter)*"]


def notebook_pages(docs: Path, execute: bool = False) -> list[Any]:
    """Each lab notebook as a page: its Markdown, its code and, with ``execute``, the outputs of
    a run (nbclient, in the notebooks' folder). Without ``execute`` the pages say how to see
    them run."""
    try:
        import nbformat
    except ImportError:
        write(docs / "notebooks" / "index.md", "# Notebooks\n\nThis site was built without "
              "nbformat (pip install 'plclab[site]'), so the notebooks are not shown.\n")
        return ["notebooks/index.md"]
    src = REPO / "notebooks"
    folder = docs / "notebooks"
    folder.mkdir(parents=True, exist_ok=True)
    nav: list[Any] = ["notebooks/index.md"]
    rows = ["# Notebooks", "", "One Jupyter notebook per lab: the task, your program in a cell, "
            "a run on the plant with its timing diagram, and the lab's checks. Open them with "
            "`pip install 'plclab[notebooks]'` and `jupyter lab notebooks/`.", ""]
    if not execute:
        rows += ["These pages show the notebooks without outputs (`plclab site build "
                 "--notebooks` runs them and shows what they print and draw).", ""]
    for path in sorted(src.glob("*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        if execute:
            from nbclient import NotebookClient

            NotebookClient(nb, timeout=600, kernel_name="python3",
                           resources={"metadata": {"path": str(src)}}).execute()
        lines: list[str] = []
        n = 0
        for cell in nb.cells:
            if cell.cell_type == "markdown":
                lines += [cell.source.rstrip(), ""]
            elif cell.cell_type == "code":
                lines += ["```python", cell.source.rstrip(), "```", ""]
                for out in cell.get("outputs", []):
                    n += 1
                    lines += _output_md(out, folder, path.stem, n) + [""]
        written_from(write(folder / f"{path.stem}.md", "\n".join(lines)),
                     f"notebooks/{path.name}")
        title = next((c.source.splitlines()[0].lstrip("# ") for c in nb.cells
                      if c.cell_type == "markdown" and c.source.startswith("# ")), path.stem)
        rows.append(f"- [{title}]({path.stem}.md)")
        nav.append(f"notebooks/{path.stem}.md")
    write(folder / "index.md", "\n".join(rows) + "\n")
    return nav
