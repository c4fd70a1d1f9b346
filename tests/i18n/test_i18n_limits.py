"""What a criterion checks, as the failure pictures and the "checks:" lines word it, is Russian
under ``--lang ru`` for every built-in check: no English word is left around the signal names,
ST conditions and numbers (which stay as they are, numbers with a decimal comma)."""

import re

import pytest

from plclab.grade.criteria_limits import describe_limits, limits_of
from plclab.i18n_check import english_runs

# one set of parameters per built-in check that has limits; names upper case, like a lab's
CHECKS = {
    "never": {"condition": "LEVEL >= 1.75", "from": 6},
    "always": {"condition": "TEMP > 48.5 AND TEMP < 52", "to": 60},
    "eventually": {"condition": "LEVEL >= 1.5"},
    "implies": {"if": "LS2", "then": "NOT PUMP"},
    "within": {"trigger": "START", "response": "K1", "time": 0.5},
    "alarm_within": {"trigger": "LEVEL > 1.9", "alarm": "HI", "time": 2},
    "ack_before_restart": {"restart": "PUMP", "alarm": "HI", "time": 1.5},
    "in_band": {"signal": "TEMP", "lo": 48, "hi": 52, "min_fraction": 0.9},
    "settles": {"signal": "TEMP", "target": 60, "band": 0.5, "within": 600},
    "value": {"signal": "COUNT", "min": 3, "max": 7.5, "at": 90},
    "max_switchings": {"signal": "PUMP", "per_hour": 12.5},
    "no_chatter": {"signal": "PUMP", "min_toggles": 4, "window": 20},
    "min_dwell": {"signal": "PUMP", "on": 2.5, "off": 3},
    "max_on": {"signal": "HEATER", "max": 30},
    "blink_frequency": {"signal": "LAMP", "hz": 2.5, "tol": 0.1},
    "event_count": {"event": "X1", "min": 2, "max": 5},
    "counter": {"signal": "GOOD", "event": "X1"},
    "event_data": {"event": "X1", "field": "ML", "lo": 95, "hi": 105.5},
}


def english_words(text: str) -> list[str]:
    return english_runs(text, min_words=1)


@pytest.mark.parametrize("check", sorted(CHECKS))
def test_every_limit_is_worded_in_russian(russian, check):
    text = describe_limits(limits_of(check, CHECKS[check]))
    assert text and not english_words(text), (check, text)
    prose = text
    for key in ("condition", "if", "then", "trigger", "response", "restart"):
        prose = prose.replace(str(CHECKS[check].get(key, "\0")), "ST")  # ST keeps its point
    assert not re.search(r"\d\.\d", prose), text  # numbers in prose take the decimal comma


def test_the_english_labels_are_unchanged_and_the_check_sees_english():
    text = describe_limits(limits_of("no_chatter", CHECKS["no_chatter"]))
    assert text == "PUMP fewer than 4 switchings in 20 s"
    assert english_words(text)  # the test above would see a label left in English


def test_a_label_missing_from_the_catalogue_is_found(russian, ru_ui):
    ru_ui({"fewer than {n} switchings in {s:num} s": None})
    assert english_words(describe_limits(limits_of("no_chatter", CHECKS["no_chatter"])))
