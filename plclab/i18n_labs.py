"""A lab's texts in the language chosen: criterion names, messages and hints, scenario
descriptions and the title, from ``lab.<lang>.toml`` beside the lab's ``lab.toml`` (ADR 0063).

The file is keyed by the English names, so the scenarios and criteria stay one shared
definition in ``lab.toml``; a name missing there is shown in English::

    title = "Бак: двухпозиционное регулирование уровня"
    [criteria."pump starts below LS1"]
    name = "насос включается ниже LS1"
    message = "насос не включается, когда уровень ниже LS1"
    hint = "..."
    hint_fix = "..."
    [scenarios.normal]
    description = "..."

:func:`localize_result` turns a grading result (English, as the grading process made it) into
the language's before :func:`plclab.grade.feedback.render_feedback` writes it.
"""

from __future__ import annotations

import copy
import re
import tomllib
from pathlib import Path
from typing import Any

from .i18n import (
    SOURCE,
    catalogue,
    fill,
    language,
    localize_line,
    message,
    template_parts,
    tr_in,
)

TEXT_KEYS = ("name", "message", "hint", "hint_fix", "description")


def texts_file(lab_path: Path, lang: str) -> Path:
    """The file of ``lang`` texts of the lab whose folder is ``lab_path``."""
    return Path(lab_path) / f"lab.{lang}.toml"


def lab_texts(lab: Any, lang: str | None = None) -> dict[str, Any]:
    """The texts of ``lab`` (a :class:`plclab.grade.lab.Lab`) in ``lang`` ({} in English or
    when the lab has none)."""
    lang = lang or language()
    if lang == SOURCE:
        return {}
    path = texts_file(lab.path, lang)
    if not path.is_file():
        return {}
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as e:  # the English texts rather than no feedback
        import sys

        print(f"{path}: warning PLC9301: {e}; the English texts are shown instead",
              file=sys.stderr)
        return {}


def criterion_text(texts: dict[str, Any], name: str, key: str, english: str) -> str:
    """``key`` of criterion ``name`` from ``texts``, else ``english``."""
    got = texts.get("criteria", {}).get(name, {}).get(key)
    return got if isinstance(got, str) and got.strip() else english


def scenario_text(texts: dict[str, Any], name: str, english: str) -> str:
    """The description of scenario ``name`` from ``texts``, else ``english``."""
    got = texts.get("scenarios", {}).get(name, {}).get("description")
    return got if isinstance(got, str) and got.strip() else english


def detail(text: str, texts: dict[str, Any], lang: str | None = None) -> str:
    """A verdict's English detail in the language: the lab's own templates (``messages`` of
    ``lab.<lang>.toml``, for the texts of its ``checks.py``), then the feedback templates of
    ``ui.toml``; criterion names inside it in the language; else unchanged."""
    lang = lang or language()
    if lang == SOURCE or not text:
        return text
    ui = catalogue(lang, "ui")
    templates = [*texts.get("messages", []), *ui.get("messages", [])]
    phrases = [*texts.get("phrases", []), *ui.get("phrases", [])]
    got = translate_nested(text, templates, lang, phrases)
    if got is None:
        return text
    for en, entry in texts.get("criteria", {}).items():  # "counts only when 'X' passes"
        if isinstance(entry, dict) and entry.get("name"):
            got = got.replace(f"'{en}'", f"'{entry['name']}'")
    return got


def translate_nested(text: str, templates: list[dict[str, str]], lang: str,
                     phrases: list[dict[str, str]] = (), depth: int = 3) -> str | None:
    """``text`` in ``lang`` by the most specific of ``templates`` that matches all of it (the
    one with the most literal text: ``"{name} = {v} at {t:time}"`` matches much that a longer
    template says better), and each captured part that one of ``phrases`` or of
    ``templates`` matches is translated too (a check's message that quotes a part made
    elsewhere: ``"at the end: {what}"`` with ``what = "the tub is not empty"``, a plant event's
    text, a verdict inside a note). Phrases apply only to such parts, never to a whole
    message; a part ``{fault}`` beside a ``{code}`` is that code's diagnostic
    (:func:`plclab.i18n.message`). None when no template matches."""
    found = []
    for t in templates:
        en, target = t.get("en"), t.get(lang)
        if en and target and (parts := template_parts(en, text)) is not None:
            found.append((-len(_LITERAL.sub("", en)), len(found), parts, target))
    for _, _, parts, target in sorted(found, key=lambda f: f[:2]):
        if depth > 0:
            for k, v in parts.items():
                if k == "fault" and "code" in parts:
                    parts[k] = message(parts["code"], v, lang)
                elif v and not _NUMBER.fullmatch(v):
                    parts[k] = (translate_nested(v, phrases, lang, phrases, depth - 1)
                                or translate_nested(v, templates, lang, phrases, depth - 1)
                                or v)
        try:
            return fill(target, parts, lang)
        except (KeyError, ValueError, IndexError):  # a bad translation: the next one
            continue
    return None


_LITERAL = re.compile(r"\{[^{}]*\}")
_NUMBER = re.compile(r"[-+]?[\d.]+")


