"""The language of plclab's messages: English (the source texts) and Russian.

One mechanism for every text a student reads (ADR 0063): the English text stays where it is
written (an f-string at a raise site, ``problems.toml``, a lab's ``lab.toml``); a language's
texts live in ``plclab/locale/<lang>/*.toml``, keyed by what they translate:

- ``problems.toml``: by code, the ``title`` and ``explanation`` of the explain page and
  ``messages``, a list of ``{ en = ..., ru = ... }`` templates matched against a diagnostic's
  English message (``"undeclared name '{name}'"``) so that its parameters carry over;
- ``ui.toml``: command-line lines, feedback lines, argparse help, keyed by the English
  template itself (gettext's msgid, in TOML);
- a lab's own ``lab.<lang>.toml`` beside its ``lab.toml``: criterion names, messages, hints.

The language is ``--lang`` (:func:`set_language`), else ``PLCLAB_LANG``, else the locale
(``LC_ALL``, ``LC_MESSAGES``, ``LANG``); English when none names a shipped language. A text
missing in a language is shown in English. Files are read lazily, only when a language other
than English is chosen, so ``import plclab`` reads none of them.

>>> set_language("en"); tr("{n} passed", n=3)
'3 passed'
>>> set_language(None)
"""

from __future__ import annotations

import os
import re
import string
from functools import cache
from pathlib import Path
from typing import Any

SOURCE = "en"
LANGUAGES = ("en", "ru")
"""The shipped languages (tests/i18n checks that none of their texts is missing)."""
LOCALE_DIR = Path(__file__).with_name("locale")
ENV = "PLCLAB_LANG"

_chosen: str | None = None  # --lang
_resolved: str | None = None


def normalize(tag: str | None) -> str | None:
    """``ru_RU.UTF-8`` -> ``ru``; ``C``, ``POSIX``, empty or unknown -> None.

    >>> normalize("ru_RU.UTF-8"), normalize("en"), normalize("C"), normalize("de_DE")
    ('ru', 'en', None, None)
    """
    if not tag:
        return None
    base = re.split(r"[_.@-]", tag.strip().lower(), maxsplit=1)[0]
    return base if base in LANGUAGES else None


def set_language(lang: str | None) -> None:
    """Choose the language (``--lang``); None forgets the choice and reads the environment
    again on the next :func:`language`. An unknown language is a ValueError (the command line
    reports it as PLC9300)."""
    global _chosen, _resolved
    if lang is not None and normalize(lang) is None:
        raise ValueError(unknown_language(lang))
    _chosen = normalize(lang) if lang is not None else None
    _resolved = None


def unknown_language(lang: str) -> str:
    """The message of PLC9300 for ``--lang lang``."""
    return f"--lang {lang}: plclab speaks {', '.join(LANGUAGES)}; write e.g. --lang ru"


def chosen() -> str | None:
    """The language set by :func:`set_language` (``--lang``), None when none is."""
    return _chosen


def language() -> str:
    """The language in use: ``--lang``, else ``PLCLAB_LANG``, else the locale, else English.
    A ``PLCLAB_LANG`` naming no shipped language is ignored (the next source decides)."""
    global _resolved
    if _chosen is not None:
        return _chosen
    if _resolved is None:
        found = None
        for var in (ENV, "LC_ALL", "LC_MESSAGES", "LANG"):
            value = os.environ.get(var)
            if value:  # the first one set decides, as in POSIX (LC_ALL hides LANG)
                found = normalize(value)
                if found or var != ENV:
                    break
        _resolved = found or SOURCE
    return _resolved


@cache
def catalogue(lang: str, name: str) -> dict[str, Any]:
    """``plclab/locale/<lang>/<name>.toml`` as a dict ({} when there is none)."""
    path = LOCALE_DIR / lang / f"{name}.toml"
    if lang == SOURCE or not path.is_file():
        return {}
    import tomllib

    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as e:  # a broken translation must not stop a student's work
        import sys

        print(f"{path}: warning PLC9301: {e}; the English texts are shown instead",
              file=sys.stderr)
        return {}


