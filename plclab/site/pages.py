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

from plclab.i18n import SOURCE, decimal, language, problem_text, tr

from .links import written_from

REPO = Path(__file__).resolve().parents[2]
PLAYGROUND_LANGUAGES = ("st", "il", "ld")


def localized(path: Path) -> Path:
    """The edition's file of ``path``: ``chapter.md`` -> ``chapter.ru.md`` (README.md,
    home.md, quiz.toml...) in the Russian edition when that file exists, else ``path``."""
    if language() != SOURCE:
        own = path.with_name(f"{path.stem}.{language()}{path.suffix}")
        if own.exists():
            return own
    return path


def english_only(text: str) -> str:
    """A page the edition has no translation of yet: the notice under its first heading (the
    Russian edition keeps every page, so its links and its language switch never leave it),
    and out of the edition's search (its words are the English edition's to find)."""
    if language() == SOURCE:
        return text
    note = ["", '!!! note "' + tr("Not translated yet") + '"',
            "    " + tr("This page is not translated yet; its English text follows."), ""]
    lines = text.splitlines()
    at = next((i + 1 for i, line in enumerate(lines) if line.startswith("# ")), 0)
    return "\n".join(["---", "search:", "  exclude: true", "---", *lines[:at], *note,
                      *lines[at:]]) + "\n"


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
            out += ["", tr("*A deliberate mistake: plclab reports [{code}]({href}).*",
                           code=error.group(1),
                           href=f"{'../' * depth}problems/{error.group(1)}/index.md")]
        if lang in PLAYGROUND_LANGUAGES:
            code = "\n".join(lines[i + 1:j]) + "\n"
            expect = f"&expect={error.group(1)}" if error else ""  # the page announces it
            out += ["", f'<a class="try-it" href="{try_link(code, lang, depth)}{expect}">'
                    f'{tr("Try it in the playground")}</a>']
        i = j + 1
    return "\n".join(out) + "\n"


def _heading(text: str, default: str) -> str:
    return next((line[2:].strip() for line in text.splitlines() if line.startswith("# ")),
                default)


def course_pages(docs: Path, figures: bool = True,
                 english: Path | None = None) -> tuple[list[Any], list[str]]:
    """Every chapter under ``docs/course/<slug>/index.md`` with its figures drawn from real
    runs, and its quiz (``quiz.md``); returns the nav and the problems the course build
    reported. A translated edition passes ``english``, the English edition's ``docs``: its
    chapters are the ``chapter.<lang>.md`` files and its figures are copied from there (they
    are drawn, run and checked once)."""
    from plclab.course.build import build_chapter
    from plclab.course.model import chapters

    nav: list[Any] = ["course/index.md"]
    problems: list[str] = []
    rows = [tr("# The course"), "", tr("Read the chapters in this order; each ends with the "
            "labs that practise it. Every figure was drawn from a real run when this site was "
            "built."), "", tr("| # | chapter | quiz | labs |"), "|---|---|---|---|"]
    for ch in chapters():
        dest = docs / "course" / ch.slug
        if english is None:
            rep = build_chapter(ch, docs / "course", figures=figures)
            problems += rep.problems
            (dest / "chapter.md").unlink()
            for extra in ("quiz.toml", "figures.toml"):
                (dest / extra).unlink(missing_ok=True)
        else:  # the figures and examples the English edition drew
            shutil.copytree(english / "course" / ch.slug, dest,
                            ignore=shutil.ignore_patterns("*.md"))
        source = localized(ch.folder / "chapter.md")
        text = source.read_text(encoding="utf-8")
        quiz = quiz_page(ch)
        if quiz:
            text = text.rstrip() + "\n\n" + tr("[Quiz of this chapter]({href}): {n} questions "
                                               "with their answers.", href="quiz.md",
                                               n=quiz[1]) + "\n"
            write(dest / "quiz.md", quiz[0])
        written_from(write(dest / "index.md", _with_try_links(text, depth=2)),
                     source.relative_to(REPO).as_posix())
        labs = ", ".join(f"[{lab}](../labs/{lab}/index.md)" for lab in ch.lab_refs) or "-"
        quiz_cell = f"[{quiz[1]}]({ch.slug}/quiz.md)" if quiz else "-"
        rows.append(f"| {ch.number} | [{_heading(text, ch.title)}]({ch.slug}/index.md) | "
                    f"{quiz_cell} | {labs} |")
        nav.append(f"course/{ch.slug}/index.md")
    from plclab.course.glossary import glossary_markdown, glossary_path, terms

    if glossary_path().exists():  # the glossary and its index (course/glossary.toml)
        page = glossary_markdown(terms(), chapters(), link=lambda c: f"{c.slug}/index.md")
        if language() != SOURCE:
            page = _glossary_translated(page)
        written_from(write(docs / "course" / "glossary.md", page), "course/glossary.toml")
        rows += ["", tr("[Glossary and index](glossary.md): every term in English and Russian, "
                        "and the chapters that use it.")]
        nav.append("course/glossary.md")
    write(docs / "course" / "index.md", "\n".join(rows) + "\n")
    return nav, problems


