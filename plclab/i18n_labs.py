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
import tomllib
from pathlib import Path
from typing import Any

from .i18n import SOURCE, catalogue, language, localize_line, translate_by_templates

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


def detail(text: str, texts: dict[str, Any], lang: str | None = None) -> str:
    """A verdict's English detail in the language: the feedback templates of ``ui.toml``
    (``[[messages]]``), criterion names inside it in the language; else unchanged."""
    lang = lang or language()
    if lang == SOURCE or not text:
        return text
    got = translate_by_templates(text, catalogue(lang, "ui").get("messages", []), lang)
    if got is None:
        return text
    for en, entry in texts.get("criteria", {}).items():  # "counts only when 'X' passes"
        if isinstance(entry, dict) and entry.get("name"):
            got = got.replace(f"'{en}'", f"'{entry['name']}'")
    return got


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
        got = texts.get("scenarios", {}).get(run.name, {}).get("description")
        r2.description = got if isinstance(got, str) and got.strip() else run.description
        r2.notes = [detail(n, texts, lang) for n in run.notes]
        r2.error = localize_line(detail(run.error, texts, lang))
        runs.append(r2)
    out.scenarios = runs
    fixes = {criterion_text(texts, n, "name", n): criterion_text(texts, n, "hint_fix", f)
             for n, f in fixes.items()}
    return out, fixes
