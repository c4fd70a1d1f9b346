"""What a student sees after a failed check, for every lab and each of its mistakes.

    python -m plclab.grade.lab_pictures --out /tmp/pics [--labs a,b] [--first] [--no-viewer]
                                        [--hidden] [--sheets]

For each mistake (``labs/*/mistakes/*``; ``--first``: the first of each lab) it runs, as a
student would, ``plclab lab check LAB MISTAKE --png P --rrd R`` (visible scenarios) and keeps:

- ``LAB--MISTAKE.png``: the ``--png`` timing diagram (the first failure, its criterion's limits);
- ``LAB--MISTAKE--viewer.png``: the real rerun viewer's *default* view of ``R`` (no clicks, no
  cursor moved: under Xvfb at 1600x1000, saved with ``ViewerClient.save_screenshot``);
- a line in ``index.tsv``: lab, mistake, its score, the scenario and criterion ``--png`` drew,
  the limits of that criterion the picture draws (``criterion_limits``), what the viewer opened
  (its recording, where its time cursor stood), ``hidden`` when it was drawn from a hidden
  scenario, and what the recording holds to mark the failure (:func:`recorded`: the plots
  crossed by the failure line, the criterion's dashed limits, the first-failure lane's words).

``--hidden``: a mistake that passes every visible scenario is checked again with the
instructor's ``lab check --hidden`` (hidden scenarios too), so that its failure is drawn.

``--sheets``: contact sheets (``sheets/LAB-N.png``, four viewer screenshots to a page, each
under its lab, mistake and what the viewer opened) so that all 151 can be looked at;
``--sheets-only`` makes them again from the ``--out`` folder a run filled.

How the viewer is run headless (checked with rerun-sdk 0.41 on Debian 12): Xvfb at
1600x1000x24 and Mesa's software Vulkan (lavapipe, ``apt-get install xvfb
mesa-vulkan-drivers``), no other setting needed; ``WGPU_BACKEND=gl`` / ``--renderer gl``
exits at once ("Adapter does not support drawing to texture format R32Float"). An X grab
of the screen (``import -window root``, ``xwd``, Pillow's ``ImageGrab``) comes back all
black: the viewer presents through Vulkan, which Xvfb does not composite, so the picture
is taken by the viewer itself,
``rerun.experimental.ViewerClient.save_screenshot``, once its recording is loaded and
it has drawn for ``--wait`` seconds.

Not run by the test suite (minutes per lab). ``docs/figures/rerun/`` holds a chosen few.
"""

from __future__ import annotations

import argparse
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .lab import list_labs
from .screenshots import display, park_pointer, shrink, viewer


def mistakes(labs: list[str] | None, first: bool) -> list[tuple[str, Path]]:
    out = []
    for d in list_labs():
        if labs and d.name not in labs:
            continue
        ms = sorted(p for p in (d / "mistakes").glob("*.*")) if (d / "mistakes").is_dir() else []
        out += [(d.name, m) for m in (ms[:1] if first else ms)]
    return out


def check(lab: str, program: Path, png: Path, rrd: Path, hidden: bool = False) -> str:
    """``plclab lab check`` as a student runs it (``hidden``: as the instructor, with the
    hidden scenarios); its output."""
    done = subprocess.run([sys.executable, "-m", "plclab", "lab", "check", lab, str(program),
                           "--png", str(png), "--rrd", str(rrd)] + (["--hidden"] if hidden else []),
                          capture_output=True, text=True)
    return done.stdout + done.stderr


def drawn_limits(lab: str, criterion: str) -> str:
    """The limits ``--png`` draws for ``criterion`` of ``lab`` (its one description), as
    words; ``-`` when it has none."""
    from .criteria import criterion_limits
    from .lab import load_lab

    crit = next((c for c in load_lab(lab).criteria if c.name == criterion), None)
    lims = criterion_limits(crit) if crit is not None else []
    return "; ".join(f"{lim.kind}: {lim.label}" for lim in lims) or "-"


