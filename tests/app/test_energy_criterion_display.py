"""The energy criterion on the Diagrams and Floquet scenes, without a browser.

References: the QC energy E_ren^QC (eq. Eren_QC) on a dense grid of the closed form (its
minimum on the soft family w₊ = −0.04 of a = −1, b = 10, near V ≈ 0.759; monotone on the paper's
family w₊ = 1, Fig. SWamp_energy_QCcubic); the discrete minimum of the same soft family located
from a continued family of other velocities (fpucore.floquet.energy_criterion).
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from fpucore import floquet as fq  # noqa: E402
from fpucore import qc  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}
LAW = CubicLaw(-1.0, 10.0)
W_SOFT = -0.04


def attached(key: str, **params):
    st = ExplorerState(**params)
    sc = BY_KEY[key](st)
    sc.panel.get_root(Document())
    return st, sc


def qc_minimum_on_a_dense_grid() -> float:
    grid = np.linspace(0.74, 0.78, 4001)  # spacing 1e-5
    return float(grid[np.argmin([qc.solitary(LAW, W_SOFT, v).energy for v in grid])])


def test_diagram_marks_the_qc_energy_minimum_with_its_error():
    st, sc = attached("diagram", w_plus=W_SOFT, V=0.7)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    d = sc.ext_qc.src.data
    assert len(d["x"]) == 1 and abs(d["x"][0] - qc_minimum_on_a_dense_grid()) < 2e-5
    dv = d["right"][0] - d["x"][0]
    assert 0 < dv < 1e-5 and "±" in d["label"][0] and "minimum" in d["label"][0]
    assert sc.ext_qc.line.visible and sc.ext_legend[0].visible
    assert "E_ren^QC minimum at V = 0.7591" in sc.ext_legend[0].label["value"]
    status = sc.status.object
    assert "has a minimum at V = 0.7591" in status and "stability can change only there" in status
    assert "E_ren^QC extremum location" in status  # its error bar in the error line
    assert not sc.ext_d.line.visible  # no discrete dots asked for: no discrete extremum
    assert "E_QC_extremum_V" in sc.download_data()[1].getvalue()


def test_diagram_says_so_when_the_family_has_no_extremum():
    _, sc = attached("diagram", w_plus=1.0, V=5.0)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    assert len(sc.ext_qc.src.data["x"]) == 0 and not sc.ext_qc.line.visible
    assert not sc.ext_legend[0].visible
    assert "has no minimum or maximum between c₊ and c₋" in sc.status.object


def test_sweep_energy_check_locates_the_discrete_minimum_from_the_sweeps_own_waves():
    Vs = [0.66, 0.71, 0.76, 0.81, 0.86]
    lw = compute.laws.law(-1.0, 10.0)
    req = compute.SweepRequest("solitary", W_SOFT, Vs, 100)
    check = compute.SampledEnergyRequest(req)
    assert compute.run(lw, check) is None  # nothing swept: nothing
    compute.run(lw, req)
    c = compute.run(lw, check)
    ec, changes = c.value
    assert ec.extrema_kind == ("min",) and ec.qc_extrema_kind == ("min",)
    ref = fq.energy_criterion(LAW, W_SOFT, np.linspace(0.72, 0.82, 5), N=100, qc_samples=0)
    assert abs(ec.extrema_V[0] - ref.extrema_V[0]) <= ec.extrema_V_error[0] + ref.extrema_V_error[0]
    assert abs(ec.qc_extrema_V[0] - qc_minimum_on_a_dense_grid()) < 2e-5
    assert all(ch.explained for ch in changes)
    assert compute.run(lw, check).cached


def test_floquet_sweep_panel_shows_the_criterion_and_the_cross_check():
    st, sc = attached("floquet", w_plus=1.0, V=5.0, N=100, tol=1e-8)
    sc.n_sweep.value = 6  # total: 3 per interval
    sc._want_sweep = True  # what the Sweep button sets
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    assert sc.fig_c.visible
    status = sc.status.object
    # E_ren^QC is monotone on both intervals at w₊ = 1 (dense-grid check in tests/floquet)
    assert "neither along the sweep's discrete waves nor in the QC family" in status
    assert not sc.ext_q.line.visible and not sc.sw_legend[2].visible
    sw = sc._sweep_result
    assert list(sw.classification) and all(c in fq.CLASSES for c in sw.classification)
    unstable = [c == "unstable" for c in sw.classification]
    (lo1, hi1), (lo2, hi2) = qc.solitary_intervals(LAW, 1.0)
    crossings = 0
    for lo, hi in ((lo1, hi1), (lo2, hi2)):
        u = [x for x, v in zip(unstable, sw.V) if lo < v < hi]
        crossings += sum(p != q for p, q in zip(u, u[1:]))
    # the paper's figure: max|μ| − 1 on a log axis, every point in the colour of its decision
    assert type(sc.fig_c.y_scale).__name__ == "LogScale" and sc.fig_c.y_range.start > 0
    for c in fq.CLASSES:
        drawn = sorted(sc.r_cls[c][1].data["x"])
        assert np.allclose(drawn, sorted(v for v, k in zip(sw.V, sw.classification) if k == c))
    # the cross-check is one line, never one paragraph per change
    assert status.count("Cross-check") == 1
    if sc._ec[0].extrema_V.size == 0 and crossings:
        # no extremum anywhere: every crossing of the stable/unstable line is a finite-size effect
        assert f"{crossings} change" in status and "none at an extremum of E_ren" in status
    if crossings == 0:
        assert "No change between stable and unstable along the sweep" in status
    code = sc.python_code()
    assert "criterion_from_samples" in code and "stability_changes" in code


def test_diagram_marks_the_discrete_minimum_once_its_dots_exist():
    """20 dots per interval put one next to the minimum (0.549, 0.766, 0.984, …): the discrete
    E_ren's minimum is marked (dashed) within its error bar plus the measured QC–discrete
    deviation (≤ 2 %, fpucore.floquet.energy.QC_DISCRETE_ALLOWANCE) of the QC one."""
    st, sc = attached("diagram", w_plus=W_SOFT, V=0.7, N=200, tol=1e-8)
    sc.n_discrete.value = 20
    sc.refresh()
    assert not sc.ext_d.line.visible  # not asked for yet: no discrete waves, no mark
    sc._want_discrete = True  # what the button sets
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    d = sc.ext_d.src.data
    assert len(d["x"]) == 1 and sc.ext_d.line.visible and sc.ext_legend[1].visible
    dv = d["right"][0] - d["x"][0]
    v_qc = qc_minimum_on_a_dense_grid()
    assert abs(d["x"][0] - v_qc) <= dv + fq.energy.QC_DISCRETE_ALLOWANCE * v_qc
    assert "E_ren(V) of the discrete dots has a minimum" in sc.status.object
    assert (
        compute.run(
            st.law(),
            compute.SampledEnergyRequest(compute.FamilyRequest(st.w_plus, [0.5, 0.6], 200, 1e-8)),
        )
        is None
    )  # not cached
