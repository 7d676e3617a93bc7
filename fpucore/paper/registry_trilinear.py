"""The trilinear family's figures (soft–hard–soft piecewise-linear law; the companion study
arXiv 2406.06437): a second, small registry with the same :class:`~fpucore.paper.registry.Figure`
entries as the paper's, computed by fpucore.paper.figures_trilinear and figures_trilinear_waves.

    FIGURES["tri_law"].compute(reduced=True) -> FigureResult
    fpu paper --family trilinear --list

The rows compare computed values with the trilinear closed forms (QC speeds, equal areas, the
explicit compact waves of the E₁ = 0 case) or with a second method; there are no printed
numbers to match, so ``printed`` holds the formula.
"""

from __future__ import annotations

from fpucore.errors import ParameterError
from fpucore.paper import figures_trilinear as ft
from fpucore.paper import figures_trilinear_riemann as fr
from fpucore.paper import figures_trilinear_waves as fw
from fpucore.paper.figure import FigureResult
from fpucore.paper.registry import Figure

_F = [
    ("tri_law", "law", ft.fig_tri_law, 0.1,
     "The trilinear law f(w) (w₁ = 0.5, w₂ = 1.5, E₁ = 1, E₂ = 4, E₃ = 0.2) with its corners and "
     "the equal-area (Maxwell) line of the superkink from w₊ = 0.3: the Rayleigh line of slope "
     "V_SK² cutting equal areas; dashed, the degenerate law E₁ = 0."),
    ("tri_existence", "QC", ft.fig_tri_existence, 0.1,
     "Existence diagram: (a) c₊, V_SK, c₋ against w₊ (solitary waves for c₊ < V < V_SK and "
     "V_SK < V < c₋; superkinks bifurcate at w₊ → w₁ with V_SK → √E₂); (b) the same at "
     "w₊ = 0.3 against the asymmetry E₃."),
    ("tri_flattops", "waves", fw.fig_tri_flattops, 25.0,
     "Solitary waves near the kink limit, w₊ = 0.3: discrete (points, N = 64) and QC (curves) at "
     "V_SK ∓ ΔV — flat tops (kink–antikink bundles) whose plateau tends to w₋."),
    ("tri_compact", "waves", fw.fig_tri_compact, 25.0,
     "The degenerate law E₁ = 0: compact discrete solitary waves on w_B = 0.2 for 0 < V < V_max; "
     "(a) amplitude against V, explicit form (curve) and solver (points); (b) profiles."),
    ("tri_floquet", "Floquet", fw.fig_tri_floquet, 5.0,
     "Maximum modulus of the Floquet multipliers of trilinear superkinks against V at a modest N "
     "(64 reduced, 128 full), crossings located in the monodromy."),
    ("tri_riemann", "simulation", fr.fig_tri_riemann, 90.0,
     "The degenerate Riemann run, E₁ = 0: a velocity jump on w_B = 0.2 sends out periodic "
     "trains of compact solitary waves (a Whitham shock into the sonic vacuum), each wave the "
     "explicit compact wave of its measured V at spacing 2; (d) the data at rest w = 0.6 | 0: "
     "a front followed by a modulated train of pulses."),
]  # fmt: skip

FIGURES: dict[str, Figure] = {
    label: Figure(label, i + 1, section, caption, run, cost)
    for i, (label, section, run, cost, caption) in enumerate(_F)
}
LABELS = tuple(FIGURES)


def figure(label: str) -> Figure:
    """The entry of ``label`` (a ParameterError naming the valid labels otherwise)."""
    if not isinstance(label, str) or label not in FIGURES:
        raise ParameterError("figure", label, "one of " + ", ".join(LABELS))
    return FIGURES[label]


def compute(label: str, reduced: bool = False) -> FigureResult:
    """Compute figure ``label`` (see :meth:`fpucore.paper.registry.Figure.compute`)."""
    return figure(label).compute(reduced)
