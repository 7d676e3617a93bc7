"""The exported Floquet figure draws the unit circle round: the complex plane's fixed square
frame (app.views.floquet.square_figure) keeps its proportions in the Matplotlib export (it was
drawn 360 × 300 px for the same x and y spans: an ellipse)."""

from __future__ import annotations

import io

import numpy as np
import pytest

pytest.importorskip("panel")
matplotlib = pytest.importorskip("matplotlib")

from matplotlib.figure import Figure  # noqa: E402

from app.views import export  # noqa: E402
from app.views.floquet import square_figure  # noqa: E402


def test_the_square_frame_stays_square_in_a_wide_export():
    fig = square_figure("multipliers")
    th = np.linspace(0, 2 * np.pi, 200)
    fig.line(np.cos(th), np.sin(th))
    fig.x_range.start, fig.x_range.end = -1.2, 1.2
    fig.y_range.start, fig.y_range.end = -1.2, 1.2
    mfig = Figure(figsize=(10, 3), dpi=100)
    ax = mfig.add_subplot(1, 1, 1)
    export.draw_figure(ax, fig)
    mfig.savefig(io.BytesIO(), format="png")  # drawn as the export draws it
    # the circle itself: its drawn width and height in pixels agree
    pts = ax.transData.transform(np.c_[np.cos(th), np.sin(th)])
    assert np.ptp(pts[:, 0]) == pytest.approx(np.ptp(pts[:, 1]), rel=0.01)
