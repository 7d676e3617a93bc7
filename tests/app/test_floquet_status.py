"""The Floquet scene's status: bold headline and sentence come from one decision record, for
each of the four classes, and what they say is true of the numbers drawn in panel (d).

The spectrum is a real one (superkink V = 5.2, N = 128); for each class its decision is replaced
by the record fpucore.floquet.finite_size.decide makes of a synthetic window with that answer
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
    return compute.floquet_spectrum(st.law(), st.mode, st.w_plus, st.V, st.N, st.tol)


@pytest.mark.parametrize("cls", list(WINDOWS))
def test_status_words_agree_with_the_numbers(cls, real, monkeypatch):
    rc, fc = real
    e = WINDOWS[cls]
    err = np.full(e.size, 1e-12)
    d, fit = fs.decide(WIN, e, err, growth_rate=0.01)
    assert d.classification == cls, d.sentence
    fr = dataclasses.replace(
        fc.value, decision=d, classification=cls, verdict=d.sentence,
        finite_size_N=WIN.astype(np.int64), finite_size_excess=e, finite_size_error=err,
        finite_size_exponent=fit["p"], finite_size_exponent_error=fit["p_error"],
    )  # fmt: skip
    monkeypatch.setattr(compute, "floquet_spectrum",
                        lambda *a, **k: (rc, dataclasses.replace(fc, value=fr)))  # fmt: skip
    st = ExplorerState(N=N, tol=1e-8)
    sc = BY_KEY["floquet"](st)
    sc.panel.get_root(Document())
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    status = sc.status.object
    bold = [b for b in re.findall(r"\*\*(.+?)\*\*", status) if b != "Shown:"]
    assert bold[0] == d.headline and f"**{d.headline}**: {d.sentence}" in status
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
    for p, dp in re.findall(r"p = ([-\d.]+) ± ([-\d.]+)", title):
        assert float(dp) < abs(float(p))
