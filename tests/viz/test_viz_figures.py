"""The timer and counter figures (001 Figs 42-48) come from real runs of the blocks."""

import pytest

from plclab.viz.figures import BLOCKS, block_run


def _changes(vals):
    out = [vals[0]]
    for v in vals[1:]:
        if v != out[-1]:
            out.append(v)
    return out


def test_tp_ignores_a_retrigger_while_running():
    t, c = block_run("TP")
    q_rises = [t[i] for i in range(1, len(t)) if c["Q"][i] and not c["Q"][i - 1]]
    assert q_rises == [0.1, 0.6]  # the second IN pulse at 0.25 s is ignored
    assert max(c["ET"]) == pytest.approx(0.3)


def test_ton_et_stops_at_pt_and_resets_with_in():
    t, c = block_run("TON")
    assert max(c["ET"]) == pytest.approx(0.3)
    assert [t[i] for i in range(1, len(t)) if c["Q"][i] and not c["Q"][i - 1]] == [0.7]


def test_counters_count_edges():
    _, c = block_run("CTUD")
    assert _changes(c["CV"]) == [0, 1, 2, 3, 4, 3, 2, 0]
    _, c = block_run("CTD")
    assert _changes(c["CV"]) == [0, 3, 2, 1, 0, -1]


@pytest.mark.parametrize("block", BLOCKS)
def test_every_figure_renders(block, tmp_path):
    pytest.importorskip("matplotlib")
    from plclab.viz.figures import block_figure

    block_figure(block, tmp_path / f"{block}.svg")
    svg = (tmp_path / f"{block}.svg").read_text()
    assert f">{block} (" in svg