def _glossary_translated(page: str) -> str:
    """The glossary page's own words (headings, the table's head, the lead) in the edition's
    language; the terms, their Russian and the chapter links are the same table."""
    lines = page.splitlines()
    out = []
    for line in lines:
        if line == "# Glossary and index":
            line = tr("# Glossary and index")
        elif line.startswith("Each term with its Russian equivalent"):
            line = tr("Each term with its Russian equivalent (the word the Russian source texts "
                      "use), a short definition and the chapter that introduces it; the index "
                      "below lists every chapter whose text uses the term.")
        elif line == "| term | по-русски | meaning | introduced in |":
            line = tr("| term | по-русски | meaning | introduced in |")
        elif line == "## Index":
            line = tr("## Index")
        out.append(line)
    return "\n".join(out) + "\n"


_QUIZ_KEYS: dict[str, str] = {}
"""An item's fields but its texts (the same in every edition, ADR 0066) -> the answer as the
page shows it: each key is recomputed once for both editions."""
_QUIZ_TEXTS = ("question", "choices", "explain", "unit")


def _quiz_key(d: dict[str, Any]) -> str:
    from plclab.course.quiz import evaluate_output, numeric_key

    key = json.dumps({k: v for k, v in d.items() if k not in _QUIZ_TEXTS}, sort_keys=True,
                     default=str)
    if key not in _QUIZ_KEYS:
        if d["kind"] == "numeric":
            v = numeric_key(d)
            _QUIZ_KEYS[key] = str(int(v)) if v.is_integer() and abs(v) < 1e15 else f"{v:.6g}"
        else:
            _QUIZ_KEYS[key] = evaluate_output(d).strip()
    return _QUIZ_KEYS[key]


