"""asyncua's side of the access rules: the user manager and the permission ruleset."""

from __future__ import annotations

from typing import Any

from asyncua import ua
from asyncua.crypto.permission_rules import PermissionRuleset, User, UserRole

_NEEDS_WRITE = {ua.NodeId(ua.ObjectIds.WriteRequest_Encoding_DefaultBinary),
                ua.NodeId(ua.ObjectIds.CallRequest_Encoding_DefaultBinary)}
_ADMIN_ONLY = {ua.NodeId(i) for i in (
    ua.ObjectIds.AddNodesRequest_Encoding_DefaultBinary,
    ua.ObjectIds.DeleteNodesRequest_Encoding_DefaultBinary,
    ua.ObjectIds.AddReferencesRequest_Encoding_DefaultBinary,
    ua.ObjectIds.DeleteReferencesRequest_Encoding_DefaultBinary,
    ua.ObjectIds.RegisterServerRequest_Encoding_DefaultBinary,
    ua.ObjectIds.RegisterServer2Request_Encoding_DefaultBinary)}


class PlcUserManager:
    """Anonymous and user/password logins by the :class:`.access.Access` rules."""

    def __init__(self, access: Any) -> None:
        self.access = access

    def get_user(self, iserver: Any, username: str | None = None, password: str | None = None,
                 certificate: Any = None) -> User | None:
        # no X509 user tokens: the server offers no secured endpoint (ADR 0055)
        try:
            name = self.access.login(username or None, password)
        except KeyError:
            return None
        if name is None:
            return User(role=UserRole.Anonymous)
        return User(role=UserRole.User, name=name)


class PlcRuleset(PermissionRuleset):
    """Writes and method calls (acknowledging an alarm) need the ``write`` role; nobody
    changes the address space."""

    def __init__(self, access: Any) -> None:
        self.access = access

    def check_validity(self, user: Any, action_type_id: Any, body: Any) -> bool:
        if action_type_id in _ADMIN_ONLY:
            return False
        if action_type_id in _NEEDS_WRITE:
            name = None if user is None or user.role == UserRole.Anonymous else user.name
            return self.access.role(name) == "write"
        return True
