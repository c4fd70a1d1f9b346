"""Screenshots of the default rerun view of every lab's reference run and its first mistake.

    python -m plclab.grade.screenshots --out docs/figures/rerun [--labs tank-two-position,...]

For each lab: grade the reference solution (the first ``solution/*.st``) and the first mistake
(``mistakes/*.st`` in name order) in process, record its first failing scenario (else its first
scenario) as ``plclab lab check --rrd`` does, open it in the rerun viewer under Xvfb
(software Vulkan: ``apt-get install xvfb mesa-vulkan-drivers``), move the time cursor to the
first failure (else to the middle of the run), park the mouse pointer out of the way (xdotool,
if installed) and save what the window draws with
``rerun.experimental.ViewerClient.save_screenshot`` (an X screen grab comes back black).

Nothing is written into the source tree unless ``--out`` points there.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .lab import find_lab, list_labs


def runs(lab_id: str) -> list[tuple[str, Path]]:
    """(tag, program) of the reference solution and the first mistake."""
    d = find_lab(lab_id)
    sols = sorted((d / "solution").glob("*.st")) or sorted((d / "solution").glob("*"))
    mistakes = sorted((d / "mistakes").glob("*.st")) or sorted((d / "mistakes").glob("*"))
    out = [("reference", sols[0])] if sols else []
    if mistakes:
        out.append((mistakes[0].stem.replace("_", "-"), mistakes[0]))
    return out


def record(lab_id: str, program: Path, path: Path) -> tuple[float, str]:
    """Grade ``program`` and write its recording; returns the time to show (the first
    failure, else the end) and the recording id of the scenario to show (the first)."""
    from plclab.grade.engine import grade_sources, read_submission
    from plclab.grade.lab import load_lab
    from plclab.viz.from_trace import lab_recordings
    from plclab.viz.recording import write_many

    lab = load_lab(lab_id)
    src, _ = read_submission(str(program))
    res = grade_sources(lab, src, student="", keep_traces=True)
    from .feedback import run_limits

    recs = lab_recordings(lab, res, program.name,  # the criteria's limits drawn, as lab check
                          limits=run_limits(lab))
    first = recs[0]  # a failing scenario if there is one
    # rerun 0.41's viewer opens only one recording of a file through its catalog (the
    # default); the shot shows the first scenario, so write that one
    write_many([first], path)
    fails = [v.time for v in first.layout.info.verdicts if not v.passed and v.time is not None]
    ts = first.layout.plots[0].lines[0].series.times if first.layout.plots else [0.0]
    t = min(fails) if fails else 0.5 * (float(ts[0]) + float(ts[-1]))  # else mid-run
    return t, first.layout.info.recording_id()


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def viewer(rrd: Path, env: dict[str, str], timeout: float = 120.0):
    """A rerun viewer of its own showing ``rrd`` at 1600x1000: yields its client and its state
    once the recordings are loaded (``(None, None)`` when it did not come up within
    ``timeout``); stopped on leaving."""
    from rerun.experimental import ViewerClient

    port = free_port()
    # ``python -m rerun_cli`` starts the viewer binary as its child: a session of its own, so
    # that stopping it stops the viewer too (terminating only the wrapper left the viewer
    # drawing on, one more software renderer per shot)
    proc = subprocess.Popen([sys.executable, "-m", "rerun_cli", str(rrd), "--port", str(port),
                             "--window-size", "1600x1000"], start_new_session=True,
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        client, state = None, None
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                client = ViewerClient.connect(f"rerun+http://127.0.0.1:{port}/proxy")
                state = client.get_state()
                if state.recordings and not state.loading:
                    break
            except Exception:  # noqa: BLE001 - not up yet
                pass
            time.sleep(1.0)
        yield client, state
    finally:
        stop_group(proc)


def stop_group(proc: subprocess.Popen) -> None:
    """Stop a process started with ``start_new_session`` and every process of its group."""
    import signal

    for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 5)):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, sig)
        try:
            proc.wait(wait)
            return
        except subprocess.TimeoutExpired:
            continue


@contextlib.contextmanager
def display(needed: bool = True):
    """The environment a viewer runs in: this one's display, or an Xvfb of its own (1600x1000)
    when there is none or ``PLCLAB_XVFB`` asks for one; stopped on leaving."""
    env = {**os.environ, "RUST_LOG": "warn", "RERUN_ANALYTICS": "0"}
    xvfb = None
    if needed and (not os.environ.get("DISPLAY") or os.environ.get("PLCLAB_XVFB")):
        if shutil.which("Xvfb") is None:
            raise SystemExit("no display and no Xvfb: apt-get install xvfb mesa-vulkan-drivers")
        xvfb, n = start_xvfb()
        env["DISPLAY"] = f":{n}"
    try:
        yield env
    finally:
        if xvfb is not None:
            xvfb.terminate()
            xvfb.wait(10)


def start_xvfb(timeout: float = 30.0) -> tuple[subprocess.Popen, int]:
    """An Xvfb at 1600x1000 on a display number it picks itself (``-displayfd``), and that
    number once it listens: two shooters started at once never race for one display."""
    import select

    r, w = os.pipe()
    try:
        proc = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1600x1000x24"],
                                pass_fds=(w,), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        os.close(w)
        w = -1
        text = b""
        deadline = time.monotonic() + timeout
        while not text.endswith(b"\n") and time.monotonic() < deadline:
            ready, _, _ = select.select([r], [], [], max(0.0, deadline - time.monotonic()))
            chunk = os.read(r, 16) if ready else b""
            if not chunk:
                break
            text += chunk
    finally:
        os.close(r)
        if w >= 0:
            os.close(w)
    if not text.strip().isdigit():
        proc.kill()
        proc.wait(5)
        raise SystemExit("Xvfb did not start: it gave no display number within "
                         f"{timeout:.0f} s")
    return proc, int(text)


def park_pointer(env: dict[str, str]) -> None:
    """The pointer on the menu bar, so that no hover tooltip covers the view."""
    if shutil.which("xdotool"):
        subprocess.run(["xdotool", "mousemove", "5", "5"], env=env, check=False)


def shoot(rrd: Path, png: Path, t: float, rid: str, env: dict[str, str], wait: float) -> None:
    """Open ``rrd`` in a viewer of its own, show recording ``rid`` with the cursor at ``t``,
    save the window."""
    with viewer(rrd, env) as (client, state):
        if client is None or state is None:
            raise SystemExit(f"the viewer did not come up for {rrd}")
        rec = next((r for r in state.recordings if r.store_id.endswith(":" + rid)), None)
        if rec is None:
            print(f"  (recording {rid} not among {[r.store_id for r in state.recordings]})")
        if rec is not None:
            client.set_location(rec.location)
            time.sleep(1.0)
        client.set_time("sim_time", duration=t, play_state="paused",
                        recording=rec.store_id if rec is not None else None)
        park_pointer(env)
        time.sleep(wait)
        client.save_screenshot(str(png))
        shrink(png)


def shrink(png: Path) -> None:
    """256 colours are plenty for the viewer's flat dark UI: a third of the bytes."""
    try:
        from PIL import Image
    except ImportError:
        return
    with Image.open(png) as im:
        small = im.convert("RGB").quantize(256)
    small.save(png, optimize=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="folder for the PNGs")
    ap.add_argument("--labs", default=None, help="comma separated lab ids (default: all)")
    ap.add_argument("--keep-rrd", action="store_true", help="keep the .rrd files next to them")
    ap.add_argument("--wait", type=float, default=8.0, help="seconds to let the viewer draw")
    ns = ap.parse_args(argv)
    out = Path(ns.out)
    out.mkdir(parents=True, exist_ok=True)
    labs = ns.labs.split(",") if ns.labs else [p.name for p in list_labs()]
    with display() as env, tempfile.TemporaryDirectory(prefix="plclab-shots-") as tmp:
        for lab_id in labs:
            for tag, program in runs(lab_id):
                rrd = Path(tmp) / f"{lab_id}--{tag}.rrd"
                t, rid = record(lab_id, program, rrd)
                png = out / f"{lab_id}--{tag}.png"
                shoot(rrd, png, t, rid, env, ns.wait)
                if ns.keep_rrd:
                    shutil.copy(rrd, out / rrd.name)
                print(f"{png}  ({program}, cursor at {t:.1f} s)")
    return 0

if __name__ == "__main__":
    raise SystemExit(main())
