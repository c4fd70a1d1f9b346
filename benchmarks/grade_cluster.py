"""Submissions per minute on the local executor and on a two-worker Dask cluster on this
machine (loopback), and the overhead per task. Printed side by side, never asserted.

The same folder is graded twice into fresh output folders: ``--jobs 2`` locally, then on a
scheduler with two single-thread worker processes started here. *Overhead per task* is the
worker time a submission costs beyond its child's own wall time:
``(wall x 2 slots - sum of child times) / n`` -- process start, pipes, Dask's scheduling and
transfers, the client writing files.

    python benchmarks/grade_cluster.py [--n 1000] [--media]
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

LAB = "tank-two-position"
SLOTS = 2


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_cluster(workers: int = SLOTS) -> tuple[str, list[subprocess.Popen]]:
    """A loopback scheduler and ``workers`` single-thread worker processes."""
    from distributed import Client

    env = {**os.environ, "PYTHONPATH": str(ROOT),
           # the statistical profiler samples every thread each 10 ms: CPU the children need
           "DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED": "False"}
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL,
             "start_new_session": True, "env": env}
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler",
                               "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], **quiet)]
    procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", addr,
                                   "--nworkers", str(workers), "--nthreads", "1",
                                   "--no-dashboard"], **quiet))
    with Client(addr, timeout="60s", set_as_default=False) as c:
        c.wait_for_workers(workers, timeout=120)
    return addr, procs


def stop(procs: list[subprocess.Popen]) -> None:
    for p in reversed(procs):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)


def run(lab, subs: Path, out: Path, media: bool, executor: str | None) -> tuple[float, float]:
    """(wall time, sum of the children's wall times) of grading ``subs``."""
    from plclab.grade.grader import Grader

    t0 = time.perf_counter()
    outcomes = Grader(lab, out, jobs=SLOTS, media=media, executor=executor).grade_folder(subs)
    wall = time.perf_counter() - t0
    return wall, sum(o.wall_s for o in outcomes)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=1000)
    p.add_argument("--media", action="store_true", help="also diagrams and recordings")
    ns = p.parse_args(argv)
    from grade_many import make_half_failing

    from plclab.grade.lab import load_lab

    lab = load_lab(LAB, deep=True)
    base = Path(tempfile.mkdtemp(prefix="plclab-grade-cluster-"))
    procs: list[subprocess.Popen] = []
    try:
        subs = base / "subs"
        subs.mkdir()
        make_half_failing(subs, ns.n)
        local = run(lab, subs, base / "local", ns.media, None)
        t = time.perf_counter()
        addr, procs = start_cluster()
        start_s = time.perf_counter() - t
        dask = run(lab, subs, base / "dask", ns.media, addr)
    finally:
        stop(procs)
        shutil.rmtree(base, ignore_errors=True)
    print(f"{LAB}: {ns.n} submissions (half failing), {'with' if ns.media else 'no'} media, "
          f"{SLOTS} slots each")
    print(f"{'executor':<26}{'wall':>9}{'subs/min':>10}{'child mean':>12}{'overhead/task':>15}")
    for name, (wall, child) in (("local --jobs 2", local), ("dask, 2 workers (loopback)", dask)):
        over = (wall * SLOTS - child) / ns.n
        print(f"{name:<26}{wall:>8.1f}s{ns.n / wall * 60:>10.0f}{child / ns.n:>11.3f}s"
              f"{over * 1000:>13.0f}ms")
    print(f"cluster start (scheduler + 2 workers): {start_s:.1f} s, not counted above; "
          f"dask/local wall: {dask[0] / local[0]:.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
