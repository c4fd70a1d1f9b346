"""The fuzzing harness: a worker process per campaign, mutators, a corpus, a minimiser.

``campaign(seed, cases)`` (deterministic for a seed and a number of cases) or
``campaign(seed, seconds=...)`` runs generated programs and mutated repository files through
:mod:`worker` and returns :class:`Stats`: cases per language, outcomes, failures by signature
(each with its smallest reproducer). Only ``crash`` (an exception that is not a ``PlcError``, or
the internal errors PLC9999 and PLC9990) and ``hang`` are failures.
"""

from __future__ import annotations

import json
import os
import random
import re
import select
import subprocess
import sys
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:  # gen.py sits next to this file (pytest imports by path)
    sys.path.insert(0, str(HERE))
import gen  # noqa: E402

ROOT = HERE.parents[1]
SOFT_TIMEOUT = 3.0  # CPU seconds per case before the worker's own alarm fires
HARD_MARGIN = 57.0  # more wall-clock seconds before the parent kills a worker that does not
# answer: generous, because a loaded machine may give the worker a fraction of a core (the
# soft alarm counts CPU time, so load alone never makes a hang; only this margin could)
LANGS = {".st": "st", ".il": "il", ".ld": "ld", ".xml": "xml"}


class Runner:
    """One worker process; restarted after it is killed for a hang or dies."""

    def __init__(self, soft_timeout: float = SOFT_TIMEOUT, hard_margin: float = HARD_MARGIN,
                 argv: list[str] | None = None) -> None:
        self.soft = soft_timeout
        self.hard = hard_margin
        self.argv = argv or [sys.executable, str(HERE / "worker.py")]
        self.proc: subprocess.Popen | None = None
        self.n = 0

    def _start(self) -> subprocess.Popen:
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
        env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(
            os.pathsep)
        return subprocess.Popen(self.argv, stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                                env=env, cwd=str(HERE))

    def run(self, text: str, name: str, seed: int = 0, scans: int = 3) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self.proc = self._start()
        self.n += 1
        job = {"id": self.n, "text": text, "name": name, "seed": seed, "scans": scans,
               "timeout": self.soft}
        assert self.proc.stdin and self.proc.stdout
        try:
            self.proc.stdin.write(json.dumps(job) + "\n")
            self.proc.stdin.flush()
        except BrokenPipeError:
            self.close()
            return {"outcome": "crash", "stage": "?", "sig": "crash:?:worker-died", "msg": ""}
        ready, _, _ = select.select([self.proc.stdout], [], [], self.soft + self.hard)
        line = self.proc.stdout.readline() if ready else ""
        if not line:
            died = self.proc.poll() is not None
            self.close()
            if died:
                return {"outcome": "crash", "stage": "?", "sig": "crash:?:worker-died",
                        "msg": "the worker process died (a fatal error or the memory limit)"}
            return {"outcome": "hang", "stage": "?", "sig": "hang:?:killed",
                    "msg": "no answer, even to the alarm: stuck in C code"}
        return json.loads(line)

    def close(self) -> None:
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait()
            self.proc = None

    def __enter__(self) -> Runner:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


# -- the corpus of repository files ------------------------------------------------------------
def seed_files() -> list[tuple[str, str]]:
    """(text, name) of every example, lab starter/solution/mistake and test source file."""
    pats = ["examples/*", "labs/*/starter.*", "labs/*/solution/*", "labs/*/mistakes/*",
            "tests/**/*.st", "tests/**/*.il", "tests/**/*.ld", "tests/**/*.xml"]
    seen: dict[Path, None] = {}
    for pat in pats:
        for p in sorted(ROOT.glob(pat)):
            if p.suffix in LANGS and p.is_file() and "fuzz" not in p.parts:
                seen[p] = None
    return [(p.read_text(encoding="utf-8"), p.name) for p in seen]


