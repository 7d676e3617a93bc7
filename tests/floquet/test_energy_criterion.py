"""Energy criterion (Friesecke–Pego type): extrema of E_ren(V) along solitary families, where a
change of stability may occur, cross-checked against the three-way classification.

What we find (stated in the assertions): for the paper's families (w₊ = 1, 6) E_ren and E_ren^QC
are monotone on each velocity interval — no extremum, and the classification along a sweep never
says "unstable" (stable or finite-size artefact), consistent with the criterion.  Near the soft
end of the convex interval (w₊ = −0.04, α = −0.0496) both E_ren and E_ren^QC have a minimum near
V ≈ 0.76–0.77; the spectra on both sides of it are finite-size artefacts only and the
translation pair stays on the unit circle: no change of stability is seen across the extremum
(the criterion is necessary, not sufficient).

Cross-check along sweeps (fpucore.atlas.sweep at N = 200, its rows carry each wave's E_ren and
classification; fpucore.floquet.stability_changes): every change across the stable/unstable line
between neighbouring velocities must lie at an extremum of E_ren.  Measured: at N = 200 there is
no such change on the three families tested.  (At N = 100 the three-ring finite-size test —
rings 64, 82, 100 — calls w₊ = 1, V = 5.1 "unstable" between two stable/finite-size
neighbours, with no extremum anywhere: the cross-check flags exactly this kind of
misclassification; it is not asserted here because it depends on the finite-size test's
details.)
"""

from __future__ import annotations

import numpy as np
import pytest

from fpucore import atlas, qc, wave
from fpucore import floquet as fq
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.parallel import Executor

LAW = CubicLaw(-1.0, 10.0)
W_SOFT = -0.04


def test_locate_extrema_on_a_known_parabola():
    V = np.linspace(0.0, 1.0, 11)
    E = 3.0 * (V - 0.437) ** 2 - 1.0
    (v, dv, e, kind), = fq.energy.locate_extrema(V, E, np.full(V.size, 1e-12))  # fmt: skip
    assert kind == "min" and abs(v - 0.437) < 1e-12 and abs(e + 1.0) < 1e-12
    assert 2 * np.sqrt(1e-12 / 6.0) <= dv < 1e-5  # the δE term, parabola exact
    assert fq.energy.locate_extrema(V, V**3, np.zeros(V.size)) == []  # monotone: none


@pytest.mark.parametrize("w_plus", [1.0, 6.0])
def test_paper_families_have_no_energy_extremum_qc(w_plus):
    ec = fq.energy_criterion(LAW, w_plus)
    assert ec.qc_extrema_V.size == 0 and not ec.stability_may_change
    # independent check of the same statement: the QC energy is monotone on a dense grid
    for lo, hi in qc.solitary_intervals(LAW, w_plus):
        V = np.linspace(lo, hi, 2002)[1:-1]
        d = np.diff([qc.solitary(LAW, w_plus, v).energy for v in V])
        assert np.all(d > 0) or np.all(d < 0)


def test_paper_family_sweep_is_consistent_with_no_extremum():
    """w₊ = 1, tensile interval: no extremum of the discrete E_ren, and no velocity classified
    "unstable" along the sweep (N = 200)."""
    ec = fq.energy_criterion(LAW, 1.0, [4.6, 4.9, 5.1, 5.3])
    assert ec.converged and ec.extrema_V.size == 0 and not ec.stability_may_change
    assert np.all(np.diff(ec.energy) > ec.energy_error[1:] + ec.energy_error[:-1])
    classes = []
    for V in (4.6, 5.0, 5.3):
        fr = fq.spectrum(wave.solve_solitary(LAW, 1.0, V, N=200))
        classes.append(fr.classification)
    assert "unstable" not in classes, classes
    assert classes[-1] == "finite_size"  # the mild spurious instabilities near V_SK (§6.2)


@pytest.fixture(scope="module")
def soft_coarse():
    return fq.energy_criterion(LAW, W_SOFT, np.linspace(0.65, 0.85, 5))


def test_soft_family_has_an_energy_minimum(soft_coarse):
    ec = soft_coarse
    assert ec.converged and ec.stability_may_change
    assert ec.extrema_kind == ("min",) and ec.qc_extrema_kind == ("min",)
    # QC minimum against a brute-force dense grid of the closed form (spacing 1e-5)
    grid = np.linspace(0.74, 0.78, 4001)
    e = np.array([qc.solitary(LAW, W_SOFT, v).energy for v in grid])
    assert abs(ec.qc_extrema_V[0] - grid[np.argmin(e)]) < 2e-5
    assert ec.qc_extrema_V_error[0] < 1e-5
    # discrete minimum: halving the V spacing moves it by less than the two error bars, and the
    # error bar shrinks (parabola truncation ∝ h²)
    fine = fq.energy_criterion(LAW, W_SOFT, np.linspace(0.72, 0.82, 5))
    assert fine.extrema_kind == ("min",)
    v1, e1 = ec.extrema_V[0], ec.extrema_V_error[0]
    v2, e2 = fine.extrema_V[0], fine.extrema_V_error[0]
    assert abs(v1 - v2) <= e1 + e2 and e2 < 0.3 * e1
    # discrete and QC minima are close (QC is an approximation of the chain: ~1 %)
    assert abs(v2 - ec.qc_extrema_V[0]) < 0.02
    d = ec.as_dict()
    for k in ("extrema_V", "extrema_V_error", "extrema_kind", "qc_extrema_V",
              "qc_extrema_V_error", "qc_V", "qc_energy", "stability_may_change"):  # fmt: skip
        assert k in d
    assert "family" not in d


