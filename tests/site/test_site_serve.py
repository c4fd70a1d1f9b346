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
