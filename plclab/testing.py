"""Unit tests written in ST: ``TEST 'name' ... END_TEST`` blocks.

Each TEST runs in a fresh PLC (all variables at their initial values, clock at zero). Time is
frozen inside a test until ``ADVANCE_TIME(t)``; assertions stop the test at the first failure.
"""

from __future__ import annotations

from dataclasses import dataclass

from .errors import Diagnostic, Location, PlcError, printable
from .project import compile_sources, read_sources


@dataclass
class TestResult:
    title: str
    location: Location
    passed: bool
    message: str = ""
    failure_location: Location | None = None
    code: str = ""
    assert_text: str = ""  # the ASSERT's text when ``message`` ends with " (in <it>)"

    def __str__(self) -> str:
        if self.passed:
            return f"PASS {printable(self.title)}"
        where = self.failure_location or self.location
        return f"{where}: FAIL {printable(self.title)}: {printable(self.message)}"

    def render(self) -> str:
        """The line in the language chosen (:mod:`plclab.i18n`); ``str()`` stays English."""
        from .i18n import SOURCE, language, message, tr

        if language() == SOURCE:
            return str(self)
        if self.passed:
            return tr("PASS {title}", title=printable(self.title))
        where = self.failure_location or self.location
        msg = self.message
        suffix = f" (in {self.assert_text})" if self.assert_text else ""
        if suffix and msg.endswith(suffix):
            msg = msg[: -len(suffix)]
        text = message(self.code, msg) if self.code else msg
        if suffix:
            text += tr(" (in {text})", text=self.assert_text)
        return tr("{where}: FAIL {title}: {message}", where=where, title=printable(self.title),
                  message=printable(text))


def run_compiled_tests(compiled) -> list[TestResult]:
    from .runtime.plc import Plc

    results = []
    for title, fn, loc in compiled.tests:
        plc = Plc(compiled)
        plc.ctx.first_scan = True
        try:
            plc.ns[fn]()
        except BaseException as exc:  # noqa: BLE001
            err = plc._translate(exc)
            where = err.location
            msg = err.message
            text = None
            from .runtime.rt import AssertFailure

            if isinstance(exc, AssertFailure):
                text = compiled.assert_texts.get(exc.where)
            if text:
                msg = f"{msg} (in {text})"
            results.append(TestResult(title, loc, False, msg, where, err.code, text or ""))
            continue
        results.append(TestResult(title, loc, True))
    return results


def run_test_files(paths: list[str]) -> list[TestResult]:
    compiled = compile_sources(read_sources(paths))
    return run_compiled_tests(compiled)


def run_test_sources(sources: list[tuple[str, str]]) -> list[TestResult]:
    return run_compiled_tests(compile_sources(sources))


__all__ = ["TestResult", "run_test_files", "run_test_sources", "run_compiled_tests",
           "Diagnostic", "PlcError"]