# ------------------------------------------------------------------------------ templates


def fields(template: str) -> list[str]:
    """The placeholder names of a ``str.format`` template, in order (``{t:num}`` -> ``t``).

    >>> fields("{a} and {b:num}, {{not}}")
    ['a', 'b']
    """
    return [f.split(".")[0].split("[")[0] for _, f, _, _ in string.Formatter().parse(template)
            if f is not None]


def decimal(text: str, lang: str | None = None) -> str:
    """Numbers in prose with the language's decimal separator (a comma in Russian): every
    ``1.25`` in ``text`` becomes ``1,25``. Never for ST literals or values shown as ST.

    >>> decimal("t = 12.50 s", "ru"), decimal("t = 12.50 s", "en")
    ('t = 12,50 s', 't = 12.50 s')
    >>> decimal("`LEVEL >= 1.45` at 3.5 s, T#1.5s", "ru")
    '`LEVEL >= 1.45` at 3,5 s, T#1.5s'

    """
    lang = lang or language()
    if lang != "ru":
        return text
    parts = text.split("`")  # `code` spans are ST: their numbers keep the point
    for i in range(0, len(parts), 2):
        parts[i] = re.sub(r"(?<![\w.#])(-?\d+)\.(\d+)(?![\w.])", r"\1,\2", parts[i])
    return "`".join(parts)


def duration(text: str, lang: str | None = None) -> str:
    """A duration in prose (``1 min 2.5 s``, ``0.25 s``) in the language's words and numbers.

    >>> duration("1 min 2.5 s", "ru")
    '1 мин 2,5 с'
    """
    lang = lang or language()
    if lang != "ru":
        return text
    text = re.sub(r"\bmin\b", "мин", re.sub(r"\bms\b", "мс", text))
    return decimal(re.sub(r"(?<=\d) s\b", " с", text), lang)


def fill(template: str, params: dict[str, Any], lang: str | None = None) -> str:
    """``template`` with ``params``; a ``{x:num}`` placeholder gets the language's decimal
    separator, the other format specs are Python's."""
    out = []
    for literal, name, spec, conv in string.Formatter().parse(template):
        out.append(literal)
        if name is None:
            continue
        value = params[name]
        if conv == "r":
            value = repr(value)
        elif conv == "s":
            value = str(value)
        if spec == "num":
            out.append(decimal(value if isinstance(value, str) else f"{value:g}", lang))
        elif spec == "time":  # "1 min 2.5 s" as plclab.grade.criteria.fmt_t writes it
            out.append(duration(str(value), lang))
        else:
            out.append(format(value, spec))
    return "".join(out)


def tr(template: str, /, **params: Any) -> str:
    """A command-line or feedback text in the current language: ``template`` is the English
    text (with ``{name}`` placeholders), also the key of ``locale/<lang>/ui.toml``."""
    return tr_in(language(), template, **params)


def tr_in(lang: str, template: str, /, **params: Any) -> str:
    """:func:`tr` in ``lang`` rather than the language in use (a README's table in Russian
    written by an English command line)."""
    if lang != SOURCE:
        got = catalogue(lang, "ui").get(template)
        if isinstance(got, str):
            if not params:
                return got
            try:
                return fill(got, params, lang)
            except (KeyError, ValueError, IndexError):  # a bad translation: the English text
                pass
    return fill(template, params, SOURCE) if params else template


@cache
def _pattern(template: str) -> re.Pattern[str]:
    """The regular expression that matches what ``template`` formats to (a placeholder is any
    text; a name used twice must match the same text)."""
    parts, seen = [], set()
    for literal, name, _, _ in string.Formatter().parse(template):
        parts.append(re.escape(literal))
        if name is None:
            continue
        if name in seen:
            parts.append(f"(?P={name})")
        else:
            seen.add(name)
            parts.append(f"(?P<{name}>.*?)")
    return re.compile("".join(parts), re.DOTALL)


