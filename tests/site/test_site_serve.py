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


def test_precompressed_files_go_to_browsers_that_accept_gzip(tmp_path):
    """The build's ``.gz`` copies are sent with Content-Encoding: gzip when the request accepts
    it; otherwise the file itself. A folder URL serves its index.html the same way."""
    import gzip

    from plclab.site.freshness import precompress

    page = ("<p>" + "the playground runs a tank " * 200 + "</p>").encode()
    (tmp_path / "index.html").write_bytes(page)
    (tmp_path / "py").mkdir()
    (tmp_path / "py" / "core.wasm").write_bytes(b"\0asm" + bytes(4000))
    (tmp_path / "py" / "index.html").write_bytes(page)
    (tmp_path / "tiny.js").write_text("x=1")  # too small to be worth it
    assert precompress(tmp_path) == 3
    assert not (tmp_path / "tiny.js.gz").exists()
    server, url = serve_in_thread(tmp_path)

    def get(path, gz):
        req = urllib.request.Request(url + path, headers={"Accept-Encoding": "gzip"} if gz
                                     else {})
        with urllib.request.urlopen(req, timeout=5) as r:
            return r.headers, r.read()
    try:
        head, body = get("py/core.wasm", True)
        assert head["Content-Encoding"] == "gzip" and head["Content-Type"] == "application/wasm"
        assert gzip.decompress(body) == b"\0asm" + bytes(4000) and len(body) < 200
        head, body = get("py/core.wasm", False)
        assert head["Content-Encoding"] is None and body == b"\0asm" + bytes(4000)
        head, body = get("py/", True)
        assert head["Content-Type"].startswith("text/html") and gzip.decompress(body) == page
        head, body = get("py", True)  # redirected to py/ first, as before
        assert gzip.decompress(body) == page
        head, body = get("tiny.js", True)
        assert head["Content-Encoding"] is None and body == b"x=1"
    finally:
        server.shutdown()
        server.server_close()


def test_a_site_is_built_again_only_when_its_sources_or_options_change(tmp_path):
    from plclab.site.freshness import fingerprint, record, recorded

    src = tmp_path / "src"
    (src / "course").mkdir(parents=True)
    (src / "course" / "a.md").write_text("# A")
    first = fingerprint({"figures": True}, src, ("course",))
    marker = tmp_path / ".plclab-site"
    record(marker, first)
    assert recorded(marker) == first
    (src / "course" / "a.md").write_text("# A, edited")
    assert fingerprint({"figures": True}, src, ("course",)) != first
    (src / "course" / "a.md").write_text("# A")
    assert fingerprint({"figures": True}, src, ("course",)) == first
    (src / "course" / "b.md").write_text("")  # a new file counts too
    assert fingerprint({"figures": True}, src, ("course",)) != first
    marker.write_text("built by plclab site build\n")  # a marker of an older build
    assert recorded(marker) is None
