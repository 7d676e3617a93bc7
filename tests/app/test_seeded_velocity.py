"""One velocity for one run: a run seeded with a computed traveling wave shows the velocity
measured from the wave's passage times (fpucore.simulate.seeded: the paper's "velocity within
O(1e-8)" check), and the Simulation scene prints for Figs. stabSK and stabSW the row the Paper
tab prints for them — fpucore.paper's own run of the figure, computed here independently."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app.explorer import Explorer  # noqa: E402
from app.views.formatting import comparison_parts  # noqa: E402
from fpucore.paper.figures_dynamics import fig_stabSK, fig_stabSW  # noqa: E402


@pytest.mark.parametrize("label, figure", [("stabSK", fig_stabSK), ("stabSW", fig_stabSW)])
def test_the_simulation_scene_prints_the_paper_tabs_velocity_row(label, figure):
    ex = Explorer(lazy=True)
    ex.scene("paper").open(label)
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    shown = sc.last_info.shown
    # panel (b) of the figure as fpucore.paper computes it (the Paper tab's row)
    _, comps, _, _ = figure(False)
    row = comparison_parts([comps[1]])[0]
    assert row in shown, (row, shown)
    assert row.startswith("✓") and "paper O(1e-8)" in row
    sim = sc._sim[-1]
    assert f"measured velocity V = {sim.details['V_measured']!r}" in shown
    assert abs(sim.details["V_measured"] - sim.details["V_prescribed"]) < 1e-10
    # the tracker's coarser estimate is still there, labelled, after the measured one
    assert shown.index("measured velocity") < shown.index("the tracker's estimate:")


def test_the_superkink_v_5_2_is_the_clis_run():
    """`fpu simulate wave superkink --V 5.2` prints V_measured 5.199999999992748 (the issue's
    report); the explorer's stabSK click runs the same wave on the same chain."""
    from fpucore import simulate, wave
    from fpucore.paper.common import LAW

    s = simulate.seeded(wave.solve_superkink(LAW, 5.2))
    ex = Explorer(lazy=True)
    ex.scene("paper").open("stabSK")
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    assert sc._sim[-1].details["V_measured"] == s.details["V_measured"]
    assert sc._sim[-1].L == s.L
