"""The compile cache: what a check or a compile made of some source text, found again by a hash
(ADR 0057).

A key is the SHA-256 of everything that changes the result: the kind of result (``check``,
``python``...), plclab's version and a fingerprint of its compiler's own files (size and
modification time of every ``.py`` and ``.st`` file of :mod:`plclab.lang`,
:mod:`plclab.compile`, the block library and the top-level modules of :mod:`plclab` such as
``errors.py``, ``suggest.py`` and ``problems.toml``, so a developer's edit of the compiler is a
new key even when the version is not), the dialect, the options, and each file's name and text.

Two stores share the keys:

* :class:`MemoryCache`, a small LRU of Python objects for long-lived processes (the language
  server, the grader, the playground). Nothing in it ever left the process.
* the disk cache, one JSON file per entry in the user's cache folder (:func:`cache_dir`):
  ``$PLCLAB_CACHE_DIR``, else ``$XDG_CACHE_HOME/plclab``, else ``~/.cache/plclab`` (Windows:
  ``%LOCALAPPDATA%\\plclab\\Cache``; macOS: ``~/Library/Caches/plclab``). ``PLCLAB_NO_CACHE=1``
  (or a command's ``--no-cache``) turns it off. An entry is **data only**: JSON text (a list of
  diagnostics, generated Python *text* that is printed, never executed) that is read back with
  :func:`json.loads` and checked: its own key must be the key asked for and the SHA-256 of its
  payload must match, else it is a miss (and removed). It is never unpickled, unmarshalled or
  executed, so a planted or corrupted entry can at worst show wrong diagnostics, never run
  Python. Entries are written to a temporary file in the same folder and renamed into place
  (:func:`os.replace`, atomic), so concurrent writers and readers never see half an entry.

Importing this module imports only the standard library (json, os, CPython's SHA-256).
"""

from __future__ import annotations

import json
import os
import sys
from collections import OrderedDict
from collections.abc import Iterable
from pathlib import Path
from typing import Any

__all__ = ["FORMAT", "MemoryCache", "cache_dir", "compiler_fingerprint", "disabled", "key",
           "load_entry", "store_entry"]

FORMAT = 1
"""The layout of a disk entry; part of every key, so a new layout never reads an old one."""

MAX_ENTRY_BYTES = 64 * 1024 * 1024
"""A disk entry larger than this is not read (a 50,000-line program's generated Python is
about 6 MB)."""

def _builtin_sha256() -> Any:
    """CPython's own SHA-256 (``_sha2`` from 3.12, ``_sha256`` before): the same digests as
    hashlib's without loading OpenSSL (5 ms of a cache hit's start-up); hashlib's elsewhere."""
    import importlib

    for name in ("_sha2", "_sha256"):
        try:
            return importlib.import_module(name).sha256
        except (ImportError, AttributeError):
            continue
    from hashlib import sha256

    return sha256


_sha256 = _builtin_sha256()

_PACKAGE = Path(__file__).resolve().parent.parent
_COMPILER_PARTS = ("lang", "compile", "runtime")


def disabled() -> bool:
    """The disk cache is off: ``PLCLAB_NO_CACHE`` is set to anything but ``""`` or ``0``."""
    return os.environ.get("PLCLAB_NO_CACHE", "") not in ("", "0")


def cache_dir() -> Path:
    """The folder of the disk cache (not created here); see the module's docstring."""
    own = os.environ.get("PLCLAB_CACHE_DIR")
    if own:
        return Path(own)
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA") or str(Path.home() / "AppData" / "Local")
        return Path(base) / "plclab" / "Cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "plclab"
    xdg = os.environ.get("XDG_CACHE_HOME")
    return Path(xdg if xdg and os.path.isabs(xdg) else Path.home() / ".cache") / "plclab"


_fingerprint: str | None = None


def compiler_fingerprint() -> str:
    """plclab's version and the size and modification time of each file of the compiler (the
    ``.py`` files of lang and compile, the library's ``.st`` files, plclab's top-level modules
    and catalogue); computed once a process."""
    global _fingerprint
    if _fingerprint is None:
        version = sys.modules["plclab"].__version__  # the package is imported before this module
        h = _sha256(f"plclab {version} format {FORMAT}".encode())
        for entry in sorted(os.scandir(_PACKAGE), key=lambda e: e.name):
            if entry.name.endswith((".py", ".toml")) and entry.is_file():  # errors, suggest,
                st = entry.stat()  # durations, project... and the problem catalogue
                h.update(f"/{entry.name} {st.st_size} {st.st_mtime_ns}\n".encode())
        for part in _COMPILER_PARTS:
            for root, dirs, files in os.walk(_PACKAGE / part):
                dirs[:] = sorted(d for d in dirs if d != "__pycache__")
                for name in sorted(files):
                    if part == "runtime" and not name.endswith(".st"):
                        continue  # the runtime's Python does not change what is compiled
                    if name.endswith((".py", ".st")):
                        st = os.stat(os.path.join(root, name))
                        h.update(f"{root[len(str(_PACKAGE)):]}/{name} {st.st_size} "
                                 f"{st.st_mtime_ns}\n".encode())
        _fingerprint = h.hexdigest()
    return _fingerprint


