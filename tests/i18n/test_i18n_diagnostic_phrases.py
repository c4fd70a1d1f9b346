"""The words a diagnostic quotes from the parser (``expected {what}``) are translated inside
the code's Russian template, and every such phrase in the catalogue is one the parser says."""

from pathlib import Path

import pytest

from plclab import i18n
from plclab.errors import PlcError
from plclab.i18n_check import english_runs

ROOT = Path(__file__).resolve().parents[2]


def diagnostics(src: str) -> list[str]:
    import plclab

    try:
        plclab.loads(src)
    except PlcError as e:
        return [i18n.message(d.code, d.message) for d in e.diagnostics]
    return []


@pytest.mark.parametrize("src", [
    "PROGRAM P\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n",
    "PROGRAM P\nVAR x : INT END_VAR\nx := 1\nEND_PROGRAM\n",
    "PROGRAM P\nVAR x : ; END_VAR\nEND_PROGRAM\n",
])
def test_what_the_parser_expected_is_russian(russian, src):
    got = diagnostics(src)
    assert got and all(not english_runs(m, min_words=2) for m in got), got


def test_without_the_phrase_the_english_words_would_show(russian, ru_ui):
    ru_ui({"diagnostic_phrases": []})
    got = diagnostics("PROGRAM P\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n")
    assert any(english_runs(m, min_words=2) for m in got), got


def test_every_phrase_is_one_the_parser_says():
    source = "".join(p.read_text(encoding="utf-8") for p in (ROOT / "plclab").rglob("*.py"))
    phrases = i18n.catalogue("ru", "ui")["diagnostic_phrases"]
    stale = [p["en"] for p in phrases if f'"{p["en"]}"' not in source]
    assert not stale, stale
