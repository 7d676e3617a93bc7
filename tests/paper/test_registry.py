"""The figure registry (fpucore.paper): every figure of the paper computes through fpucore's routes
and every number the paper prints agrees with ours within our error bar plus the paper's printed
rounding (the rule of fpucore/paper/compare.py).

Reduced mode (``reduced=True``) lowers only grid sizes and the number of velocities along
families and sweeps; the compared numbers keep the paper's parameters: N = 500 for the Floquet
bounds (max|μ| − 1 scales like 1/N, so a smaller N would not test the printed bound), the paper's
L and t for Riemann1 and SWdyn, the paper's V for stabSK / stabSW.  The sweeps keep the
velocities where the printed bounds are decided (5.57, 5.74, 5.85; 5.38 and 5.21 next to V_SK).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from fpucore import paper
from fpucore.errors import ParameterError
from fpucore.paper.compare import compare, printed_rounding

ROOT = Path(__file__).resolve().parents[2]
# the paper's LaTeX source is not in the repository: ../shared beside the checkout (a worktree is
# one level deeper); the tests that read it skip without it
PAPER_TEX = next((p for p in (ROOT.parent / "shared" / "paper.tex",
                              ROOT.parent.parent / "shared" / "paper.tex") if p.exists()),
                 ROOT.parent / "shared" / "paper.tex")  # fmt: skip
SLOW = {"floquet_SK", "floquet_cubicSW", "SWamp_cubic_DvsQC", "SWenergy_cubic_DvsQC", "stabSK",
        "Riemann1", "SWdyn", "stabSW"}  # fmt: skip
_CACHE: dict[str, paper.FigureResult] = {}


def _result(label: str) -> paper.FigureResult:
    if label not in _CACHE:
        _CACHE[label] = paper.compute(label, reduced=True)
    return _CACHE[label]


def test_printed_rounding_is_half_a_unit_of_the_last_digit():
    assert printed_rounding("−5.7209") == pytest.approx(5e-5)
    assert printed_rounding("3.811") == pytest.approx(5e-4)
    assert printed_rounding("4.78423") == pytest.approx(5e-6)
    assert printed_rounding("1e-8") == pytest.approx(0.5e-8)
    assert printed_rounding("2") == pytest.approx(0.5)


def test_the_verdict_can_fail():
    kw = {"source": "test", "elapsed_s": 0.0}
    assert compare("x", "q", "4.6404", 4.6404, 4.64044, 0.0, **kw).agrees  # inside rounding
    bad = compare("x", "q", "4.6404", 4.6404, 4.64046, 1e-6, **kw)
    assert not bad.agrees and bad.verdict == "disagrees" and ">" in bad.why
    assert compare("x", "q", "4.6404", 4.6404, 4.64046, 2e-5, **kw).agrees  # the error bar counts
    assert not compare("x", "q", "< 1.005", 1.005, 1.0049, 2e-4, kind="upper_bound", **kw).agrees
    assert compare("x", "q", "> 1", 1.0, 1.0005, 1e-13, kind="lower_bound", **kw).agrees
    assert not compare("x", "q", "0", 0.0, math.nan, 0.0, **kw).agrees
    with pytest.raises(ParameterError, match="kind"):
        compare("x", "q", "1", 1.0, 1.0, 0.0, kind="about", **kw)


def test_unknown_label_is_refused_with_the_valid_ones():
    with pytest.raises(ParameterError, match="pplane"):
        paper.figure("Riemann2")


@pytest.mark.skipif(not PAPER_TEX.exists(), reason="the paper's source is not on this machine")
def test_the_registry_holds_exactly_the_papers_figures_in_order():
    labels = re.findall(r"\\label\{fig:([^}]+)\}", PAPER_TEX.read_text())
    assert list(paper.LABELS) == labels
    assert [paper.FIGURES[lab].number for lab in labels] == list(range(1, len(labels) + 1))


@pytest.mark.parametrize(
    "label",
    [
        pytest.param(lab, marks=pytest.mark.slow) if lab in SLOW else lab for lab in paper.LABELS
    ],  # fmt: skip
)
def test_figure_computes_and_every_printed_number_agrees(label):
    r = _result(label)
    assert r.label == label and r.reduced and r.elapsed_s > 0
    assert r.comparisons, "every figure compares at least one printed number"
    assert r.panels and all(p.series for p in r.panels)
    for p in r.panels:
        for s in p.series:
            data = s.z if s.style == "image" else s.y
            assert np.isfinite(data).any(), (p.title, s.label)
    for c in r.comparisons:
        assert c.figure == label and c.elapsed_s >= 0 and c.source
        assert math.isfinite(c.ours) and math.isfinite(c.error), c
        assert c.agrees, f"{c.quantity}: paper {c.printed}, ours {c.ours!r}: {c.why}"
    d = r.as_dict()
    assert d["status"] == "ok" and d["n_agree"] == len(r.comparisons)
    assert r.max_error == max(c.error for c in r.comparisons)


def test_the_papers_key_numbers_are_compared():
    """The numbers named in the task: each appears as a printed value of some comparison."""
    printed = {c.printed for lab in ("pplane", "SWvelocities_cubic", "cubic")
               for c in _result(lab).comparisons}  # fmt: skip
    assert {"2√65/3", "17/3", "3√2", "11/2", "7√5/3", "√13", "√29", "4.78423"} <= printed


@pytest.mark.slow
def test_dynamic_and_floquet_numbers_are_compared():
    want = {"floquet_SK": {"O(1e-8)", "< 1.0001", "< 1.005"},
            "floquet_cubicSW": {"< 1.0006", "< 1.001"},
            "Riemann1": {"−5.7209", "−5.6159", "4.6404", "2.0667"},
            "SWdyn": {"+5.2494", "−5.2494", "+3.811", "−3.811", "+5.025", "−5.025"}}  # fmt: skip
    for lab, printed in want.items():
        assert printed <= {c.printed for c in _result(lab).comparisons}, lab


def test_a_wrong_printed_value_would_be_caught():
    """Mutation check of the pipeline: the same computed number against a paper value off by
    3 units of its last digit disagrees (the rule does not absorb real differences)."""
    c = next(c for c in _result("cubic").comparisons if c.printed == "4.78423")
    moved = compare(c.figure, c.quantity, "4.78426", 4.78426, c.ours, c.error, source=c.source,
                    elapsed_s=c.elapsed_s)  # fmt: skip
    assert c.agrees and not moved.agrees
