"""The trilinear family's figures (fpucore.paper.registry_trilinear): every figure computes in
reduced mode with finite panels and rows that agree; the references (closed forms written out in
figures_trilinear) are checked against the equal-area and Rayleigh conditions themselves; the
CLI lists the family, writes one figure and refuses bad input by name."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fpucore import qc
from fpucore.cli.dispatch import main
from fpucore.law import TrilinearLaw
from fpucore.paper import figures_trilinear as ft
from fpucore.paper import registry_trilinear as reg
from fpucore.paper.report import family


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))


@pytest.mark.parametrize("label", reg.LABELS)
def test_every_trilinear_figure_computes_reduced_and_its_rows_agree(label):
    r = reg.compute(label, reduced=True)
    assert r.label == label and r.reduced and r.converged
    assert r.comparisons, "every figure carries rows checked against a reference"
    for c in r.comparisons:
        assert c.agrees, (c.quantity, c.why)
        assert math.isfinite(c.ours) and math.isfinite(c.error)
    assert r.panels
    for p in r.panels:
        assert p.series
        for s in p.series:
            if s.style in ("line", "dashed", "points"):
                assert s.x.shape == s.y.shape
                assert np.isfinite(s.y).any(), (p.title, s.label)


@pytest.mark.parametrize("w_plus", [-1.0, 0.0, 0.3, 0.45])
@pytest.mark.parametrize("e3", [0.0, 0.2, 2.0])
def test_the_closed_form_references_satisfy_equal_areas_and_the_rayleigh_line(w_plus, e3):
    """The written-out w₋, V_SK (figures_trilinear.closed_forms) against the conditions that
    define them, evaluated on the law object: equal areas ∫(f − R) = 0 (exact trapezoid on the
    corners) and R(w₋) = f(w₋); and against fpucore.qc.  With E₃ = 2 > E₁ the lower branch is
    w₊ > w₁ − (E₂ − E₃)(w₂ − w₁)/(E₃ − E₁) = −1.5: every w₊ here is inside it."""
    law = TrilinearLaw(ft.W1, ft.W2, ft.E1, ft.E2, e3)
    cf = ft.closed_forms(w_plus, ft.E1, e3)
    wm, V = cf["w_minus"], cf["V_SK"]
    assert wm > ft.W2
    nodes = np.array([w_plus, ft.W1, ft.W2, wm])
    gap = law.f(nodes) - (law.f(w_plus) + V**2 * (nodes - w_plus))
    area = np.sum(0.5 * (gap[1:] + gap[:-1]) * np.diff(nodes))
    assert abs(area) <= 1e-13 * np.sum(np.abs(gap)) * (wm - w_plus)
    assert abs(gap[-1]) <= 1e-13 * abs(law.f(wm))
    sk = qc.superkink_from_w_plus(law, w_plus)
    assert abs(sk.V - V) <= 1e-13 and abs(sk.w_minus - wm) <= 1e-12


def test_a_wrong_reference_disagrees():
    """The rows can fail: the speed rows of another law (E₃ = 0.5) against this figure's
    references disagree."""
    other = ft.closed_forms(ft.W_PLUS, ft.E1, 0.5)
    rows = {c.quantity: c for c in ft.speed_rows("tri_law")}
    vsk = rows[f"V_SK at w₊ = {ft.W_PLUS:g}"]
    assert abs(vsk.ours - other["V_SK"]) > 100 * vsk.error


def test_bad_family_or_label_refused_by_name():
    with pytest.raises(Exception, match="family='cubic'"):
        family("cubic")
    with pytest.raises(Exception, match="tri_law"):
        reg.figure("pplane")


def test_cli_lists_the_family(capsys):
    assert main(["paper", "--family", "trilinear", "--list"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert len(lines) == len(reg.LABELS) == 6
    assert "tri_law" in lines[0] and "tri_riemann" in lines[-1]


def test_cli_writes_one_figure_with_its_rows(tmp_path, capsys):
    out = tmp_path / "tri_compact.html"
    assert main(["paper", "--family", "trilinear", "--figure", "tri_compact", "--reduced",
                 "--workers", "1", "--out", str(out)]) == 0  # fmt: skip
    html = out.read_text()
    assert "Bokeh" in html and "compact" in html
    for c in reg.compute("tri_compact", True).comparisons:
        assert f"{c.ours:.10g}" in html, c.quantity
    text = capsys.readouterr().out
    assert "1/1 figures" in text and "rows (closed forms, second methods) agree" in text
    svg = tmp_path / "tri_law.svg"
    assert main(["paper", "--family", "trilinear", "--figure", "tri_law", "--reduced",
                 "--workers", "1", "--out", str(svg)]) == 0  # fmt: skip
    assert svg.stat().st_size > 10_000


def test_the_degenerate_riemann_figure_tracks_the_train_and_writes(tmp_path):
    """tri_riemann carries the train's rows (crest, velocity, spacing, count against the
    explicit compact waves and the mass balance), not only the runs' energy rows, and
    `fpu paper --family trilinear --figure tri_riemann --out x.html` writes it."""
    r = reg.compute("tri_riemann", True)
    rows = {c.quantity.split(" (")[0]: c for c in r.comparisons}
    for q in ("crest of the train's waves", "train velocity V", "spacing of the train",
              "waves in the right train"):  # fmt: skip
        assert q in rows and rows[q].agrees, q
    assert rows["waves in the right train"].ours >= 8
    out = tmp_path / "x.html"
    assert main(["paper", "--family", "trilinear", "--figure", "tri_riemann", "--reduced",
                 "--workers", "1", "--out", str(out)]) == 0  # fmt: skip
    assert "Bokeh" in out.read_text()


@pytest.mark.parametrize(
    "argv, match",
    [
        (["paper", "--family", "cubic", "--list"], "family='cubic'"),
        (["paper", "--family", "trilinear", "--figure", "pplane", "--out", "x.html"],
         "figure='pplane'"),
        (["paper", "--family", "trilinear", "--figure", "tri_law", "--out", "x.ipynb"],
         "notebooks"),
        (["paper", "--family", "trilinear", "--table", "t.md"], "--family"),
    ],
)  # fmt: skip
def test_cli_bad_input_exit_2_one_line(argv, match, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error:") and match in err and err.count("\n") == 1


def test_existence_diagram_curve_is_the_closed_form_and_smooth():
    """Panel (a)'s V_SK on the lower branch is the closed form at every w₊ (the general-route
    diagram gave a staircase off by up to 4% for this law) and strictly increasing toward w₁."""
    r = reg.compute("tri_existence", reduced=True)
    s = next(s for s in r.panels[0].series if s.label.startswith("V_SK"))
    assert np.all(np.diff(s.y) > 0)
    for w, v in zip(s.x[::10], s.y[::10]):
        assert abs(v - ft.closed_forms(float(w))["V_SK"]) <= 1e-13
