"""Every lab's first mistake, checked with ``lab check --png`` on the visible scenarios, draws
a failing scenario (issue 32): the PNG is read back (its title, kept as PNG text, and the red
line of the failure in its pixels) and compared with a grading of its own, so a picture of a
scenario that passed, of the wrong criterion or of no failure at all is caught."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from plclab.grade.lab import load_lab

ROOT = Path(__file__).resolve().parents[2]
FIRST = {d.name: sorted((d / "mistakes").glob("*.*"))[0] for d in sorted((ROOT / "labs").iterdir())
         if (d / "lab.toml").exists() and (d / "mistakes").is_dir()
         and any((d / "mistakes").glob("*.*"))}
LINE = re.compile(r"timing diagram: .* \(scenario '(?P<s>[^']+)', criterion '(?P<c>[^']+)', "
                  r"failed (?P<when>at t = (?P<t>[\d.]+) s|over the run)\)")


def _title(png: Path) -> str:
    from PIL import Image

    with Image.open(png) as img:
        return img.text.get("Title", "")


def _red_columns(png: Path, min_count: int = 30) -> list[int]:
    from PIL import Image

    img = Image.open(png).convert("RGB")
    px, (w, h) = img.load(), img.size
    return [x for x in range(w) if sum(px[x, y][0] - px[x, y][1] > 45 and
                                       abs(px[x, y][1] - px[x, y][2]) < 30
                                       for y in range(h)) >= min_count]


def check_png(png: Path, line: str, failed: dict[tuple[str, str], float | None],
              order: list[str]) -> list[str]:
    """What is wrong with the ``--png`` of a failed check: ``failed`` maps (scenario,
    criterion) of every real failure to its moment; ``order`` is the lab's scenario order."""
    bad = []
    m = LINE.search(line)
    if m is None:
        return [f"no 'timing diagram: ... (scenario, criterion, failed ...)' line: {line!r}"]
    s, c = m["s"], m["c"]
    if (s, c) not in failed:
        bad.append(f"drew {s}/{c}, which did not fail")
    first = min((order.index(sc) for sc, _ in failed), default=None)
    if first is not None and s in order and order.index(s) != first:
        bad.append(f"drew {s}, not the first failing scenario {order[first]}")
    title = _title(png)
    if s not in title or c not in title or "FAILED" not in title:
        bad.append(f"the title {title!r} does not name {s} and {c} as FAILED")
    if m["t"] is not None and not _red_columns(png):
        bad.append("no red line where the failure is")
    return bad


@pytest.mark.parametrize("lab_id", sorted(FIRST))
def test_the_first_mistake_of_every_lab_draws_its_first_failure(lab_id, tmp_path, capsys):
    from plclab.cli import main
    from plclab.grade.engine import grade_sources, read_submission
    from plclab.grade.feedback import real_failure

    lab = load_lab(lab_id)
    mistake = FIRST[lab_id]
    visible = [s.name for s in lab.scenarios if s.visible]
    png = tmp_path / "first.png"
    assert main(["lab", "check", lab_id, str(mistake), "--png", str(png)]) == 0
    out = capsys.readouterr().out
    src, _ = read_submission(str(mistake))
    res = grade_sources(lab, src, student="", scenarios=visible)
    failed = {(t.scenario, t.criterion): t.t_fail for t in res.tests if real_failure(t)}
    if not failed:
        pytest.skip(f"{mistake.name} passes the visible scenarios of {lab_id}")
    assert png.exists(), out
    line = next((ln for ln in out.splitlines() if ln.startswith("timing diagram:")), "")
    assert check_png(png, line, failed, visible) == []


def test_the_png_check_catches_a_passing_scenario_a_wrong_title_and_no_failure_line(tmp_path):
    """The checker above on pictures made to be wrong."""
    import numpy as np

    from plclab.viz.series import Series
    from plclab.viz.timing import failure_png

    t = np.linspace(0, 10, 101)
    rows = [Series("PUMP %QX0.0", t, (t > 5).astype(float), "bool"),
            Series("LEVEL", t, t / 10, "real")]
    good = tmp_path / "good.png"
    good.write_bytes(failure_png(rows, None, 0, 10, title="normal: pump_on (FAILED)",
                                 markers=[(5.0, "pump_on fails")]))
    line = "timing diagram: good.png (scenario 'normal', criterion 'pump_on', failed at t = 5.00 s)"
    failed = {("normal", "pump_on"): 5.0, ("late", "pump_on"): 2.0}
    assert check_png(good, line, failed, ["normal", "late"]) == []
    assert check_png(good, line, failed, ["late", "normal"])  # not the first failing scenario
    assert check_png(good, line.replace("'normal'", "'late2'"), failed, ["normal", "late"])
    assert check_png(good, "timing diagram: x.png", failed, ["normal"])
    wrong = tmp_path / "wrong.png"
    wrong.write_bytes(failure_png(rows, None, 0, 10, title="normal: pump_on", markers=[]))
    problems = check_png(wrong, line, failed, ["normal", "late"])
    assert any("title" in p for p in problems) and any("red line" in p for p in problems)