def recorded(rrd: Path, criterion: str) -> str:
    """What the main recording ``rrd`` holds to mark the failure of ``criterion`` (read back
    with rerun's reader): the plots crossed by a failure line, the dashed limits of that
    criterion, and the first-failure lane's words (``checks ...`` or ``checked by ...``)."""
    from rerun.chunk import RrdReader

    from plclab.viz.layout import slug
    from plclab.viz.recording import FAILED_LANE

    reader = RrdReader(rrd)
    stores = reader.recordings()
    if not stores:
        return "empty recording"
    plots, lines, lims, words = set(), set(), set(), ""
    for chunk in reader.stream(store=stores[0]):
        path = str(chunk.entity_path)
        if path.startswith("/plots/") and "/limits/" not in path and "/markers/" not in path:
            plots.add(path.split("/")[2])
        if path.endswith("/failed_at"):
            lines.add(path.split("/")[2])
        if "/limits/" in path and criterion and \
                path.split("/limits/")[1].split("_", 1)[-1].startswith(slug(criterion)):
            lims.add(path)
        if path == FAILED_LANE and not words:
            batch = chunk.to_record_batch()
            for name in batch.schema.names:
                if name.endswith("StateConfiguration:labels"):
                    vals = [v for row in batch.column(name).to_pylist() for v in (row or [])]
                    words = vals[0] if vals else ""
    return (f"failure line in {len(lines)}/{len(plots)} plots; {len(lims)} dashed limits of "
            f"the criterion; lane: {words or 'none'}")


def default_view(rrd: Path, png: Path, env: dict[str, str], wait: float) -> str:
    """Open ``rrd`` in a viewer of its own and save its first view untouched; what it opened."""
    with viewer(rrd, env, timeout=180) as (client, state):
        if client is None or state is None:
            return "viewer did not come up"
        park_pointer(env)
        time.sleep(wait)
        for attempt in range(3):  # a loaded machine: the viewer may answer late
            try:
                client.save_screenshot(str(png))
                state = client.get_state()
                break
            except Exception as e:  # noqa: BLE001 - TimeoutError from the viewer's gRPC
                if attempt == 2:
                    return f"no screenshot: {e}"
                time.sleep(5.0)
        shrink(png)
        act = next((r for r in state.recordings if r.store_id == state.active_recording), None)
        if act is None:
            return f"opened {state.active_recording}"
        t = act.current_time
        when = f"{t / 1e9:.2f} s" if t is not None else "unset"
        return f"opened {act.store_id.split(':')[-1]}, cursor at {when}"


SHEET_TILE = (800, 500)  # half the viewer's 1600x1000: four to a 1600x1000 page


