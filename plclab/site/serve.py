"""Serve a built site on loopback, with the MIME types the playground needs (``.wasm`` as
``application/wasm``, so the browser compiles Pyodide while it downloads)."""

from __future__ import annotations

import functools
import http.server
import os
import threading
from pathlib import Path

from ..scada.http_limits import BoundedHTTPServer, DeadlineMixin

EXTRA_TYPES = {".wasm": "application/wasm", ".mjs": "text/javascript", ".zip": "application/zip",
               ".json": "application/json", ".svg": "image/svg+xml"}


class _Handler(DeadlineMixin, http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **EXTRA_TYPES}

    timeout = 30  # a client that stops sending does not hold a thread: each read, and the
    # whole request (DeadlineMixin: a client sending a byte now and then is cut off too)

    def log_message(self, format: str, *args: object) -> None:  # noqa: A002 - the base's name
        pass

    def send_head(self):  # noqa: ANN201 - the base's signature
        """The file's ``.gz`` copy (written by the build) to a browser that accepts gzip."""
        path = self.translate_path(self.path)
        if os.path.isdir(path):
            if not self.path.split("?", 1)[0].endswith("/"):
                return super().send_head()  # the base redirects to the folder's URL
            path = os.path.join(path, "index.html")
        packed = path + ".gz"
        accepts = "gzip" in self.headers.get("Accept-Encoding", "")
        if not (accepts and os.path.isfile(path) and os.path.isfile(packed)):
            return super().send_head()
        try:
            f = open(packed, "rb")  # noqa: SIM115 - the base class closes it after copying
        except OSError:
            return super().send_head()
        self.send_response(200)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Encoding", "gzip")
        self.send_header("Vary", "Accept-Encoding")
        self.send_header("Content-Length", str(os.fstat(f.fileno()).st_size))
        self.end_headers()
        return f

    def list_directory(self, path: str):  # noqa: ANN201 - the base's signature
        """No directory listings: a folder without index.html is 404 (ADR 0041)."""
        self.send_error(404, "No such page")
        return None


def make_server(root: Path, port: int = 0) -> http.server.ThreadingHTTPServer:
    """An HTTP server for ``root`` on 127.0.0.1 (``port`` 0: a free one)."""
    handler = functools.partial(_Handler, directory=str(root))
    return BoundedHTTPServer(("127.0.0.1", port), handler)


def serve_in_thread(root: Path, port: int = 0) -> tuple[http.server.ThreadingHTTPServer, str]:
    """Start serving in a daemon thread; returns the server and its base URL."""
    server = make_server(root, port)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/"


def serve_forever(root: Path, port: int) -> None:
    server = make_server(root, port)
    print(f"serving {root} at http://127.0.0.1:{server.server_address[1]}/ (Ctrl-C stops)")
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
