"""Checks of the translations (ADR 0063): what a shipped language lacks, and templates whose
placeholders differ from the English text's. ``tests/i18n`` runs them on the real files and on
broken copies; each finding is one line that says what is missing and where to add it.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path
from typing import Any

from .i18n import LOCALE_DIR, fields

PLCLAB_DIR = Path(__file__).resolve().parent
STATUS_AND_SEVERITY = ("error", "warning")


def placeholder_problems(pairs: list[tuple[str, str, str]]) -> list[str]:
    """``(where, english, translated)`` triples whose placeholder names differ (a translation
    may repeat or reorder them, not drop or invent one).

    >>> placeholder_problems([("x", "{a} of {b}", "{b} из {a}"), ("y", "{a}", "{c}")])
    ['y: the translation has {c} where the English has {a}']
    """
    out = []
    for where, en, tr in pairs:
        try:
            a, b = set(fields(en)), set(fields(tr))
        except ValueError as e:  # an unclosed brace
            out.append(f"{where}: not a valid template ({e})")
            continue
        if a != b:
            has = ", ".join("{" + f + "}" for f in sorted(b)) or "no placeholder"
            want = ", ".join("{" + f + "}" for f in sorted(a)) or "no placeholder"
            out.append(f"{where}: the translation has {has} where the English has {want}")
    return out


def catalogue_pairs(problems: dict[str, Any], ui: dict[str, Any],
                    lang: str) -> list[tuple[str, str, str]]:
    """Every (where, English, translation) of a language's ``problems.toml`` messages and
    ``ui.toml`` (its keys are the English templates; argparse's ``%(x)s`` ones are compared
    by their ``%`` names)."""
    pairs = []
    for code, entry in problems.items():
        for i, m in enumerate(entry.get("messages", []) if isinstance(entry, dict) else []):
            pairs.append((f"problems.toml [{code}] messages[{i}]", m.get("en", ""),
                          m.get(lang, "")))
    for key, value in ui.items():
        if isinstance(value, str):
            if "%(" in key or "%s" in key or "%r" in key:
                pairs.append((f"ui.toml {key!r}", _percent(key), _percent(value)))
            else:
                pairs.append((f"ui.toml {key!r}", key, value))
    for i, m in enumerate(ui.get("messages", [])):
        pairs.append((f"ui.toml messages[{i}]", m.get("en", ""), m.get(lang, "")))
    return pairs


def _percent(text: str) -> str:
    """``%(prog)s: %s`` as a brace template (``{prog}: {_1}``) for the placeholder check."""
    n = iter(range(1, 100))
    return re.sub(r"%\((\w+)\)[sr]|%[sr]", lambda m: "{" + (m[1] or f"_{next(n)}") + "}",
                  text.replace("{", "{{").replace("}", "}}"))


def missing_problems(codes: list[str], problems: dict[str, Any], lang: str,
                     english: dict[str, dict[str, Any]] | None = None) -> list[str]:
    """Codes of ``plclab/problems.toml`` without a title or an explanation in ``lang`` (and,
    with the ``english`` entries, without the ``no_example`` or ``reserved_why`` they have)."""
    out = []
    for code in codes:
        entry = problems.get(code, {})
        extra = [k for k in ("no_example", "reserved_why") if (english or {}).get(code, {}).get(k)]
        lacks = [k for k in ("title", "explanation", *extra)
                 if not (isinstance(entry.get(k), str) and entry[k].strip())]
        if lacks:
            out.append(f"{code}: no {' and no '.join(lacks)} in plclab/locale/{lang}/problems.toml"
                       f" (add [{code}] with {', '.join(lacks)} next to its numeric "
                       "neighbours)")
    return out


def tr_keys(root: Path = PLCLAB_DIR) -> dict[str, str]:
    """Every literal template passed to ``tr()`` (or ``tr_in(lang, ...)``) in plclab's source:
    template -> file:line."""
    keys: dict[str, str] = {}
    for f in sorted(root.rglob("*.py")):
        tree = ast.parse(f.read_text(encoding="utf-8"))
        for n in ast.walk(tree):
            if not (isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
                    and n.func.id in ("tr", "tr_in")):
                continue
            k = 1 if n.func.id == "tr_in" else 0  # tr_in(lang, "template")
            if (len(n.args) > k and isinstance(n.args[k], ast.Constant)
                    and isinstance(n.args[k].value, str)):
                keys.setdefault(n.args[k].value, f"{f.relative_to(root.parent)}:{n.lineno}")
    return keys


def missing_ui(keys: dict[str, str], ui: dict[str, Any], lang: str) -> list[str]:
    """Templates of ``keys`` (template -> where it is used) without a ``lang`` text."""
    return [f"{where}: tr({key!r}) has no text in plclab/locale/{lang}/ui.toml"
            for key, where in keys.items() if not isinstance(ui.get(key), str)]


def missing_lab_texts(lab_dir: Path, lang: str) -> list[str]:
    """What the lab in ``lab_dir`` lacks in its ``lab.<lang>.toml``: the title, each criterion's
    name and, where ``lab.toml`` has them, its message, hint, hint_fix and description, each
    scenario's description, the summary, the goals, the I/O table's descriptions and units;
    and criteria or I/O rows it names that ``lab.toml`` does not have."""
    import tomllib

    spec = tomllib.loads((lab_dir / "lab.toml").read_text(encoding="utf-8-sig"))
    path = lab_dir / f"lab.{lang}.toml"
    texts = tomllib.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}
    crits = texts.get("criteria", {})
    where = f"labs/{lab_dir.name}/{path.name}"
    out = [] if str(texts.get("title", "")).strip() else [f"{lab_dir.name}: no title in {where}"]
    for c in spec.get("criterion", []):
        name = c.get("name", "")
        got = crits.get(name) if isinstance(crits.get(name), dict) else {}
        for key in ("name", "message", "hint", "hint_fix"):
            if (key == "name" or c.get(key)) and not str(got.get(key, "")).strip():
                out.append(f"{lab_dir.name}: criterion {name!r} has no {key} in {where} (add "
                           f'[criteria.{_q(name)}] {key} = "...")')
    scen = texts.get("scenarios", {})
    for sc in spec.get("scenario", []):
        name = sc.get("name", "")
        if sc.get("description") and not str(scen.get(name, {}).get("description", "")).strip():
            out.append(f"{lab_dir.name}: scenario {name!r} has no description in {where} (add "
                       f'[scenarios.{_q(name)}] description = "...")')
    for c in spec.get("criterion", []):  # what lab show and the README's table print
        got = crits.get(c.get("name", ""))
        if c.get("description") and not str((got or {}).get("description", "")).strip():
            out.append(f"{lab_dir.name}: criterion {c.get('name')!r} has no description in "
                       f'{where} (add [criteria.{_q(c.get("name", ""))}] description = "...")')
    out += _missing_task_texts(lab_dir.name, spec, texts, where)
    for name in crits:
        if name not in {c.get("name") for c in spec.get("criterion", [])}:
            out.append(f"{lab_dir.name}: {path.name} names criterion {name!r}, which lab.toml "
                       "does not have (renamed? rename it here too)")
    return out


def _missing_task_texts(lab: str, spec: dict[str, Any], texts: dict[str, Any],
                        where: str) -> list[str]:
    """The task's texts a lab lacks in a language: ``summary``, ``goals`` (as many as in
    English) and the description (and unit) of each row of the I/O table."""
    out = []
    if spec.get("summary") and not str(texts.get("summary", "")).strip():
        out.append(f'{lab}: no summary in {where} (add summary = "...")')
    goals = texts.get("goals")
    if spec.get("goals") and not (isinstance(goals, list) and len(goals) == len(spec["goals"])):
        out.append(f"{lab}: goals in {where} are not the {len(spec['goals'])} goals of "
                   'lab.toml (add goals = ["...", ...])')
    io = texts.get("io", {})
    for row in spec.get("io", []):
        name = row.get("name", "")
        for key in ("description", "unit"):
            if row.get(key) and not str(io.get(name, {}).get(key, "")).strip():
                out.append(f"{lab}: I/O row {name!r} has no {key} in {where} (add "
                           f'[io.{_q(name)}] {key} = "...")')
    for name in io:
        if name not in {row.get("name") for row in spec.get("io", [])}:
            out.append(f"{lab}: {where} names I/O row {name!r}, which lab.toml does not have")
    return out


def _q(name: str) -> str:
    return '"' + name.replace('"', '\\"') + '"'


def parser_helps(parser: Any, where: str = "plclab") -> dict[str, str]:
    """Every help text and description of an argparse ``parser`` and its sub-commands:
    text -> the command it belongs to."""
    import argparse

    helps: dict[str, str] = {}
    if parser.description:
        helps.setdefault(parser.description, where)
    for action in parser._actions:
        if action.help and action.help != argparse.SUPPRESS:
            helps.setdefault(action.help, where)
        if isinstance(action, argparse._SubParsersAction):
            for choice in action._choices_actions:
                if choice.help:
                    helps.setdefault(choice.help, where)
            for name, sub in action.choices.items():
                for text, w in parser_helps(sub, f"{where} {name}").items():
                    helps.setdefault(text, w)
    return helps


def missing_help(helps: dict[str, str], ui: dict[str, Any], lang: str) -> list[str]:
    """Help texts of ``helps`` without a ``lang`` text in ``ui.toml``."""
    return [f"{where} --help: {text!r} has no text in plclab/locale/{lang}/ui.toml (add it "
            "under 'command-line help')" for text, where in helps.items()
            if not isinstance(ui.get(text), str)]


def locale_file(lang: str, name: str) -> Path:
    """``plclab/locale/<lang>/<name>.toml``."""
    return LOCALE_DIR / lang / f"{name}.toml"


# ----------------------------------------------------------------------- English left over

ENGLISH_WORDS = frozenset("""
a after again all also an and any are as at be been before both but by can cannot did do does
each every for from has have here how if in into is it its just less more must never no not of
off on once only or other out over same should so some still than that the then there these this
those to too under until up very was were what when which while who will with within would yet
you your""".split())
"""Short English words that are not ST keywords, identifiers or units: a run of Latin words
with one of them in it is an English sentence (:func:`english_runs`)."""

_CODE_SPAN = re.compile(r"`[^`]*`")
_TOKEN = re.compile(r"[A-Za-z]+(?:['’-][A-Za-z]+)*|[^\sA-Za-z]")
_LOWER = re.compile(r"[a-z]+(?:['’-][a-z]+)*")


def english_runs(line: str, min_words: int = 3) -> list[str]:
    """The English phrases left in a line of a translated text: runs of ``min_words`` or more
    lowercase Latin words (commas and colons may come between them), one of them a common
    English word, outside `code spans`. Identifiers (``START``, ``%QX0.0``), units, codes
    and ST in backticks are not runs.

    >>> english_runs("насос включается: `PUMP and not LS2` at t = 3,5 с")
    []
    >>> english_runs("ящик 1 закрыт: box 1 was closed after 2 bottle(s)")
    ['was closed after']
    """
    out: list[str] = []
    run: list[str] = []

    def flush() -> None:
        if len(run) >= min_words and any(w.lower() in ENGLISH_WORDS for w in run):
            out.append(" ".join(run))

    for tok in _TOKEN.findall(_CODE_SPAN.sub(" # ", line.replace("\\`", "`"))):
        if _LOWER.fullmatch(tok):
            run.append(tok)
        elif tok in ",:;" and run:
            continue
        else:
            flush()
            run = []
    flush()
    return out


def check_messages(path: Path) -> list[str]:
    """Sample texts of the messages a lab's ``checks.py`` returns (the string of a
    ``return (passed, message, ...)`` or of ``Verdict(passed, message)``): each f-string with
    ``1.5`` for a formatted number and ``X`` for any other part. A message built in pieces
    (``msg += ...``) or only of other parts (``f"{head}: {why}"``) is not found;
    :func:`english_runs` on a real run finds those."""
    src = path.read_text(encoding="utf-8")
    out: list[str] = []
    for n in ast.walk(ast.parse(src)):
        cands = []
        if isinstance(n, ast.Return) and isinstance(n.value, ast.Tuple) \
                and len(n.value.elts) >= 2:
            cands.append(n.value.elts[1])
        if isinstance(n, ast.Call) and getattr(n.func, "id", "") == "Verdict" \
                and len(n.args) >= 2:
            cands.append(n.args[1])
        for c in cands:
            text = _sample(c)
            if text is not None and re.sub(r"X|[^A-Za-z]", "", text) == "":
                continue  # made only of parts ("{head}: {why}"): the parts are found
            if text is not None and text not in out:
                out.append(text)
    return out


def _sample(node: ast.AST) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if not isinstance(node, ast.JoinedStr):
        return None
    parts = []
    for v in node.values:
        if isinstance(v, ast.Constant):
            parts.append(str(v.value))
        else:
            spec = "".join(c.value for c in getattr(v.format_spec, "values", [])
                           if isinstance(c, ast.Constant))
            parts.append("1.5" if any(ch in spec for ch in "fg%") else "X")
    return "".join(parts)


def untranslated_check_messages(lab_dir: Path, lang: str) -> list[str]:
    """The messages of the lab's ``checks.py`` that no template of its ``lab.<lang>.toml``
    (``messages``) or of ``ui.toml`` turns into ``lang``; each with where to add it."""
    import tomllib

    from .i18n_labs import translate_nested

    checks = lab_dir / "checks.py"
    if not checks.is_file():
        return []
    path = lab_dir / f"lab.{lang}.toml"
    texts = tomllib.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}
    ui = tomllib.loads(locale_file(lang, "ui").read_text(encoding="utf-8"))
    templates = [*texts.get("messages", []), *ui.get("messages", [])]
    return [f"labs/{lab_dir.name}/checks.py: {m!r} has no template in labs/{lab_dir.name}/"
            f'{path.name} (add to messages: {{ en = "...", {lang} = "..." }})'
            for m in check_messages(checks)
            if translate_nested(m, templates, lang) is None]
