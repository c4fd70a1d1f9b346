"""Who may connect and what a client may write: the access rules of ``plclab opcua``.

Secure by default (ADR 0055): the server listens on 127.0.0.1, anonymous clients may read
but not write, and no variable is writable until a rule names it. A configuration file
(TOML) or the command line opens it up::

    host = "127.0.0.1"          # a non-loopback address also needs --allow-remote
    port = 4840
    anonymous = "read"          # read (default) | write | none (users only)
    writable = ["Main.SetPoint", "Main.Start*"]   # variables (patterns) a client may write

    [[user]]
    name = "operator"
    password_sha256 = "5e884898da28047151d0e56f8dc6292773603d0d6aabbdd62a11ef721d1542d8"
    role = "write"              # write (default): write the writable variables, acknowledge
                                # alarms; read: only read

Errors are PlcError PLC7053 (a rule that names nothing or a variable a client must not
write) and PLC7054 (the file itself).
"""

from __future__ import annotations

import fnmatch
import hashlib
import hmac
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

ROLES = ("read", "write")
ANONYMOUS = ("read", "write", "none")
PASSWORD_ENV = "PLCLAB_OPCUA_PASSWORD"
_KEYS = {"host", "port", "anonymous", "writable", "user"}
_USER_KEYS = {"name", "password", "password_sha256", "role"}


@dataclass
class User:
    name: str
    sha256: str  # hex digest of the password
    role: str = "write"

    def check(self, password: str | None) -> bool:
        digest = hashlib.sha256((password or "").encode()).hexdigest()
        return hmac.compare_digest(digest, self.sha256)


@dataclass
class Access:
    """The access rules: anonymous role, users, writable variable patterns."""

    anonymous: str = "read"
    users: dict[str, User] = field(default_factory=dict)
    writable: list[str] = field(default_factory=list)
    host: str | None = None
    port: int | None = None
    source: str = "the command line"

    def role(self, user_name: str | None) -> str:
        """``read``/``write`` of a session's user (None: anonymous)."""
        if user_name is None:
            return self.anonymous
        u = self.users.get(user_name)
        return u.role if u is not None else "none"

    def login(self, name: str | None, password: str | None) -> str | None:
        """The user name of a good login (None for anonymous); raises KeyError when refused."""
        if name is None:
            if self.anonymous == "none":
                raise KeyError("anonymous")
            return None
        u = self.users.get(name)
        if u is None or not u.check(password):
            raise KeyError(name)
        return name

    def add_user(self, name: str, password: str | None = None, *, sha256: str | None = None,
                 role: str = "write", where: str = "--user") -> None:
        if not name or not name.replace("_", "").replace("-", "").isalnum():
            raise PlcError("PLC7054", f"{where}: user name {name!r}: use letters, digits, - "
                           "and _ (e.g. operator)")
        if role not in ROLES:
            raise PlcError("PLC7054", f"{where}: user {name}: role {role!r} is not one of "
                           f"{', '.join(ROLES)}")
        if name in self.users:
            raise PlcError("PLC7054", f"{where}: user {name} is defined twice")
        if sha256 is None:
            if not password:
                raise PlcError("PLC7054", f"{where}: user {name} needs a password (password or "
                               "password_sha256 in the file; the environment variable "
                               f"{PASSWORD_ENV} for --user)")
            sha256 = hashlib.sha256(password.encode()).hexdigest()
        elif len(sha256) != 64 or any(c not in "0123456789abcdef" for c in sha256.lower()):
            raise PlcError("PLC7054", f"{where}: user {name}: password_sha256 is 64 hex digits "
                           "(python -c \"import hashlib; print(hashlib.sha256(b'PASSWORD')"
                           ".hexdigest())\")")
        self.users[name] = User(name, sha256.lower(), role)

    def matches(self, path: str) -> bool:
        """Whether a rule names the tag ``path`` (patterns as in a shell, case-insensitive)."""
        return any(self.matches_one(rule, path) for rule in self.writable)

    @staticmethod
    def matches_one(rule: str, path: str) -> bool:
        return fnmatch.fnmatchcase(path.upper(), rule.upper())


def load_access(path: str | None = None, *, writable: list[str] | None = None,
                anonymous: str | None = None, user: str | None = None) -> Access:
    """The rules of a config file (optional) with the command line's on top."""
    acc = Access()
    if path is not None:
        acc = _from_file(Path(path))
    for w in writable or []:
        _check_pattern(w, "--writable")
        acc.writable.append(w.strip())
    if anonymous is not None:
        if anonymous not in ANONYMOUS:
            raise PlcError("PLC7054", f"--anonymous {anonymous}: give one of "
                           f"{', '.join(ANONYMOUS)}")
        acc.anonymous = anonymous
    if user is not None:
        acc.add_user(user, os.environ.get(PASSWORD_ENV), where="--user")
    return acc


def _check_pattern(rule: Any, where: str) -> None:
    if not isinstance(rule, str) or not rule.strip():
        raise PlcError("PLC7053", f"{where}: {rule!r} is not a variable name or pattern; write "
                       "e.g. Main.SetPoint or \"Main.SP_*\"")


def _from_file(path: Path) -> Access:
    where = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise PlcError("PLC7054", f"cannot read the OPC UA configuration {where}: "
                       f"{exc.strerror or exc}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise PlcError("PLC7054", f"{where} is not valid TOML: {exc}") from None
    bad = set(data) - _KEYS
    if bad:
        raise PlcError("PLC7054", f"{where}: unknown key(s) {', '.join(sorted(bad))}; the file "
                       f"has {', '.join(sorted(_KEYS))}")
    acc = Access(source=where)
    anon = data.get("anonymous", "read")
    if anon not in ANONYMOUS:
        raise PlcError("PLC7054", f"{where}: anonymous = {anon!r}: give one of "
                       f"{', '.join(ANONYMOUS)}")
    acc.anonymous = anon
    host = data.get("host")
    if host is not None and not isinstance(host, str):
        raise PlcError("PLC7054", f"{where}: host is an address such as \"127.0.0.1\"")
    acc.host = host
    port = data.get("port")
    if port is not None and (isinstance(port, bool) or not isinstance(port, int)):
        raise PlcError("PLC7054", f"{where}: port is a whole number (4840)")
    acc.port = port
    rules = data.get("writable", [])
    if not isinstance(rules, list):
        raise PlcError("PLC7053", f"{where}: writable is a list of variables, e.g. writable = "
                       "[\"Main.SetPoint\"]")
    for r in rules:
        _check_pattern(r, f"{where}: writable")
        acc.writable.append(r.strip())
    users = data.get("user", [])
    if not isinstance(users, list):
        raise PlcError("PLC7054", f"{where}: write each user as a [[user]] table")
    for i, row in enumerate(users, 1):
        if not isinstance(row, dict) or not isinstance(row.get("name"), str):
            raise PlcError("PLC7054", f"{where}: [[user]] {i} needs a name")
        extra = set(row) - _USER_KEYS
        if extra:
            raise PlcError("PLC7054", f"{where}: user {row['name']}: unknown key(s) "
                           f"{', '.join(sorted(extra))}; a user has "
                           f"{', '.join(sorted(_USER_KEYS))}")
        pw, digest = row.get("password"), row.get("password_sha256")
        if pw is not None and not isinstance(pw, str) or \
                digest is not None and not isinstance(digest, str):
            raise PlcError("PLC7054", f"{where}: user {row['name']}: a password is a string")
        acc.add_user(row["name"], pw, sha256=digest, role=row.get("role", "write"),
                     where=where)
    return acc
