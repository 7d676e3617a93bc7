"""Verdict wording: two percentages compared in one sentence are printed with the digits that
tell them apart, and a text that shows the headline first does not repeat it."""

from __future__ import annotations

from fpucore.floquet.decision import Decision


def unresolved(drop: float, needed: float, p: float = 0.64, p_error: float = 0.13) -> Decision:
    # an excess that neither converged nor fell enough: the shape of the case
    return Decision(
        classification="undetermined", reason="unresolved", N=64, excess=2.0e-3, error=1e-6,
        growth_rate=0.01, points_N=(40, 52, 64), points_excess=(2.8e-3, 2.5e-3, 2.0e-3),
        points_error=(1e-6, 1e-6, 1e-6), p=p, p_error=p_error, spread=0.4,
        envelope_N=(40, 52, 64), peak_N=40, drop=drop, drop_needed=needed,
        next_step="compute larger N",
    )  # fmt: skip


def test_a_drop_short_of_the_required_one_is_printed_apart_from_it():
    s = unresolved(0.2904, 0.2929).sentence
    assert "it falls 29.0 % from its largest value at N = 40, short of the 29.3 % required" in s
    s = unresolved(0.20, 0.29).sentence  # whole percentages already differ
    assert "falls 20 % from" in s and "short of the 29 % required" in s


def test_the_evidence_does_not_repeat_the_headline():
    d = unresolved(0.2904, 0.2929)
    assert d.headline == "not determined at N = 64"
    assert d.sentence.startswith("not determined at N = 64: ")
    text = f"{d.headline}: {d.evidence}"
    assert text.count("not determined at N = 64") == 1
    assert d.evidence.startswith("multipliers leave the unit circle by")