def test_classification_across_the_soft_minimum(soft_coarse):
    """Both sides of the E_ren minimum: finite-size artefacts only, translation pair on the
    circle — no change of stability detected across the extremum."""
    v_star = soft_coarse.extrema_V[0]
    for V in (0.65, 0.85):
        assert abs(V - v_star) > 3 * soft_coarse.extrema_V_error[0]
        fr = fq.spectrum(wave.solve_solitary(LAW, W_SOFT, V, N=200))
        assert fr.classification == "finite_size", fr.verdict
        assert fr.n_trivial == 4
        assert np.all(np.abs(np.abs(fr.trivial) - 1.0) < 1e-10)


@pytest.mark.parametrize("w_plus", [1.0, 6.0, W_SOFT])
def test_qc_grid_is_the_scalar_closed_form(w_plus):
    """The criterion's QC grid (one vectorised closed form per interval, background w_S(V) above
    V_SK) against fpucore.qc.solitary one velocity at a time, within its round-off bound."""
    for lo, hi in qc.solitary_intervals(LAW, w_plus):
        V, E, dE = fq.energy.qc_energy_grid(LAW, w_plus, lo, hi, 50)
        for i in (0, 17, 49):
            s = qc.solitary(LAW, w_plus, float(V[i]))
            assert abs(E[i] - s.energy) <= dE[i] + s.energy_error, (w_plus, V[i])


def test_bad_input():
    with pytest.raises(ParameterError, match="w_plus"):
        fq.energy_criterion(LAW, float("nan"))
    with pytest.raises(ParameterError, match="qc_samples"):
        fq.energy_criterion(LAW, 1.0, qc_samples=2)


def test_stability_changes_on_synthetic_samples():
    """The checker on known samples: a parabola with its minimum at 0.76 explains a change
    between 0.71 and 0.81; a monotone E explains nothing; stable ↔ finite_size is no change."""
    V = np.array([0.66, 0.71, 0.81, 0.86])
    ok = np.ones(V.size, bool)
    par = fq.criterion_from_samples(LAW, W_SOFT, V, (V - 0.76) ** 2, np.full(4, 1e-14), ok, 0)
    mono = fq.criterion_from_samples(LAW, W_SOFT, V, V**3, np.full(4, 1e-14), ok, 0)
    assert par.extrema_kind == ("min",) and mono.extrema_V.size == 0
    assert par.qc_V.size == 0  # qc_samples = 0: the QC family is skipped
    cls = ["stable", "unstable", "finite_size", "finite_size"]
    (ch1, ch2) = fq.stability_changes(LAW, W_SOFT, V, cls, par)  # fmt: skip
    assert (ch1.V_from, ch1.V_to, ch1.explained) == (0.66, 0.71, False)
    assert (ch2.V_from, ch2.V_to, ch2.explained) == (0.71, 0.81, True)
    assert abs(ch2.extremum_V - 0.76) < 1e-9
    assert not any(c.explained for c in fq.stability_changes(LAW, W_SOFT, V, cls, mono))
    assert fq.stability_changes(LAW, W_SOFT, V, ["stable", "finite_size"] * 2, mono) == []
    with pytest.raises(ParameterError, match="classification"):
        fq.stability_changes(LAW, W_SOFT, V, cls[:3], par)


SWEEPS = [
    (1.0, [4.4, 4.8, 5.0, 5.2, 5.3]),  # tensile interval (c₊ = 4.243, V_SK = 5.375)
    (6.0, [3.8, 4.4, 5.0, 5.3, 5.38]),  # both intervals (c₊ = 3.606, V_SK = 5.217, c₋ = 5.385)
    (W_SOFT, [0.66, 0.71, 0.76, 0.81, 0.86]),  # across the E_ren minimum near 0.76
]


@pytest.mark.parametrize("w_plus, Vs", SWEEPS)
def test_classification_along_a_sweep_changes_only_at_an_energy_extremum(
    w_plus, Vs, tmp_path, monkeypatch, soft_coarse
):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    sw = atlas.sweep(LAW, "solitary", Vs, w_plus=w_plus, N=200, executor=Executor("inline"),
                  use_cache=False)  # fmt: skip
    assert sw.converged and all(c in fq.CLASSES for c in sw.classification)
    # the rows' energies are the waves' own: one direct solve at the same V and N
    r = wave.solve_solitary(LAW, w_plus, Vs[1], N=200)
    assert abs(sw.energy[1] - r.energy) <= sw.energy_error[1] + r.energy_error
    ec = fq.criterion_from_samples(
        LAW, w_plus, sw.V, sw.energy, sw.energy_error, sw.floquet_converged
    )
    changes = fq.stability_changes(LAW, w_plus, sw.V, sw.classification, ec)
    assert all(ch.explained for ch in changes), (sw.classification, changes)
    if ec.extrema_V.size == 0 and ec.qc_extrema_V.size == 0:
        assert "unstable" not in sw.classification, sw.classification
    if w_plus == W_SOFT:
        # the sweep's own waves locate the minimum where the continued family does (other
        # velocities, other solves): within the two error bars
        assert ec.extrema_kind == ("min",)
        assert abs(ec.extrema_V[0] - soft_coarse.extrema_V[0]) <= (
            ec.extrema_V_error[0] + soft_coarse.extrema_V_error[0]
        )
    else:
        assert ec.extrema_V.size == 0 and ec.qc_extrema_V.size == 0