def contact_sheets(folder: Path, per_sheet: int = 4) -> list[Path]:
    """``folder/sheets/LAB-N.png``: the viewer screenshots of ``folder`` four to a page (two
    by two, each half size), captioned with the line of ``index.tsv`` that describes it."""
    from PIL import Image, ImageDraw

    captions = {}
    index = folder / "index.tsv"
    if index.exists():
        for line in index.read_text(encoding="utf-8").splitlines():
            f = line.split("\t")
            if len(f) >= 6:
                tag = f"{f[0]}--{Path(f[1]).stem.replace('_', '-')}"
                captions[tag] = f"{f[0]} {f[1]} {f[2]}: {f[5]}"
    by_lab: dict[str, list[Path]] = {}
    for png in sorted(folder.glob("*--viewer.png")):
        by_lab.setdefault(png.name.split("--")[0], []).append(png)
    out_dir = folder / "sheets"
    out_dir.mkdir(exist_ok=True)
    made = []
    w, h = SHEET_TILE
    cap = 18  # caption band above each tile
    for lab, pngs in by_lab.items():
        for n in range(0, len(pngs), per_sheet):
            sheet = Image.new("RGB", (2 * w, 2 * (h + cap)), "white")
            draw = ImageDraw.Draw(sheet)
            for i, png in enumerate(pngs[n:n + per_sheet]):
                x, y = (i % 2) * w, (i // 2) * (h + cap)
                tag = png.name[: -len("--viewer.png")]
                draw.text((x + 4, y + 3), captions.get(tag, tag)[:130], fill="black")
                with Image.open(png) as im:
                    sheet.paste(im.convert("RGB").resize(SHEET_TILE, Image.LANCZOS), (x, y + cap))
            path = out_dir / f"{lab}-{n // per_sheet + 1}.png"
            sheet.save(path, optimize=True)
            made.append(path)
    return made


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--labs", default=None, help="comma separated lab ids (default: all)")
    ap.add_argument("--first", action="store_true", help="only the first mistake of each lab")
    ap.add_argument("--no-viewer", action="store_true", help="only the --png pictures")
    ap.add_argument("--hidden", action="store_true",
                    help="a mistake that passes the visible scenarios: check it again with "
                    "the hidden ones (the instructor's view)")
    ap.add_argument("--wait", type=float, default=10.0, help="seconds to let the viewer draw")
    ap.add_argument("--resume", action="store_true",
                    help="skip the mistakes OUT/index.tsv already has (a run stopped midway)")
    ap.add_argument("--sheets", action="store_true",
                    help="also contact sheets of the viewer screenshots (OUT/sheets/)")
    ap.add_argument("--sheets-only", action="store_true",
                    help="only make the contact sheets of what OUT already holds")
    ns = ap.parse_args(argv)
    out = Path(ns.out)
    if ns.sheets_only:
        for path in contact_sheets(out):
            print(path)
        return 0
    out.mkdir(parents=True, exist_ok=True)
    index = out / "index.tsv"
    # stopped (kill PID): leave through the context managers, so that the Xvfb and the
    # viewer it started stop too (a background job ignores Ctrl-C's SIGINT)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    with display(not ns.no_viewer) as env, \
            tempfile.TemporaryDirectory(prefix="plclab-pics-") as tmp:
        done = set()
        if ns.resume and index.exists():
            done = {tuple(line.split("\t")[:2])
                    for line in index.read_text(encoding="utf-8").splitlines()}
        for lab, program in mistakes(ns.labs.split(",") if ns.labs else None, ns.first):
            if (lab, program.name) in done:
                continue
            tag = f"{lab}--{program.stem.replace('_', '-')}"
            png, rrd = out / f"{tag}.png", Path(tmp) / f"{tag}.rrd"
            text = check(lab, program, png, rrd)
            m = re.search(r"timing diagram: \S+ \((.*)\)", text)
            score = re.findall(r"score: (\S+)/(\S+)", text)
            full = bool(score) and score[-1][0] == score[-1][1]
            hidden = "-"
            if ns.hidden and m is None and full:  # fails only in hidden scenarios
                text = check(lab, program, png, rrd, hidden=True)
                m = re.search(r"timing diagram: \S+ \((.*)\)", text)
                score = re.findall(r"score: (\S+)/(\S+)", text)
                full = bool(score) and score[-1][0] == score[-1][1]
                hidden = "hidden"
            crit = re.search(r"criterion '([^']*)'", m.group(1)) if m else None
            lims = drawn_limits(lab, crit.group(1)) if crit else "-"
            drew = m.group(1) if m else ("passed the visible scenarios (no failure to draw)"
                                         if full else "no failure picture")
            seen, marks = "-", "-"
            if rrd.exists():
                marks = recorded(rrd, crit.group(1) if crit else "")
            if not ns.no_viewer and rrd.exists():
                seen = default_view(rrd, out / f"{tag}--viewer.png", env, ns.wait)
            line = "\t".join([lab, program.name, "/".join(score[-1]) if score else "?", drew,
                              lims, seen, hidden, marks])
            with index.open("a", encoding="utf-8") as f:
                f.write(line + "\n")
            print(line, flush=True)
    if ns.sheets and not ns.no_viewer:
        for path in contact_sheets(out):
            print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
