"""What Russian messages cost (ADR 0063): printing a diagnostic in English and in Russian, the
first Russian text (the catalogues are read then), and ``plclab check`` of a file with errors
in both languages as a student runs it (a new process each time).

Run ``python benchmarks/i18n_bench.py``; numbers are printed side by side, medians of a few runs.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from plclab import i18n  # noqa: E402
from plclab.errors import Diagnostic, Location  # noqa: E402

MESSAGES = [
    ("PLC0100", "countr is not declared; did you mean COUNTER?"),
    ("PLC0113", "do not assign the FOR variable I inside the loop; use a WHILE loop or EXIT "
                "instead"),
    ("PLC0118", "cannot assign DINT to INT without a conversion; convert explicitly with "
                "DINT_TO_INT(...)"),
    ("PLC0190", "a message no template matches, shown after the Russian title"),
]
BAD = """PROGRAM Main
VAR i : INT; total : INT; b : BOOL; END_VAR
FOR i := 1 TO 10 DO i := i + 1; END_FOR;
totl := 1;
b := i;
IF i THEN b := TRUE; END_IF;
END_PROGRAM
"""


def per_render(lang: str, n: int = 20000) -> float:
    i18n.set_language(lang)
    diags = [Diagnostic(c, m, Location("main.st", 3, 5)) for c, m in MESSAGES]
    for d in diags:  # the catalogues are read on the first one
        d.render()
    t0 = time.perf_counter()
    for k in range(n):
        diags[k % len(diags)].render()
    return (time.perf_counter() - t0) / n * 1e6


def first_text() -> float:
    code = ("import time, plclab.i18n as i; i.set_language('ru'); t = time.perf_counter(); "
            "i.problem_text('PLC0100', 'title', 'x'); i.tr('error'); "
            "print((time.perf_counter() - t) * 1000)")
    runs = [float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                 cwd=ROOT, check=True).stdout) for _ in range(5)]
    return statistics.median(runs)


def check_time(lang: str, path: Path) -> float:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PLCLAB_LANG": lang}
    runs = []
    for _ in range(5):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "plclab", "check", str(path)], env=env,
                       capture_output=True, text=True)
        runs.append(time.perf_counter() - t0)
    return statistics.median(runs) * 1000


def main() -> None:
    en, ru = per_render("en"), per_render("ru")
    i18n.set_language(None)
    print(f"render one diagnostic:      en {en:7.1f} us   ru {ru:7.1f} us")
    print(f"first Russian text (reads problems.toml and ui.toml): {first_text():.1f} ms")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "main.st"
        path.write_text(BAD, encoding="utf-8")
        print(f"plclab check (4 errors):    en {check_time('en', path):7.0f} ms   "
              f"ru {check_time('ru', path):7.0f} ms")


if __name__ == "__main__":
    main()
