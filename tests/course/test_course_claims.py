"""The numbers chapter 12 states about its plant runs are what those runs give: the figure
specifications are re-run here (same program, plant, wiring and seed) and the quoted values
checked against the trace, so a change of the plant or the PID block shows in the text."""

import numpy as np
import pytest

from plclab.course.model import find_chapter
from plclab.sim import run

CHAPTER = find_chapter(12)


def _trace(figure: str, **scenario_changes):
    spec = next(s for s in CHAPTER.figure_specs if s["file"] == figure)
    scenario = dict(spec.get("scenario", {}), **scenario_changes)
    return run([str(CHAPTER.folder / "examples" / spec["program"])], plant=spec["plant"],
               duration=spec["duration"], scenario=scenario, seed=int(spec.get("seed", 1)),
               plant_params=spec.get("plant_params"))


def test_comparator_chatters_and_hysteresis_does_not():
    chatter = _trace("comparator.svg").switchings("HEATER")
    calm = _trace("hysteresis.svg").switchings("HEATER")
    assert chatter > 2300 and calm == 14
    assert "more than 2,300 times in 10 minutes" in CHAPTER.text
    assert "switches 14 times in 10 minutes" in CHAPTER.text


@pytest.mark.parametrize("figure", ["heater_pi.svg", "heater_pi100.svg"])
def test_pi_runs_as_the_text_says(figure):
    tr = _trace(figure)
    t, temp = np.asarray(tr.time), np.asarray(tr["TEMP"])
    before, after = temp[t < 900], temp[t >= 900]
    if figure == "heater_pi.svg":  # TN = 700 s: "0.6 °C short" after 15 min, "0.25 °C short" at 30
        assert 50.0 - before[-1] == pytest.approx(0.6, abs=0.05)
        assert 55.0 - temp[-1] == pytest.approx(0.25, abs=0.03)
    else:  # TN = 100 s: 50.0 °C within 10 min, the 55 °C step overshoots by 0.36 °C
        assert temp[np.searchsorted(t, 600.0)] == pytest.approx(50.0, abs=0.05)
        assert after.max() - 55.0 == pytest.approx(0.36, abs=0.03)
    assert before.max() - 50.0 < 0.08  # anti-windup: "at most 0.07 °C"
    text = " ".join(CHAPTER.text.split())
    for quoted in ("0.6 °C short of 50 °C", "0.25 °C short", "reaches 50.0 °C within 10 minutes",
                   "by only 0.36 °C", "(at most 0.07 °C)"):
        assert quoted in text