def template_parts(template: str, text: str) -> dict[str, str] | None:
    """The parts of ``text`` by the placeholders of ``template`` when the template matches
    all of it, else None.

    >>> template_parts("{n} passed", "3 passed"), template_parts("{n} passed", "3 failed")
    ({'n': '3'}, None)
    """
    m = _pattern(template).fullmatch(text)
    return m.groupdict() if m else None


def translate_by_templates(text: str, templates: list[dict[str, str]], lang: str,
                           phrases: list[dict[str, str]] = ()) -> str | None:
    """``text`` matched against the English side of ``templates`` (the first whose ``en``
    matches all of it) and formatted with the ``lang`` side; None when none matches. A
    captured part that one of ``phrases`` matches whole is translated too (the parser's
    ``expected {what}`` with ``what = "an expression"``).

    >>> translate_by_templates("expected an expression, found ';'",
    ...     [{"en": "expected {what}, found {found}", "ru": "ожидалось {what}, а найдено {found}"}],
    ...     "ru", [{"en": "an expression", "ru": "выражение"}])
    "ожидалось выражение, а найдено ';'"
    """
    for t in templates:
        en, target = t.get("en"), t.get(lang)
        if not en or not target:
            continue
        m = _pattern(en).fullmatch(text)
        if m:
            parts = m.groupdict()
            if phrases:
                parts = {k: (translate_by_templates(v, phrases, lang) or v) if v else v
                         for k, v in parts.items()}
            try:
                return fill(target, parts, lang)
            except (KeyError, ValueError, IndexError):  # a bad translation: the next one
                continue
    return None


# ------------------------------------------------------------------------------ problems


def problem_text(code: str, key: str, english: str, lang: str | None = None) -> str:
    """The ``title`` or ``explanation`` (``key``) of ``code`` in the language; ``english``
    when it has none."""
    lang = lang or language()
    if lang == SOURCE:
        return english
    got = catalogue(lang, "problems").get(code, {}).get(key)
    return got if isinstance(got, str) and got.strip() else english


def message(code: str, text: str, lang: str | None = None) -> str:
    """A diagnostic's English message ``text`` of ``code`` in the language: the first of the
    code's templates that matches it; else the fragments of ``ui.toml``'s ``[fragments]``;
    else the code's title in the language before the English text (English when the code
    has no title there either)."""
    lang = lang or language()
    if lang == SOURCE:
        return text
    entry = catalogue(lang, "problems").get(code, {})
    phrases = catalogue(lang, "ui").get("diagnostic_phrases", [])
    got = translate_by_templates(text, entry.get("messages", []), lang, phrases)
    if got is None:
        got = translate_by_templates(text, catalogue(lang, "ui").get("messages", []), lang,
                                     phrases)
    if got is not None:
        return got
    title = entry.get("title")
    return f"{title}: {text}" if title else text


SEVERITY = {"error": "error", "warning": "warning"}


def severity(word: str, lang: str | None = None) -> str:
    """``error``/``warning`` in the language (``ошибка``/``предупреждение``)."""
    return tr(word) if (lang or language()) != SOURCE else word


_LINE = re.compile(r"^(?P<where>.*?: )?(?P<sev>error|warning) (?P<code>PLC\d{4}): (?P<msg>.*)$",
                   re.DOTALL)


def localize_line(line: str) -> str:
    """A diagnostic already rendered in English (``file:1:2: error PLC0100: ...``, as a child
    process or a saved result holds it) in the current language; other text unchanged."""
    if language() == SOURCE:
        return line
    m = _LINE.match(line)
    if not m:
        return line
    return (f"{m['where'] or ''}{severity(m['sev'])} {m['code']}: "
            f"{message(m['code'], m['msg'])}")