def key(kind: str, sources: Iterable[tuple[str, str]], dialect: str | None = None,
        options: dict[str, Any] | None = None, *, version: str | None = None) -> str:
    """The key of ``kind`` made of (text, filename) ``sources`` in ``dialect`` with ``options``
    (JSON-able values); ``version`` replaces the compiler's fingerprint (for tests)."""
    h = _sha256()
    head = [FORMAT, kind, version if version is not None else compiler_fingerprint(),
            dialect, sorted((options or {}).items())]
    h.update(json.dumps(head, sort_keys=True, default=repr).encode())
    for text, filename in sources:
        for part in (filename, text):
            data = part.encode("utf-8", "surrogatepass")
            h.update(len(data).to_bytes(8, "little"))
            h.update(data)
    return h.hexdigest()


class MemoryCache:
    """At most ``size`` results by key, the least recently used dropped first."""

    def __init__(self, size: int = 32) -> None:
        self.size = size
        self._items: OrderedDict[str, Any] = OrderedDict()
        self.hits = self.misses = 0

    def get(self, k: str) -> Any:
        try:
            value = self._items[k]
        except KeyError:
            self.misses += 1
            return None
        self._items.move_to_end(k)
        self.hits += 1
        return value

    def put(self, k: str, value: Any) -> None:
        self._items[k] = value
        self._items.move_to_end(k)
        while len(self._items) > self.size:
            self._items.popitem(last=False)

    def __len__(self) -> int:
        return len(self._items)

    def clear(self) -> None:
        self._items.clear()


def _entry_path(k: str, folder: Path | None = None) -> Path:
    return (folder or cache_dir()) / k[:2] / f"{k}.json"


def load_entry(k: str, folder: Path | None = None) -> Any:
    """The payload stored under key ``k`` (a JSON value), or None: no entry, the cache is off,
    or the entry is not one this function wrote for ``k`` (then it is removed)."""
    if disabled():
        return None
    path = _entry_path(k, folder)
    try:
        if path.stat().st_size > MAX_ENTRY_BYTES:
            raise ValueError("too large")
        raw = path.read_bytes()
    except (OSError, ValueError):
        return None
    try:
        entry = json.loads(raw)
        payload = entry["payload"]
        ok = (isinstance(entry, dict) and entry.get("format") == FORMAT
              and entry.get("key") == k and isinstance(payload, str)
              and _sha256(payload.encode("utf-8", "surrogatepass")).hexdigest()
              == entry.get("sha256"))
        value = json.loads(payload) if ok else None
    except (ValueError, TypeError, KeyError, UnicodeError, RecursionError):
        ok, value = False, None
    if not ok:
        try:
            path.unlink()  # corrupted, truncated or planted: the next store replaces it
        except OSError:
            pass
        return None
    return value


def store_entry(k: str, value: Any, folder: Path | None = None) -> bool:
    """Store the JSON-able ``value`` under ``k``, atomically; False when it could not be
    written (the cache is off, the folder is read-only, the disk is full): never an error,
    a cache only saves time."""
    if disabled():
        return False
    path = _entry_path(k, folder)
    payload = json.dumps(value, ensure_ascii=False, separators=(",", ":"))
    data = json.dumps({"format": FORMAT, "key": k, "sha256": _sha256(
        payload.encode("utf-8", "surrogatepass")).hexdigest(), "payload": payload},
        ensure_ascii=True).encode("ascii")
    if len(data) > MAX_ENTRY_BYTES:
        return False
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        tmp = path.parent / f".{k}.{os.getpid()}.{id(data):x}.tmp"
        with open(tmp, "xb") as fh:
            fh.write(data)
        os.replace(tmp, path)  # atomic: a reader sees the old entry or the new one
        return True
    except OSError:
        if tmp is not None:
            try:
                tmp.unlink()
            except OSError:
                pass
        return False
