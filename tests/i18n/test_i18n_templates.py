"""A template is tied to the wording of its English message: when a raise site's English
changes, the template silently stops matching and Russian falls back to the title plus the
English text. So every code that has templates and a wrong example in plclab/problems.toml must
have the message its wrong example raises matched by one of them."""

import re
import tomllib

import pytest

import plclab
from plclab import i18n, i18n_check
from plclab.problems import catalogue
from plclab.project import check_sources
from plclab.testing import run_test_sources

RU = tomllib.loads(i18n_check.locale_file("ru", "problems").read_text(encoding="utf-8"))
TEMPLATED = sorted(c for c, e in RU.items()
                   if e.get("messages") and catalogue()[c].wrong is not None)


def messages_of(code: str) -> list[str]:
    """The messages of ``code`` that its wrong example raises (compiled, scanned or tested)."""
    p = catalogue()[code]
    name = f"wrong.{p.language or 'st'}"
    out = [d.message for d in check_sources([(p.wrong, name)], lint=True)[1] if d.code == code]
    if p.run == "test":
        out += [r.message for r in run_test_sources([(p.wrong, name)])
                if not r.passed and r.code == code]
    elif p.scans:
        try:
            plclab.loads(p.wrong, name).scan(p.scans)
        except plclab.PlcRuntimeFault as e:
            out.append(e.message)
    return out


def test_there_are_templated_codes_with_examples():
    assert len(TEMPLATED) >= 20 and "PLC0113" in TEMPLATED and "PLC2001" in TEMPLATED


@pytest.mark.parametrize("code", TEMPLATED)
def test_the_wrong_example_of_a_templated_code_is_translated(code):
    got = messages_of(code)
    assert got, f"{code}: its wrong example raised nothing"
    for message in got:
        if " (in " in message and code == "PLC2010":  # the ASSERT's text, added by `test`
            message = message[: message.index(" (in ")]
        ru = i18n.translate_by_templates(message, RU[code]["messages"], "ru")
        assert ru is not None, (f"{code}: no template of plclab/locale/ru/problems.toml matches "
                                f"{message!r}; the English wording changed? Update [{code}] "
                                "messages")
        assert ru != message and re.search("[а-яё]", ru), (code, ru)


def test_a_drifted_template_is_caught():
    stale = [{"en": "do not assign the FOR variable {name} within the loop", "ru": "x {name}"}]
    (message,) = [m for m in messages_of("PLC0113") if "do not assign" in m]
    assert i18n.translate_by_templates(message, stale, "ru") is None
