"""The explorer's wave table (simulation scene): plain names with a one-line explanation, and
V ± error, w_B ± error whose intervals hold the paper's Riemann values (Fig. Riemann1)."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("panel")

from app.views.simulation_table import fmt_pm, wave_table  # noqa: E402
from fpucore import simulate  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402


def _interval(cell: str) -> tuple[float, float]:
    m = re.fullmatch(r"\s*(-?[0-9.]+) ± ([0-9.e+-]+)\s*", cell)
    assert m, cell
    x, e = float(m.group(1)), float(m.group(2))
    return x - e, x + e


def test_wave_table_of_the_papers_riemann_run():
    s = simulate.riemann(CubicLaw(-1.0, 10.0), 4.6, 0.0, L=3600, t_end=300)
    text = wave_table(s.waves)
    rows = [r for r in text.splitlines() if r.startswith("| ") and "---" not in r][1:]
    paper = [("superkink", -5.7209, 4.6), ("edge of the dispersive shock", -5.6159, 2.0667),
             ("edge of the dispersive shock", 4.6404, 0.0)]  # fmt: skip
    assert len(rows) == len(paper)
    for row, (name, V, w_B) in zip(rows, paper):
        cells = row.strip("|").split("|")
        assert cells[0].strip() == name
        lo, hi = _interval(cells[1])
        assert lo - 5e-5 <= V <= hi + 5e-5, (row, V)  # the paper's 4 printed decimals
        if w_B:
            lo, hi = _interval(cells[2])
            assert lo - 5e-5 <= w_B <= hi + 5e-5, (row, w_B)
    assert "- **superkink**: a supersonic front" in text
    assert "- **edge of the dispersive shock**: the leading pulse" in text
    assert "dsw_edge" not in text  # the code's name is not shown


def test_value_with_error_rounds_to_the_errors_digits():
    assert fmt_pm(-5.6157663, 7.72e-4) == "-5.61577 ± 7.7e-04"
    assert fmt_pm(4.6, 0.0) == "4.6 ± 0"
    assert fmt_pm(1.0, float("nan")).endswith("± ?")


def test_status_line_velocities_carry_their_errors():
    """The status line printed "-5.61577" for the left DSW edge, whose V is known to 7.7e-4:
    every velocity now comes with its error and the digits the error supports."""
    from types import SimpleNamespace as W

    from app.views.simulation_table import tracked_velocities

    waves = [W(velocity=-5.720916787446, velocity_error=2.6e-12),
             W(velocity=-5.615766265, velocity_error=7.72e-4),
             W(velocity=4.64032987, velocity_error=1.01e-4)]  # fmt: skip
    line = tracked_velocities(waves)
    assert line == ("tracked velocities: -5.720916787446 ± 2.6e-12, -5.61577 ± 7.7e-04, "
                    "4.64033 ± 1.0e-04")  # fmt: skip
    assert tracked_velocities([]) == "tracked velocities: none"
    assert "(and 1 more in the table)" in tracked_velocities(waves * 2, k=5)
