"""The Floquet scene's status: bold headline and sentence come from one decision record, for
each of the four classes, and what they say is true of the numbers drawn in panel (d).

The spectrum is a real one (superkink V = 5.2, N = 128); for each class its decision is replaced
by the record fpucore.floquet.decision.decide makes of a synthetic window with that answer
(the same windows as tests/floquet/test_decision.py), so the scene renders every class.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from benchmarks.verdict_audit import audit_sentence  # noqa: E402
from fpucore.floquet import decision  # noqa: E402
from fpucore.floquet import finite_size as fs  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}
N = 128
WIN = np.array(fs.chain_lengths(N, 64) + [N], float)
SAW = np.array([1.0, 0.35, 0.9, 0.55, 1.0, 0.95])
WINDOWS = {
    "stable": np.r_[np.full(WIN.size - 1, 1e-3), 1e-14],
    "finite_size": 0.3 / WIN * SAW,
    "unstable": np.full(WIN.size, 1e-3),
    "undetermined": np.linspace(3e-5, 7e-5, WIN.size),
}


@pytest.fixture(scope="module")
def real():
    st = ExplorerState(N=N, tol=1e-8)
    wave = compute.WaveRequest(st.mode, st.w_plus, st.V, st.N, st.tol)
    return compute.run(st.law(), compute.SpectrumRequest(wave)).value


@pytest.mark.parametrize("cls", list(WINDOWS))
def test_status_words_agree_with_the_numbers(cls, real, monkeypatch):
    rc, fc = real
    e = WINDOWS[cls]
    err = np.full(e.size, 1e-12)
    d, fit = decision.decide(WIN, e, err, growth_rate=0.01)
    assert d.classification == cls, d.sentence
    fr = dataclasses.replace(
        fc.value, decision=d, classification=cls, verdict=d.sentence,
        finite_size_N=WIN.astype(np.int64), finite_size_excess=e, finite_size_error=err,
        finite_size_exponent=fit["p"], finite_size_exponent_error=fit["p_error"],
    )  # fmt: skip
    pair = compute.Computed((rc, dataclasses.replace(fc, value=fr)), 0.0, True)
    monkeypatch.setattr(compute, "run", lambda *a, **k: pair)
    st = ExplorerState(N=N, tol=1e-8)
    sc = BY_KEY["floquet"](st)
    sc.panel.get_root(Document())
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    status = sc.status.object
    bold = [b for b in re.findall(r"\*\*(.+?)\*\*", status) if b != "Shown:"]
    # the headline, then the sentence's evidence (its first words are the headline's: not twice)
    assert bold[0] == d.headline and f"**{d.headline}**: {d.evidence}" in status
    head = d.sentence[: len(d.sentence) - len(d.evidence)]
    assert head == "" or f"**{d.headline}**: {head}" not in status
    # every word of the rendered headline and sentence agrees with the numbers printed in it
    shown = head + status.split(f"**{bold[0]}**: ", 1)[1].split("\n")[0]
    assert audit_sentence(shown, bold[0], cls) == [], shown
    # the headline's first word is the sentence's
    assert d.sentence.split(":")[0].split()[0] == d.headline.split()[0]
    # (d) draws exactly the points the sentence quotes
    drawn = np.asarray(sc.r_fs[1].data["y"], float)
    assert np.array_equal(drawn, e)
    quoted = [float(x) for x in re.findall(r"\d: (\d\.\d+e[-+]\d+)", d.sentence)]
    if cls != "stable":
        assert np.allclose(quoted, e, rtol=6e-3)
    if cls == "stable":
        assert e[-1] <= err[-1] and "within the error bar" in status
    elif cls == "finite_size":
        k = list(d.points_N).index(d.dip_N[0])  # the dip the headline's words rest on
        assert e[k] < 0.5 * min(e[:k].max(), e[k + 1 :].max()) and "comes and goes" in d.headline
    elif cls == "unstable":
        assert np.ptp(e) <= 0.1 * e[-1] and "persists" in d.headline
    else:
        assert np.ptp(e) > 0.1 * e[-1] and e[-1] == e.max()  # neither converged nor decaying
        assert f"compute at N >= {2 * N}" in status
    title = sc.fig_d.title.text
    for p, dp in re.findall(r"p = ([-\d.]+) ± ([-\d.e+]+)", title):
        assert float(dp) < abs(float(p))


def test_sweep_panel_says_which_velocities_are_missing_and_why(real, monkeypatch):
    """A sweep row left out of (c) is named for what happened to it: a wave that did not
    converge, or a velocity never computed (a sweep stopped early) — the old note called every
    missing row "did not converge"."""
    from app.compute.cache import Computed
    from fpucore.atlas import sweeps
    from fpucore.atlas.point import empty_record
    from fpucore.result import jsonable

    rc, fc = real
    V = np.array([5.0, 5.2, 5.4])

    def row(V, status, message, **fields):  # a sweep row: V and its atlas record
        return {"V": V, **jsonable(empty_record(status, message)), **fields}

    rows = [
        row(5.0, "not_converged", "Newton stalled", N=N),  # the wave did not converge
        row(5.2, "", "time budget of 1 s exceeded after 1 of 3 velocities"),  # never computed
        row(5.4, "ok", "", N=N, converged=True, floquet_converged=True, max_modulus=1.0005,
            max_modulus_away_from_1=1.0005, max_modulus_error=1e-11, n_unstable=2,
            classification="finite_size", verdict="x", headline="finite-size artefact (x)"),
    ]  # fmt: skip
    nan2 = [np.nan, np.nan]
    sw = sweeps.SweepResult(
        kind="superkink", N=N, w_plus=None, method="structured", V=V,
        max_modulus=np.array([*nan2, 1.0005]), max_modulus_away_from_1=np.array([*nan2, 1.0005]),
        max_modulus_error=np.array([*nan2, 1e-11]), n_unstable=np.array([0, 0, 2]),
        floquet_converged=np.array([False, False, True]), cached=np.zeros(3, bool),
        energy=np.full(3, np.nan), energy_error=np.full(3, np.nan),
        classification=("", "", "finite_size"), rows=rows, converged=False, stopped=True,
        message="time budget", elapsed_s=0.1,
    )  # fmt: skip

    real_run = compute.run

    def run(lw, req, **kw):  # the spectrum as computed, the sweep above
        if isinstance(req, compute.SpectrumRequest):
            return Computed((rc, fc), 0.1, True)
        if isinstance(req, compute.SampledEnergyRequest):  # the sweep above is not cached
            return real_run(lw, req, **kw)
        return Computed(sw, 0.1, False)

    monkeypatch.setattr(compute, "run", run)
    st = ExplorerState(N=N, tol=1e-8)
    sc = BY_KEY["floquet"](st)
    sc.panel.get_root(Document())
    sc.n_sweep.value = 3
    sc._want_sweep = True
    sc.refresh()
    status = sc.status.object
    assert "sweep: 1 velocity did not converge" in status
    assert "sweep: 1 of 3 velocities not computed (not drawn): time budget" in status
    assert sum(len(src.data["x"]) for _, src in sc.r_cls.values()) == 1


MEASURED = {  # README superkink sweep (measured windows): a rise then a fall, a slow fall, 1/N
    "V5.6-N500": ([250, 300, 350, 400, 450, 500],
                  [3.97e-05, 7.25e-05, 8.40e-05, 8.07e-05, 9.68e-05, 6.20e-05]),
    "V5.3-N200": ([100, 120, 140, 160, 180, 200],
                  [9.97e-04, 1.03e-03, 9.63e-04, 8.81e-04, 8.89e-04, 8.09e-04]),
    "V4.8-N500": ([250, 300, 350, 400, 450, 500],
                  [7.60e-03, 6.36e-03, 5.47e-03, 4.81e-03, 4.28e-03, 3.86e-03]),
}  # fmt: skip


@pytest.mark.parametrize("key", list(MEASURED))
def test_measured_windows_render_words_that_agree(key, real, monkeypatch):
    rc, fc = real
    n, e = (np.asarray(x, float) for x in MEASURED[key])
    err = np.full(e.size, 1e-10)
    d, fit = decision.decide(n, e, err, growth_rate=0.01)
    fr = dataclasses.replace(
        fc.value, decision=d, classification=d.classification, verdict=d.sentence,
        finite_size_N=n.astype(np.int64), finite_size_excess=e, finite_size_error=err,
        finite_size_exponent=fit["p"], finite_size_exponent_error=fit["p_error"],
    )  # fmt: skip
    pair = compute.Computed((rc, dataclasses.replace(fc, value=fr)), 0.0, True)
    monkeypatch.setattr(compute, "run", lambda *a, **k: pair)
    sc = BY_KEY["floquet"](ExplorerState(N=N, tol=1e-8))
    sc.panel.get_root(Document())
    sc.refresh()
    status = sc.status.object
    head = d.sentence[: len(d.sentence) - len(d.evidence)]  # the words the headline says
    shown = head + status.split(f"**{d.headline}**: ", 1)[1].split("\n")[0]
    assert audit_sentence(shown, d.headline, d.classification) == [], shown
    title = sc.fig_d.title.text
    assert not re.search(r"± 0\.0*(?![\d.])", title)  # no zero error bar (two-point line)
    for p, dp in re.findall(r"p = ([-\d.]+) ± ([-\d.e+]+)", title):
        assert 0 < float(dp) < abs(float(p))