# -- mutators -----------------------------------------------------------------------------------
TOKEN = re.compile(r"\s+|[A-Za-z_][A-Za-z0-9_]*|\d[\w#.]*|:=|=>|\*\*|<=|>=|<>|\(\*|\*\)|.", re.S)
KEYWORDS = ["PROGRAM", "END_PROGRAM", "VAR", "VAR_GLOBAL", "VAR_INPUT", "VAR_OUTPUT",
            "VAR_IN_OUT", "VAR_TEMP", "VAR_EXTERNAL", "END_VAR", "CONSTANT", "RETAIN",
            "FUNCTION", "END_FUNCTION", "FUNCTION_BLOCK", "END_FUNCTION_BLOCK", "TYPE", "END_TYPE",
            "STRUCT", "END_STRUCT", "ARRAY", "OF", "IF", "THEN", "ELSIF", "ELSE", "END_IF", "CASE",
            "END_CASE", "FOR", "TO", "BY", "DO", "END_FOR", "WHILE", "END_WHILE", "REPEAT",
            "UNTIL", "END_REPEAT", "EXIT", "RETURN", "CONTINUE", "TEST", "END_TEST", "AT",
            "CONFIGURATION", "END_CONFIGURATION", "RESOURCE", "END_RESOURCE", "TASK", "WITH",
            "ON", "INTERVAL", "PRIORITY", "AND", "OR", "XOR", "NOT", "MOD", "TRUE", "FALSE",
            "LD", "LDN", "ST", "STN", "S", "R", "JMP", "JMPC", "JMPCN", "CAL", "CALC", "RET",
            "AND(", ")", "INT", "DINT", "LINT", "SINT", "REAL", "LREAL", "BOOL", "TIME", "WORD",
            "STRING", "TON", "CTU", "T#1s", "16#FFFF", "1.0E400", "99999999999999999999",
            "[ ]", "(S)", "+", "|", "---", "<![CDATA[", "]]>", "</pou>", "<variable name=\"z\">",
            "&amp;", "&#0;", "(*", "*)", "{", "}", "'", "$", "\"", ";", ":", "..", "%IX0.0",
            "%QW99999", "%MD4", "T#0s", "-", "**", "=>", ",", "[", "]",
            # SFC, textual and PLCopen
            "INITIAL_STEP", "STEP", "END_STEP", "TRANSITION", "FROM", "END_TRANSITION",
            "ACTION", "END_ACTION", "(N)", "(L, T#1s)", "<step localId=\"1\" name=\"S\"/>",
            "<jumpStep localId=\"7\" targetName=\"S\"/>", "refLocalId=\"1\"",
            "</SFC>", "<macroStep localId=\"9\" name=\"M\">"]


def _tokens(text: str) -> list[str]:
    return TOKEN.findall(text)


def mutate(text: str, rng: random.Random) -> str:
    """One to four random edits: byte flips, token deletion/duplication/swap, truncation,
    section moves (lines), keyword swaps and insertions of dangerous pieces."""
    for _ in range(rng.randint(1, 4)):
        if not text:
            text = rng.choice(KEYWORDS)
        op = rng.randrange(9)
        if op == 0:  # byte flip
            b = bytearray(text.encode("utf-8", "surrogatepass"))
            i = rng.randrange(len(b))
            b[i] ^= 1 << rng.randrange(8)
            text = b.decode("utf-8", "replace")
        elif op in (1, 2, 3, 4):
            toks = _tokens(text)
            significant = [i for i, t in enumerate(toks) if not t.isspace()] or [0]
            i = rng.choice(significant)
            if op == 1:
                del toks[i]
            elif op == 2:
                toks.insert(i, toks[i])
            elif op == 3:
                j = rng.choice(significant)
                toks[i], toks[j] = toks[j], toks[i]
            else:
                toks[i] = rng.choice(KEYWORDS)
            text = "".join(toks)
        elif op == 5:  # truncation
            text = text[:rng.randrange(len(text) + 1)]
        elif op == 6:  # section move: a block of lines elsewhere
            lines = text.splitlines(keepends=True)
            if len(lines) > 2:
                i = rng.randrange(len(lines))
                j = min(len(lines), i + rng.randint(1, 8))
                block, rest = lines[i:j], lines[:i] + lines[j:]
                k = rng.randrange(len(rest) + 1)
                text = "".join(rest[:k] + block + rest[k:])
        elif op == 7:  # insert a piece at a random place
            i = rng.randrange(len(text) + 1)
            text = text[:i] + rng.choice(KEYWORDS) + " " + text[i:]
        else:  # duplicate a section
            i = rng.randrange(len(text))
            j = min(len(text), i + rng.randint(1, 200))
            k = rng.randrange(len(text) + 1)
            text = text[:k] + text[i:j] + text[k:]
    return text


def same_failure(a: str | None, b: str) -> bool:
    """Crashes match exactly; a hang matches any hang in the same stage (the alarm can stop
    a loop in any of its frames)."""
    if a is None:
        return False
    if b.startswith("hang:"):
        return a.split(":")[:2] == b.split(":")[:2]
    return a == b


