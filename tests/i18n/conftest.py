"""Fixtures of the language tests: Russian for one test, and a Russian ``ui.toml`` with a
change (to show what a test would catch when a text is missing)."""

import pytest

from plclab import i18n


@pytest.fixture
def russian():
    """The language in use is Russian for this test, English again after it."""
    i18n.set_language("ru")
    yield
    i18n.set_language(None)


@pytest.fixture
def ru_ui(monkeypatch):
    """``ru_ui(key=value, ...)``: the Russian ``ui.toml`` with these entries replaced (None
    removes one) for the rest of the test."""
    def change(changes: dict) -> None:
        ui = dict(i18n.catalogue("ru", "ui"))
        for key, value in changes.items():
            if value is None:
                ui.pop(key, None)
            else:
                ui[key] = value
        real = i18n.catalogue
        monkeypatch.setattr(i18n, "catalogue",
                            lambda lang, name: ui if name == "ui" else real(lang, name))
    return change