def localize_result(result: Any, lab: Any, lang: str | None = None) -> tuple[Any, dict]:
    """A copy of the grading ``result`` of ``lab`` with its texts in the language, and the
    literal fixes (criterion name in the language -> ``hint_fix``) for ``--hint 2``."""
    lang = lang or language()
    fixes = {c.name: c.hint_fix for c in lab.criteria if c.hint_fix}
    if lang == SOURCE:
        return result, fixes
    texts = lab_texts(lab, lang)
    out = copy.copy(result)
    out.lab_title = texts.get("title") or result.lab_title
    out.message = detail(result.message, texts, lang)
    specs = {c.name: c for c in lab.criteria}
    tests = []
    for t in result.tests:
        t2 = copy.copy(t)
        spec = specs.get(t.criterion)
        t2.criterion = criterion_text(texts, t.criterion, "name", t.criterion)
        t2.name = f"{t.scenario}: {t2.criterion}"
        msg = t.message
        en_msg = getattr(spec, "message", "") if spec is not None else ""
        if en_msg and msg.startswith(en_msg + ": "):
            rest = msg[len(en_msg) + 2:]
            msg = (f"{criterion_text(texts, t.criterion, 'message', en_msg)}: "
                   f"{detail(rest, texts, lang)}")
        elif en_msg and msg == en_msg:
            msg = criterion_text(texts, t.criterion, "message", en_msg)
        else:
            msg = detail(msg, texts, lang)
        t2.message = msg
        t2.hint = criterion_text(texts, t.criterion, "hint", t.hint) if t.hint else t.hint
        tests.append(t2)
    out.tests = tests
    runs = []
    for run in result.scenarios:
        r2 = copy.copy(run)
        r2.description = scenario_text(texts, run.name, run.description)
        r2.notes = [detail(n, texts, lang) for n in run.notes]
        r2.error = localize_line(detail(run.error, texts, lang))
        runs.append(r2)
    out.scenarios = runs
    fixes = {criterion_text(texts, n, "name", n): criterion_text(texts, n, "hint_fix", f)
             for n, f in fixes.items()}
    return out, fixes


def readme_path(lab_path: Path, lang: str | None = None) -> Path:
    """The task a student reads: ``README.<lang>.md`` when the lab has one in ``lang``, else
    ``README.md``."""
    lang = lang or language()
    own = Path(lab_path) / f"README.{lang}.md"
    return own if lang != SOURCE and own.is_file() else Path(lab_path) / "README.md"


def lab_text(texts: dict[str, Any], key: str, english: Any) -> Any:
    """A top-level text of the lab (``title``, ``summary``, ``goals``) from ``texts``, else
    ``english``."""
    got = texts.get(key)
    if isinstance(english, list):
        ok = isinstance(got, list) and len(got) == len(english) and all(
            isinstance(g, str) and g.strip() for g in got)
        return got if ok else english
    return got if isinstance(got, str) and got.strip() else english


def io_text(texts: dict[str, Any], name: str, key: str, english: str) -> str:
    """``key`` (``description``, ``unit``) of the I/O row ``name`` from ``texts``, else
    ``english``."""
    got = texts.get("io", {}).get(name, {}).get(key)
    return got if isinstance(got, str) and (got.strip() or not english.strip()) else english


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def io_table_markdown(lab: Any, lang: str | None = None) -> str:
    """The I/O table of ``lab`` as Markdown in ``lang`` (``README.<lang>.md`` holds it): the
    names, addresses and types as in ``lab.toml``, the header, units and descriptions in the
    language."""
    lang = lang or language()
    if lang == SOURCE:
        return lab.io_table_markdown()
    texts = lab_texts(lab, lang)
    rows = [f"| {tr_in(lang, 'Name')} | {tr_in(lang, 'Address')} | {tr_in(lang, 'Type')} | "
            f"{tr_in(lang, 'Unit')} | {tr_in(lang, 'Description')} |", "|---|---|---|---|---|"]
    for r in lab.io:
        rows.append(f"| `{r.name}` | `{r.address}` | {r.type} | "
                    f"{io_text(texts, r.name, 'unit', r.unit)} | "
                    f"{io_text(texts, r.name, 'description', r.description)} |")
    return "\n".join(rows)


def criteria_table_markdown(lab: Any, lang: str | None = None) -> str:
    """The criteria table of ``lab`` in ``lang``: the names, the scenarios and what each
    checks in the language; the check and its parameters as in ``lab.toml`` (they are code)."""
    lang = lang or language()
    if lang == SOURCE:
        return lab.criteria_table_markdown()
    texts = lab_texts(lab, lang)
    hidden = {s.name for s in lab.scenarios if not s.visible}
    rows = [f"| {tr_in(lang, 'Criterion')} | {tr_in(lang, 'Scenarios')} | "
            f"{tr_in(lang, 'Points')} | {tr_in(lang, 'Check')} | {tr_in(lang, 'What it checks')} |",
            "|---|---|---|---|---|"]
    for c in lab.criteria:
        scs = ", ".join(f"`{s}`" + (f" ({tr_in(lang, 'hidden')})" if s in hidden else "")
                        for s in c.scenarios)
        name = criterion_text(texts, c.name, "name", c.name)
        what = (criterion_text(texts, c.name, "description", c.description) if c.description
                else criterion_text(texts, c.name, "message", c.message))
        flags = f" ({tr_in(lang, 'critical')})" if c.critical else ""
        each = tr_in(lang, "{points} each", points=f"{c.points:g}")
        rows.append(f"| {name}{flags} | {scs} | {each} | `{_cell(c.summary())}` | "
                    f"{_cell(what)} |")  # the check is code: its numbers keep their point
    return "\n".join(rows)
