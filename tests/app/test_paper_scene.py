"""The Paper scene: one entry per figure of the paper, and a click sets the explorer's state to
the scene that shows the figure (checked against the paper's parameters and closed forms)."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("panel")

import panel as pn  # noqa: E402

from app.explorer import Explorer  # noqa: E402
from app.state import TABS, ExplorerState
from app.url_state import url_query
from app.views.formatting import fmt_num  # noqa: E402
from app.views.paper import (  # noqa: E402
    FIGURE_STATE,
    FIGURES_DIR,
    SHOWN_WIDTH,
    W_PLUS_5_2,
    PaperScene,
    comparison_markdown,
    docs_table,
)
from app.views.untrusted import md_literal  # noqa: E402
from fpucore import paper  # noqa: E402
from fpucore.paper import report  # noqa: E402


def v_sk(w_plus: float, a: float = -1.0, b: float = 10.0) -> float:
    """The paper's eq. cubic_cond2, evaluated independently of fpucore."""
    return math.sqrt(1 + b * b / (3 * abs(a)) - abs(a) * (w_plus - b / (3 * abs(a))) ** 2)


def test_every_figure_has_a_state_and_a_button():
    ex = Explorer()
    sc = ex.by_key["paper"]
    assert "paper" in TABS and set(FIGURE_STATE) == set(paper.LABELS)
    assert list(sc.buttons) == list(paper.LABELS)
    assert sc.buttons["Riemann1"].name == "Show Fig. 14"


def test_the_superkink_of_the_papers_examples():
    assert v_sk(W_PLUS_5_2) == pytest.approx(5.2, abs=1e-12)
    assert v_sk(20 / 3 - 4.6) == pytest.approx(5.7209, abs=5e-5)  # Fig. Riemann1's superkink


@pytest.mark.parametrize(
    "label, tab, mode, V",
    [
        ("pplane", "phase", "solitary", 2 * math.sqrt(65) / 3 - 0.001),
        ("Floquet_example", "floquet", "superkink", 5.2),
        ("stabSW", "simulation", "solitary", 5.2174919476),
        ("Riemann1", "simulation", "superkink", 5.720916787),
        ("superkink", "force", "superkink", 2 * math.sqrt(65) / 3),
    ],
)
def test_a_click_sets_law_mode_V_tab_and_url(label, tab, mode, V):
    ex = Explorer()
    ex.state.param.update(a=-2.0, b=12.0, mode="solitary", V=4.0, w_plus=0.5, N=200)
    ex.by_key["paper"].buttons[label].clicks += 1  # the user clicks
    st = ex.state
    assert (st.a, st.b, st.expression, st.mode, st.tab) == (-1.0, 10.0, "", mode, tab)
    # the seeded figures solve fpucore.paper's wave (N = 64, tol 1e-12), the others N = 500
    N, tol = (64, 1e-12) if label in ("stabSK", "stabSW") else (500, 1e-10)
    assert st.V == pytest.approx(V, abs=1e-9) and (st.N, st.tol) == (N, tol)
    assert st.problem() is None  # a valid wave: the scene shows it
    assert TABS[ex.tabs.active] == tab
    q = url_query(st)
    assert q["tab"] == tab and q["mode"] == mode and float(q["V"]) == pytest.approx(V, abs=1e-9)


def test_each_figure_gives_a_valid_state():
    ex = Explorer()
    for label in FIGURE_STATE:
        ex.by_key["paper"].open(label)
        assert ex.state.problem() is None, label


def test_a_figure_computed_by_fpu_paper_shows_its_comparison_row(tmp_path, monkeypatch):
    """The row under a figure is the cached fpu paper result's comparisons (paper vs ours);
    a figure not computed yet names the command instead."""

    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    sc = PaperScene(ExplorerState())
    sc.refresh()
    assert "fpu paper --figure pplane" in sc.cmp_panes["pplane"].object
    (r,), missing, _ = report.compute_many(["pplane"], reduced=True, workers=1)
    assert not missing
    sc.refresh()  # the next render finds it
    row = sc.cmp_panes["pplane"].object
    assert f"{r.n_agree}/{len(r.comparisons)} agree" in row
    for c in r.comparisons:  # V_SK = 2√65/3 and w₋ = 17/3 beside ours
        assert f"paper {c.printed}" in row and f"{c.ours:.8g}" in row
    assert v_sk(1.0) == pytest.approx(r.comparisons[0].ours, abs=1e-12)
    assert "fpu paper --figure superkink" in sc.cmp_panes["superkink"].object


def test_the_list_shows_every_figures_committed_thumbnail_embedded():
    """One thumbnail per figure beside its caption, at a fixed width, its bytes inside the page
    (a data: URL — no request to the server's files or to another host)."""
    sc = PaperScene(ExplorerState())
    sc.refresh()
    thumbs = [p for p in sc.plot.select(pn.pane.PNG) if "paper-thumb" in p.css_classes]
    assert len(thumbs) == len(paper.LABELS) == 17
    for label, p in zip(paper.LABELS, thumbs, strict=True):
        assert f"paper-thumb-{label}" in p.css_classes and p.width == SHOWN_WIDTH
        assert p.object == (FIGURES_DIR / f"{label}.png").read_bytes()  # package data
        html = p._transform_object(p.object)["object"]
        assert "data:image/png;base64," in html and "http" not in html


def test_without_a_cached_run_the_row_is_the_committed_docs_row(tmp_path, monkeypatch):
    """No fpu paper run cached for this source: each row shows docs/paper_comparison.json's
    numbers, said to come from docs/ with the fpucore version that wrote them."""
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    doc = docs_table()
    assert set(doc["figures"]) == set(paper.LABELS)
    sc = PaperScene(ExplorerState())
    sc.refresh()
    for label in paper.LABELS:
        row = sc.cmp_panes[label].object
        comps = doc["figures"][label]["comparisons"]
        ok = sum(c["agrees"] for c in comps)
        assert f"**{ok}/{len(comps)} agree** (from docs/, fpucore {doc['fpucore_version']}" in row
        assert f"fpu paper --figure {label}" in row  # how to compute it here instead
        for c in comps:
            assert f"paper {md_literal(c['printed'])}, ours {fmt_num(c['ours'], 8)}" in row
    # V_SK = 2√65/3 beside the paper's closed form, from the docs
    assert f"ours {fmt_num(v_sk(1.0), 8)}" in sc.cmp_panes["pplane"].object
    assert "0 computed here" in sc.last_info.shown and "17 from docs/" in sc.last_info.shown


def test_without_docs_the_row_names_the_command(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    row = comparison_markdown("pplane", None, {})
    assert "not compared yet" in row and "fpu paper --figure pplane" in row
