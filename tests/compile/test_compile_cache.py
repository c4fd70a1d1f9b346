"""The compile cache (ADR 0057): keys, invalidation, safety of disk entries, atomic writes, and
``plclab check`` answered from it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from plclab.cli import cached_check, main
from plclab.compile import cache

SRC = "PROGRAM P\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n"  # one error: y is not declared
OK = "PROGRAM P\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"


@pytest.fixture
def cache_folder(tmp_path, monkeypatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv("PLCLAB_CACHE_DIR", str(folder))
    monkeypatch.delenv("PLCLAB_NO_CACHE", raising=False)
    return folder


def entries(folder: Path) -> list[Path]:
    return sorted(folder.rglob("*.json")) if folder.exists() else []


# -- keys ----------------------------------------------------------------------------------


def test_key_changes_with_everything_that_changes_the_result():
    base = cache.key("check", [(SRC, "a.st")], None, {"lint": True}, version="1")
    assert base == cache.key("check", [(SRC, "a.st")], None, {"lint": True}, version="1")
    others = [
        cache.key("check", [(SRC + " ", "a.st")], None, {"lint": True}, version="1"),  # text
        cache.key("check", [(SRC, "b.st")], None, {"lint": True}, version="1"),  # file name
        cache.key("check", [(SRC, "a.st")], "iec", {"lint": True}, version="1"),  # dialect
        cache.key("check", [(SRC, "a.st")], None, {"lint": False}, version="1"),  # option
        cache.key("check", [(SRC, "a.st")], None, {"lint": True}, version="2"),  # plclab
        cache.key("python", [(SRC, "a.st")], None, {"lint": True}, version="1"),  # kind
    ]
    assert len({base, *others}) == len(others) + 1


def test_the_cache_hashes_as_hashlib_does():
    import hashlib

    for data in (b"", b"abc", "Kühler ∑".encode() * 1000):
        assert cache._sha256(data).hexdigest() == hashlib.sha256(data).hexdigest()


def test_key_does_not_confuse_where_one_file_ends():
    one = cache.key("check", [("ab", "x.st"), ("c", "y.st")], version="1")
    two = cache.key("check", [("a", "x.st"), ("bc", "y.st")], version="1")
    assert one != two


def test_key_follows_plclabs_version_and_its_compiler_files(monkeypatch, tmp_path):
    import plclab

    first = cache.key("check", [(SRC, "a.st")])
    monkeypatch.setattr(plclab, "__version__", plclab.__version__ + ".post1")
    monkeypatch.setattr(cache, "_fingerprint", None)
    assert cache.key("check", [(SRC, "a.st")]) != first
    # an edited compiler file (a developer's checkout keeps its version) is a new key too
    monkeypatch.setattr(plclab, "__version__", plclab.__version__[:-len(".post1")])
    monkeypatch.setattr(cache, "_fingerprint", None)
    assert cache.key("check", [(SRC, "a.st")]) == first
    fake = tmp_path / "plclab"
    for part in ("lang", "compile", "runtime"):
        (fake / part).mkdir(parents=True)
    (fake / "lang" / "lexer.py").write_text("x = 1\n")
    monkeypatch.setattr(cache, "_PACKAGE", fake)
    monkeypatch.setattr(cache, "_fingerprint", None)
    one = cache.compiler_fingerprint()
    (fake / "lang" / "lexer.py").write_text("x = 22\n")
    monkeypatch.setattr(cache, "_fingerprint", None)
    two = cache.compiler_fingerprint()
    assert two != one
    (fake / "suggest.py").write_text("hint = 1\n")  # a top-level module the checker uses
    monkeypatch.setattr(cache, "_fingerprint", None)
    three = cache.compiler_fingerprint()
    assert three != two
    (fake / "runtime" / "plc.py").write_text("x = 1\n")  # the runtime's Python: no change
    (fake / "lang" / "notes.txt").write_text("x")
    monkeypatch.setattr(cache, "_fingerprint", None)
    assert cache.compiler_fingerprint() == three


def test_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("PLCLAB_CACHE_DIR", str(tmp_path / "own"))
    assert cache.cache_dir() == tmp_path / "own"
    if sys.platform.startswith("linux"):
        monkeypatch.delenv("PLCLAB_CACHE_DIR")
        monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
        assert cache.cache_dir() == tmp_path / "xdg" / "plclab"
        monkeypatch.setenv("XDG_CACHE_HOME", "relative/not/allowed")  # the spec: ignore it
        assert cache.cache_dir() == Path.home() / ".cache" / "plclab"


# -- the disk store ------------------------------------------------------------------------


def test_store_and_load_round_trip(cache_folder):
    k = cache.key("check", [(SRC, "a.st")], version="t")
    assert cache.load_entry(k) is None
    assert cache.store_entry(k, [["PLC0100", "y", "error", "a.st", 3, 6]])
    assert cache.load_entry(k) == [["PLC0100", "y", "error", "a.st", 3, 6]]
    assert [p.name for p in entries(cache_folder)] == [f"{k}.json"]
    assert not [p for p in cache_folder.rglob("*") if p.name.endswith(".tmp")]


def test_no_cache_variable_turns_the_disk_cache_off(cache_folder, monkeypatch):
    k = cache.key("check", [(SRC, "a.st")], version="t")
    monkeypatch.setenv("PLCLAB_NO_CACHE", "1")
    assert not cache.store_entry(k, [1])
    assert cache.load_entry(k) is None
    assert entries(cache_folder) == []
    monkeypatch.setenv("PLCLAB_NO_CACHE", "0")
    assert cache.store_entry(k, [1]) and cache.load_entry(k) == [1]


@pytest.mark.parametrize("spoil", [
    lambda raw: raw[: len(raw) // 2],                                  # truncated
    lambda raw: b"\x00\xff" + raw,                                     # garbage
    lambda raw: raw.replace(b'"payload"', b'"pay"'),                   # a field missing
    lambda raw: raw.replace(b"PLC0100", b"PLC0101"),                   # payload changed
    lambda raw: b"[]",                                                 # not an entry
    lambda raw: json.dumps({"format": 1, "key": "0" * 64, "sha256": "", "payload": "1"}
                           ).encode(),                                 # another key's entry
])
def test_a_spoiled_entry_is_a_miss_and_is_removed(cache_folder, spoil):
    k = cache.key("check", [(SRC, "a.st")], version="t")
    cache.store_entry(k, [["PLC0100", "y", "error", "a.st", 3, 6]])
    [path] = entries(cache_folder)
    path.write_bytes(spoil(path.read_bytes()))
    assert cache.load_entry(k) is None
    assert not path.exists()


def test_a_read_only_folder_is_not_an_error(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("PLCLAB_CACHE_DIR", str(blocker / "cache"))
    k = cache.key("check", [(SRC, "a.st")], version="t")
    assert cache.store_entry(k, [1]) is False
    assert cache.load_entry(k) is None


def test_concurrent_writers_and_readers_see_whole_entries(cache_folder):
    k = cache.key("check", [(SRC, "a.st")], version="t")
    big = [["PLC0100", "m" * 2000, "error", "a.st", i, 1] for i in range(300)]
    seen: list[object] = []
    errors: list[BaseException] = []

    def write() -> None:
        try:
            for _ in range(20):
                assert cache.store_entry(k, big)
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    def read() -> None:
        for _ in range(60):
            v = cache.load_entry(k)
            if v is not None:
                seen.append(v)

    threads = [threading.Thread(target=write) for _ in range(3)] + [
        threading.Thread(target=read) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert all(v == big for v in seen)  # never half an entry
    assert cache.load_entry(k) == big
    assert not [p for p in cache_folder.rglob("*") if p.name.endswith(".tmp")]


def test_writers_in_separate_processes(cache_folder):
    code = ("import sys; from plclab.compile import cache\n"
            "k = sys.argv[1]\n"
            "for i in range(30):\n    assert cache.store_entry(k, list(range(2000)))\n")
    k = cache.key("check", [(SRC, "a.st")], version="t")
    env = dict(os.environ, PLCLAB_CACHE_DIR=str(cache_folder))
    procs = [subprocess.Popen([sys.executable, "-c", code, k], env=env) for _ in range(3)]
    assert [p.wait(timeout=120) for p in procs] == [0, 0, 0]
    assert cache.load_entry(k) == list(range(2000))


# -- the memory store ----------------------------------------------------------------------


def test_memory_cache_drops_the_least_recently_used():
    m = cache.MemoryCache(size=2)
    m.put("a", 1)
    m.put("b", 2)
    assert m.get("a") == 1  # a is now the most recent
    m.put("c", 3)
    assert m.get("b") is None and m.get("a") == 1 and m.get("c") == 3
    assert len(m) == 2 and m.hits == 3 and m.misses == 1


# -- plclab check -------------------------------------------------------------------------


def _check(path: Path, *extra: str, capsys) -> tuple[int, str]:
    rc = main(["check", *extra, str(path)])
    return rc, capsys.readouterr().out


def test_check_answers_from_the_cache_and_rechecks_an_edit(cache_folder, tmp_path, capsys,
                                                           monkeypatch):
    src = tmp_path / "p.st"
    src.write_text(SRC, encoding="utf-8")
    first = _check(src, capsys=capsys)
    assert first[0] == 1 and "PLC0100" in first[1]
    assert len(entries(cache_folder)) == 1
    import plclab.project as project

    calls: list[int] = []
    real = project.check_sources
    monkeypatch.setattr(project, "check_sources",
                        lambda *a, **k: calls.append(1) or real(*a, **k))
    assert _check(src, capsys=capsys) == first  # the same text: from the cache
    assert calls == []
    src.write_text(OK, encoding="utf-8")  # an edit: checked again
    rc, out = _check(src, capsys=capsys)
    assert (rc, calls) == (0, [1]) and "0 error(s)" in out
    assert _check(src, "--dialect", "iec", capsys=capsys)[0] == 0  # another dialect: again
    assert calls == [1, 1]
    assert _check(src, "--no-cache", capsys=capsys)[0] == 0  # --no-cache: again
    assert calls == [1, 1, 1]
    assert len(entries(cache_folder)) == 3


def test_check_ignores_a_planted_entry_of_the_wrong_shape(cache_folder, tmp_path, capsys):
    src = tmp_path / "p.st"
    src.write_text(SRC, encoding="utf-8")
    k = cache.key("check", [(SRC, str(src))], None, {"lint": True})
    # well formed as an entry (its own key and hash), but not diagnostics: checked again
    for planted in ([["PLC0100", ["not", "text"], "error", None, 0, 0]], {"a": 1},
                    [["PLC0100", "m", "fatal", None, 0, 0]], [["X", "m", "error", "f", "1", 0]]):
        assert cache.store_entry(k, planted)
        rc, out = _check(src, capsys=capsys)
        assert rc == 1 and "y is not declared" in out
        assert cache.load_entry(k) != planted  # replaced by the real diagnostics


def test_cached_check_gives_the_same_diagnostics_as_a_check(cache_folder):
    from plclab.project import check_sources

    sources = [("PROGRAM P\nVAR x : INT; u : INT; END_VAR\nx := y;\nEND_PROGRAM\n", "w.st")]
    fresh = check_sources(sources, None, lint=True)[1]
    assert cached_check(sources) == fresh  # a miss, stored
    assert cached_check(sources) == fresh  # a hit
    assert entries(cache_folder)


# -- compile_sources: the memory cache ------------------------------------------------------

TESTED = OK + "TEST 'one'\n  ASSERT_TRUE(TRUE);\nEND_TEST\nTEST 'two'\n  ASSERT_TRUE(TRUE);\nEND_TEST\n"


def test_compile_sources_compiles_the_same_text_once(monkeypatch):
    import plclab.compile.codegen as codegen
    from plclab.project import compile_sources
    from plclab.runtime.plc import Plc

    monkeypatch.delenv("PLCLAB_NO_CACHE", raising=False)
    calls: list[int] = []
    real = codegen.generate
    monkeypatch.setattr(codegen, "generate", lambda *a, **k: calls.append(1) or real(*a, **k))
    a = compile_sources([(OK, "p.st")])
    b = compile_sources([(OK, "p.st")])
    assert calls == [1]
    assert a is not b and a.code is b.code  # the code objects are shared, the object is not
    plc_a, plc_b = Plc(a), Plc(b)
    plc_a.scan(3)
    plc_b.scan(1)
    assert (plc_a["x"], plc_b["x"]) == (3, 1)  # two PLCs of one cached program: own memory
    compile_sources([(OK + "\n", "p.st")])  # another text
    compile_sources([(OK, "q.st")])  # another file name
    compile_sources([(OK, "p.st")], dialect="iec")  # another dialect
    compile_sources([(OK, "p.st")], cache=False)  # asked not to
    assert calls == [1] * 5
    monkeypatch.setenv("PLCLAB_NO_CACHE", "1")  # turned off
    compile_sources([(OK, "p.st")])
    assert calls == [1] * 6


def test_a_cached_compile_gives_each_caller_its_own_lists(monkeypatch):
    from plclab.project import compile_sources

    monkeypatch.delenv("PLCLAB_NO_CACHE", raising=False)

    first = compile_sources([(TESTED, "t.st")])
    assert [t[0] for t in first.tests] == ["one", "two"]
    first.tests = [t for t in first.tests if t[0] == "two"]  # what `plclab test -k` does
    first.tests.clear()
    again = compile_sources([(TESTED, "t.st")])
    assert [t[0] for t in again.tests] == ["one", "two"]


def test_compile_errors_are_not_cached_as_results():
    from plclab.errors import PlcError
    from plclab.project import compile_sources

    for _ in range(2):
        with pytest.raises(PlcError) as e:
            compile_sources([(SRC, "bad.st")])
        assert e.value.code == "PLC0100"