def quiz_page(ch: Any) -> tuple[str, int] | None:
    """The chapter's quiz as a page: each question (with its program), its choices and,
    folded, the answer with its explanation; keys are recomputed by plclab, as ``plclab quiz``
    does. None when the chapter has no quiz."""
    path = localized(ch.folder / "quiz.toml")
    if not path.exists():
        return None
    with open(path, "rb") as fh:
        found = tomllib.load(fh).get("item", [])
    if not found:
        return None
    lines = [tr("# Quiz: {title}", title=_heading(localized(ch.folder / "chapter.md")
                                                   .read_text(encoding="utf-8"), ch.title)),
             "", tr("Answer in your head or on paper, then open the answer. `plclab quiz {n}` "
                    "asks the same questions in the terminal and checks what you write.",
                    n=ch.number), ""]
    for n, d in enumerate(found, 1):
        lines += [f"**{n}.** " + " ".join(d["question"].split()), ""]
        lang = Path(str(d.get("filename", "quiz.st"))).suffix[1:] or "st"  # st, il, ld
        for name in ("program", "starter"):
            if d.get(name):
                lines += [f"```{lang}", str(d[name]).strip("\n"), "```", ""]
        choices = [str(c) for c in d.get("choices", [])]
        lines += [f"{i}. {_md_cell(c)}" for i, c in enumerate(choices, 1)]
        answer = ""
        if d["kind"] == "choice":
            k = int(d["answer"])
            answer = f"{k}. {_md_cell(choices[k - 1])}"
        elif d["kind"] in ("numeric", "output"):
            value = _quiz_key(d)
            answer = f"`{value}`" if d["kind"] == "output" else decimal(value)
            if d.get("unit"):
                answer += f" {d['unit']}"
        else:
            answer = tr("write the program; `plclab quiz {n}` runs it against the grading "
                        "scenario", n=ch.number)
        lines += ["", f'??? question "{tr("Answer")}"', f"    **{answer}**", ""]
        lines += ["    " + line if line else ""
                  for line in str(d.get("explain", "")).strip().splitlines()]
        lines.append("")
    return "\n".join(lines), len(found)


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
    the labs the playground can check into ``site_assets/labs.json``. A translated edition
    takes ``README.<lang>.md`` where the lab has one (else it says so and shows the English
    text) and the lab's titles, scenarios and criteria from ``lab.<lang>.toml``."""
    from plclab.grade.courseware import PRIVATE_DIRS, student_lab_data

    from .lab_check import BROWSER_LABS, lab_json_from_dict

    nav: list[Any] = ["labs/index.md"]
    rows = [tr("# Labs"), "", tr("Each lab is a task on a simulated plant. Write the program, "
            "then run `plclab lab check LAB FILE` (or, for the first labs, the playground's "
            "*Check against the lab*)."), "", tr("| lab | plant | languages |"), "|---|---|---|"]
    browser: dict[str, Any] = {}
    for lab_dir in sorted(p for p in (REPO / "labs").iterdir() if (p / "lab.toml").exists()):
        with open(lab_dir / "lab.toml", "rb") as fh:
            data = student_lab_data(tomllib.load(fh))
        texts = _lab_texts(lab_dir)
        lab = lab_dir.name
        title = texts.get("title") or data.get("title", lab)
        source = localized(lab_dir / "README.md")
        readme = source.read_text(encoding="utf-8") if source.exists() else f"# {title}\n"
        if source.exists() and source.name == "README.md" and language() != SOURCE:
            readme = _untranslated_readme(readme, title)
        parts = [readme.rstrip()]
        if not re.search(r"^## (I/O table|Таблица входов)", readme, re.M):
            parts += ["", tr("## I/O table of lab.toml"), "",
                      tr("| name | address | type | description |"), "|---|---|---|---|"]
            parts += [f"| `{io['name']}` | `{io.get('address', '')}` | {io.get('type', '')} | "
                      f"{_md_cell(io.get('description', ''))} |" for io in data.get("io", [])]
        starters = sorted(p for p in lab_dir.glob("starter.*"))
        for st in starters:
            lang = st.suffix[1:]
            code = st.read_text(encoding="utf-8")
            parts += ["", tr("## Starter program (`{name}`)", name=st.name), "", f"```{lang}",
                      code.rstrip(), "```"]
            if lang in PLAYGROUND_LANGUAGES:
                query = f"&lab={lab}" if lab in BROWSER_LABS else ""
                parts += ["", f'<a class="try-it" href="{try_link(code, lang, 2)}{query}">'
                          f'{tr("Open the starter in the playground")}</a>']
        parts += ["", tr("## Scenarios your program runs in"), ""]
        scenarios = texts.get("scenarios", {})
        parts += [f"- **{s['name']}** ({decimal(str(s.get('duration', '')))}): "
                  f"{scenarios.get(s['name'], {}).get('description', s.get('description', ''))}"
                  for s in data.get("scenario", [])]
        parts += ["", tr("Further scenarios stay hidden until grading.")]
        criteria = texts.get("criteria", {})
        if "criteria-table:start" not in readme:  # the README's generated table, else this
            parts += ["", tr("## Criteria"), "", tr("| criterion | points | what is checked |"),
                      "|---|---:|---|"]
            for c in data.get("criterion", []):
                own = criteria.get(c["name"], {})
                what = own.get("message") or c.get("description", c.get("message", ""))
                parts.append(f"| {_md_cell(own.get('name', c['name']))} | "
                             f"{c.get('points', 1)} | {_md_cell(what)} |")
        written_from(write(docs / "labs" / lab / "index.md", "\n".join(parts) + "\n"),
                     (source if source.exists() else lab_dir / "README.md")
                     .relative_to(REPO).as_posix())
        assert not any((docs / "labs" / lab / d).exists() for d in PRIVATE_DIRS)
        rows.append(f"| [{_md_cell(title)}]({lab}/index.md) | "
                    f"{data.get('plant', '')} | {', '.join(data.get('languages', []))} |")
        nav.append(f"labs/{lab}/index.md")
        if lab in BROWSER_LABS:
            browser[lab] = _translated_lab_json(
                lab_json_from_dict(lab, data, _lab_wiring(lab_dir, data)), texts)
    write(docs / "labs" / "index.md", "\n".join(rows) + "\n")
    write(site_assets / "labs.json", json.dumps(browser, indent=1, ensure_ascii=False))
    return nav


