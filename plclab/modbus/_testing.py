"""Helpers for tests of the Modbus layer: free ports, ``plclab`` server subprocesses.

Every helper stays on 127.0.0.1, waits with bounded loops, and stops what it started.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nobody listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_port(port: int, timeout: float = 15.0, proc: subprocess.Popen | None = None) -> None:
    """Wait until something accepts connections on 127.0.0.1:port."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if proc is not None and proc.poll() is not None:
            raise RuntimeError(f"the server exited early with code {proc.returncode}")
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            time.sleep(0.05)
    raise TimeoutError(f"nothing listens on 127.0.0.1:{port} after {timeout} s")


def wait_until(predicate, timeout: float = 10.0, interval: float = 0.05):
    """Call ``predicate`` until it returns a true value (returned) or ``timeout`` passes."""
    end = time.monotonic() + timeout
    last = None
    while time.monotonic() < end:
        last = predicate()
        if last:
            return last
        time.sleep(interval)
    return last


class PlclabProcess:
    """``python -m plclab ARGS...`` in a subprocess, output captured in a temporary file.

    Entering waits until the server listens on ``port``; leaving stops it with SIGINT and keeps
    what it printed in ``output``. For example::

        with PlclabProcess(["serve", "prog.st", "--port", str(port)], port=port) as p:
            c = connect(port=port)          # plclab.modbus.connect
            c["%MW0"] = 42
        assert "listening on" in p.output
    """

    def __init__(self, args: list[str], port: int | None = None, cwd: str | None = None,
                 timeout: float = 15.0) -> None:
        self.args = [sys.executable, "-m", "plclab", *args]
        self.port = port
        self.cwd = cwd
        self.timeout = timeout
        self.proc: subprocess.Popen | None = None
        self._out = None
        self.output = ""
        self.returncode: int | None = None

    def start(self) -> PlclabProcess:
        root = str(Path(__file__).resolve().parents[2])
        env = dict(os.environ)
        env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
        env["PYTHONUNBUFFERED"] = "1"
        self._out = tempfile.TemporaryFile(mode="w+", encoding="utf-8")
        self.proc = subprocess.Popen(self.args, stdout=self._out, stderr=subprocess.STDOUT,
                                     cwd=self.cwd, env=env)
        if self.port is not None:
            try:
                wait_port(self.port, self.timeout, self.proc)
            except BaseException:
                self.stop()
                raise RuntimeError(f"{' '.join(self.args[2:])} did not start:\n{self.output}") \
                    from None
        return self

    def read_output(self) -> str:
        if self._out is None:
            return self.output
        self._out.seek(0)
        return self._out.read()

    def stop(self, sig: int = signal.SIGINT, timeout: float = 30.0) -> int:
        """Send ``sig`` (SIGINT = Ctrl-C), wait for the exit; kill after ``timeout``."""
        if self.proc is None:
            return self.returncode if self.returncode is not None else -1
        proc, self.proc = self.proc, None
        if proc.poll() is None:
            proc.send_signal(sig)
            try:
                proc.wait(timeout)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(5)
        self.returncode = proc.returncode
        self.output = self.read_output()
        if self._out is not None:
            self._out.close()
            self._out = None
        return self.returncode

    def __enter__(self) -> PlclabProcess:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()
