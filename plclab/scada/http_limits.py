"""Limits of plclab's small HTTP servers (the operator panel, ``plclab site serve``): a whole
request within a deadline and a bounded number of connections (ADR 0041).

The standard library's ``timeout`` bounds each read only: a client sending a byte now and
then holds a thread for ever, and ``ThreadingHTTPServer`` starts a thread for every
connection. :class:`DeadlineMixin` hangs up on a request that has not arrived (request line,
headers and, for a POST, the body the handler reads) ``request_deadline()`` seconds after it
began; :class:`BoundedHTTPServer` serves at most ``max_connections`` at once and closes any
further connection at once.
"""

from __future__ import annotations

import socket
import sys
import threading
from http.server import ThreadingHTTPServer
from typing import Any


class DeadlineMixin:
    """For a ``BaseHTTPRequestHandler``: the whole request within ``request_deadline()`` s.

    The deadline is lifted when the headers are parsed, except for a request with a body
    (POST, PUT): its handler calls :meth:`request_arrived` once it has read the body."""

    _deadline: threading.Timer | None = None

    def request_deadline(self) -> float:
        return float(getattr(self, "timeout", None) or 5.0)

    def handle_one_request(self) -> None:
        self._deadline = threading.Timer(self.request_deadline(), self._expire)
        self._deadline.daemon = True
        self._deadline.start()
        try:
            super().handle_one_request()  # type: ignore[misc]
        finally:
            self.request_arrived()

    def parse_request(self) -> bool:
        ok = super().parse_request()  # type: ignore[misc]
        if ok and self.command not in ("POST", "PUT"):  # type: ignore[attr-defined]
            self.request_arrived()
        return ok

    def request_arrived(self) -> None:
        if self._deadline is not None:
            self._deadline.cancel()

    def _expire(self) -> None:
        self.close_connection = True
        try:
            self.connection.shutdown(socket.SHUT_RDWR)  # type: ignore[attr-defined]
        except OSError:
            pass


class BoundedHTTPServer(ThreadingHTTPServer):
    """At most ``max_connections`` connections at once; quiet about clients that hang up."""

    daemon_threads = True
    max_connections = 32
    request_queue_size = 64  # the listen backlog: accept them all, then count

    def __init__(self, *args: Any, max_connections: int | None = None, **kwargs: Any) -> None:
        if max_connections is not None:
            self.max_connections = max_connections
        self._slots = threading.BoundedSemaphore(self.max_connections)
        super().__init__(*args, **kwargs)

    def process_request(self, request: Any, client_address: Any) -> None:
        if not self._slots.acquire(blocking=False):
            self.shutdown_request(request)
            return
        try:
            super().process_request(request, client_address)
        except BaseException:
            self._slots.release()
            raise

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self._slots.release()

    def handle_error(self, request: Any, client_address: Any) -> None:
        if not isinstance(sys.exc_info()[1], OSError):  # a hang-up is no news
            super().handle_error(request, client_address)