def _lab_texts(lab_dir: Path) -> dict[str, Any]:
    """The lab's ``lab.<lang>.toml`` in a translated edition ({} in English or without one)."""
    path = lab_dir / f"lab.{language()}.toml"
    if language() == SOURCE or not path.exists():
        return {}
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def _untranslated_readme(readme: str, title: str) -> str:
    """A lab README with no translation yet: the translated title, a notice, the English."""
    # the README's generated criteria table is English: the page's own, translated, replaces it
    readme = re.sub(r"^<!-- criteria-table:start.*?^<!-- criteria-table:end -->\n?", "", readme,
                    flags=re.S | re.M)
    lines = readme.splitlines()
    at = next((i for i, line in enumerate(lines) if line.startswith("# ")), None)
    english = lines[at + 1:] if at is not None else lines
    head = lines[at][2:].strip() if at is not None else title
    return "\n".join([f"# {title}", "", '!!! note "' + tr("Not translated yet") + '"',
                      "    " + tr("The text of this lab is not translated yet; its English "
                                  "text follows. The title, the scenarios and the criteria "
                                  "below are translated."), "", f"*{head}*", *english]) + "\n"


def _translated_lab_json(lab: dict[str, Any], texts: dict[str, Any]) -> dict[str, Any]:
    """The playground's lab with the edition's title, scenario descriptions, criterion names
    (``label``: the ``name`` stays the key ``requires`` refers to) and messages."""
    if not texts:
        return lab
    lab["title"] = texts.get("title") or lab["title"]
    for s in lab["scenarios"]:
        s["description"] = texts.get("scenarios", {}).get(s["name"], {}).get(
            "description", s.get("description", ""))
    for c in lab["criteria"]:
        own = texts.get("criteria", {}).get(c["name"], {})
        if own.get("name"):
            c["label"] = own["name"]
        if own.get("message"):
            c["message"] = own["message"]
    return lab


# ------------------------------------------------------------------------------ problems


def problem_pages(docs: Path) -> list[Any]:
    """``problems/index.md`` (every code) and one page per code with its wrong and right
    example."""
    from plclab.problems import catalogue

    rows = [tr("# Diagnostic codes"), "", tr("Every message plclab prints carries a code. Each "
            "page says what it means and, for a mistake in a program, shows a wrong program and "
            "its fix (`plclab explain CODE` prints the same)."), "",
            tr("| code | title |"), "|---|---|"]
    for code, p in catalogue().items():
        title = problem_text(code, "title", p.title)
        page = [f"# {code}: {title}", "",
                problem_text(code, "explanation", p.explanation).strip(), ""]
        if p.reserved:
            page += [tr("*Reserved*: {why}", why=problem_text(
                code, "reserved_why", p.reserved_why or "no module raises it yet.")), ""]
        lang = p.language or "st"
        if p.wrong:
            page += [tr("## Wrong"), "", f"```{lang}", p.wrong.strip("\n"), "```", ""]
            if lang in PLAYGROUND_LANGUAGES:
                page += [f'<a class="try-it" href="{try_link(p.wrong, lang, 2)}'
                         f'&expect={code}">{tr("Try the wrong program")}</a>', ""]
        if p.fix:
            page += [tr("## Right"), "", f"```{lang}", p.fix.strip("\n"), "```", ""]
            if lang in PLAYGROUND_LANGUAGES:
                page += [f'<a class="try-it" href="{try_link(p.fix, lang, 2)}">'
                         f'{tr("Try the fix")}</a>', ""]
        if p.example:
            page += [tr("## Example"), "", "```text", p.example.strip("\n"), "```", ""]
        if p.no_example:
            page += [tr("*No example program*: {why}", why=problem_text(
                code, "no_example", p.no_example)), ""]
        write(docs / "problems" / code / "index.md", "\n".join(page))
        rows.append(f"| [{code}]({code}/index.md) | {_md_cell(title)} |")
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