# -- the minimiser ------------------------------------------------------------------------------
def _ddmin(items: list[str], still_fails, budget: list[int]) -> list[str]:
    """Zeller's delta debugging over a list of pieces (lines, tokens or characters)."""
    n = 2
    while len(items) >= 2 and budget[0] > 0:
        chunk = max(1, len(items) // n)
        reduced = False
        for start in range(0, len(items), chunk):
            candidate = items[:start] + items[start + chunk:]
            budget[0] -= 1
            if candidate and still_fails(candidate):
                items, n, reduced = candidate, max(n - 1, 2), True
                break
            if budget[0] <= 0:
                return items
        if not reduced:
            if n >= len(items):
                break
            n = min(len(items), n * 2)
    return items


def minimise(text: str, name: str, sig: str, runner: Runner, budget: int = 300,
             seed: int = 0) -> str:
    """The smallest text (by lines, then tokens, then characters) that fails with ``sig``."""
    left = [budget]

    def fails(pieces: list[str]) -> bool:
        return same_failure(runner.run("".join(pieces), name, seed=seed).get("sig"), sig)

    lines = _ddmin(text.splitlines(keepends=True), fails, left)
    toks = _ddmin(_tokens("".join(lines)), fails, left)
    chars = _ddmin(list("".join(toks)), fails, left) if len("".join(toks)) < 400 else toks
    return "".join(chars)


# -- a campaign ---------------------------------------------------------------------------------
@dataclass
class Failure:
    sig: str
    name: str
    text: str
    msg: str
    seed: int = 0
    count: int = 1
    minimal: str | None = None


@dataclass
class Stats:
    cases: Counter = field(default_factory=Counter)  # (language, "gen"/"mut") -> n
    outcomes: Counter = field(default_factory=Counter)  # (language, outcome) -> n
    failures: dict[str, Failure] = field(default_factory=dict)
    seconds: float = 0.0

    def add(self, lang: str, kind: str, text: str, name: str, res: dict, seed: int = 0) -> None:
        self.cases[(lang, kind)] += 1
        self.outcomes[(lang, res["outcome"])] += 1
        if res["outcome"] in ("crash", "hang"):
            f = self.failures.get(res["sig"])
            if f is None:
                self.failures[res["sig"]] = Failure(res["sig"], name, text, res.get("msg", ""),
                                                    seed)
            else:
                f.count += 1
                if len(text) < len(f.text):
                    f.text, f.name, f.seed = text, name, seed

    def report(self) -> str:
        out = [f"fuzz: {sum(self.cases.values())} cases in {self.seconds:.0f} s"]
        for lang in sorted({k[0] for k in self.cases}):
            kinds = ", ".join(f"{k} {self.cases[(lang, k)]}" for k in ("gen", "mut"))
            outs = ", ".join(f"{o} {n}" for (lg, o), n in sorted(self.outcomes.items())
                             if lg == lang)
            out.append(f"  {lang:4} {kinds}: {outs}")
        for f in sorted(self.failures.values(), key=lambda f: -f.count):
            out.append(f"  FAIL x{f.count} {f.sig} ({f.name}) {f.msg[:160]}")
            shown = f.minimal if f.minimal is not None else f.text[:600]
            out.append("    reproducer: " + repr(shown))
        return "\n".join(out)


def cases(seed: int):
    """An endless, deterministic stream of (language, kind, text, filename, case seed)."""
    rng = random.Random(seed)
    corpus = seed_files()
    langs = list(gen.GENERATORS)
    i = 0
    while True:
        i += 1
        case_seed = rng.getrandbits(32)
        crng = random.Random(case_seed)
        if i % 2:
            lang = langs[(i // 2) % len(langs)]
            text, name = gen.GENERATORS[lang](crng)
            if crng.random() < 0.25:  # a generated program, mutated a little
                yield lang, "mut", mutate(text, crng), name, case_seed
            else:
                yield lang, "gen", text, name, case_seed
        else:
            text, name = corpus[crng.randrange(len(corpus))]
            yield LANGS[Path(name).suffix], "mut", mutate(text, crng), name, case_seed


def campaign(seed: int, n_cases: int | None = None, seconds: float | None = None,
             minimise_budget: int = 300, progress=None, skip=lambda sig: False) -> Stats:
    """Run cases until ``n_cases`` or ``seconds``; minimise each failure signature for which
    ``skip(sig)`` is false (known issues already have their reproducer)."""
    stats = Stats()
    t0 = time.monotonic()
    with Runner() as runner:
        for n, (lang, kind, text, name, cseed) in enumerate(cases(seed)):
            if n_cases is not None and n >= n_cases:
                break
            if seconds is not None and time.monotonic() - t0 > seconds:
                break
            res = runner.run(text, name, seed=cseed)
            stats.add(lang, kind, text, name, res, cseed)
            if progress is not None and n % 500 == 0:
                progress(stats)
        if minimise_budget:
            with Runner(soft_timeout=1.0) as mini:
                for f in stats.failures.values():
                    if not skip(f.sig):
                        f.minimal = minimise(f.text, f.name, _resig(mini, f), mini,
                                             minimise_budget, f.seed)
    stats.seconds = time.monotonic() - t0
    return stats


def _resig(runner: Runner, f: Failure) -> str:
    """The signature under the minimiser's shorter timeout (a hang is found at another frame)."""
    return runner.run(f.text, f.name, seed=f.seed).get("sig") or f.sig
