"""The site server (``plclab site serve``) serves files, never a listing of a folder."""

import urllib.error
import urllib.request

import pytest

from plclab.site.serve import serve_in_thread


def test_a_folder_without_index_is_not_listed(tmp_path):
    (tmp_path / "index.html").write_text("<p>home</p>", encoding="utf-8")
    (tmp_path / "private").mkdir()
    (tmp_path / "private" / "secret.txt").write_text("x", encoding="utf-8")
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "index.html").write_text("<p>docs</p>", encoding="utf-8")
    server, url = serve_in_thread(tmp_path)
    try:
        with urllib.request.urlopen(url, timeout=5) as r:
            assert b"home" in r.read()
        with urllib.request.urlopen(url + "docs/", timeout=5) as r:
            assert b"docs" in r.read()
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(url + "private/", timeout=5)
        assert e.value.code == 404 and b"secret.txt" not in e.value.read()
        with urllib.request.urlopen(url + "private/secret.txt", timeout=5) as r:
            assert r.read() == b"x"
    finally:
        server.shutdown()
        server.server_close()


def test_a_trickled_request_loses_its_connection(tmp_path, monkeypatch):
    """The per-read timeout does not bound a client sending a header line now and then; the
    whole request does (DeadlineMixin), and the server goes on serving others."""
    import socket
    import time

    from plclab.site import serve

    monkeypatch.setattr(serve._Handler, "timeout", 0.5)
    (tmp_path / "index.html").write_text("<p>hi</p>", encoding="utf-8")
    server, url = serve_in_thread(tmp_path)
    try:
        port = server.server_address[1]
        with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
            s.sendall(b"GET / HTTP/1.1\r\n")
            cut = False
            for _ in range(100):  # 10 s of header lines at most
                time.sleep(0.1)
                try:
                    s.sendall(b"X-Slow: 1\r\n")
                except OSError:
                    cut = True
                    break
            assert cut
        with urllib.request.urlopen(url, timeout=5) as r:
            assert r.read() == b"<p>hi</p>"
    finally:
        server.shutdown()
        server.server_close()
