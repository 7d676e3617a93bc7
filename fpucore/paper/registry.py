"""The paper's 17 figures by LaTeX label, in the paper's order: caption, parameters, the
computation (fpucore routes only) and the comparisons with the numbers printed in the paper.

    FIGURES["pplane"].compute(reduced=False) -> FigureResult
    compute("pplane")                         # the same by label, with a clear error otherwise

``reduced=True`` (tests, quick looks) lowers only grid sizes and the number of velocities along
families and sweeps; every printed number is still checked at the paper's parameters (N = 500
for the Floquet bounds, the paper's L and t for simulations), see each figure's docstring.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from fpucore.errors import ParameterError
from fpucore.paper import figures_dynamics as dyn
from fpucore.paper import figures_qc as fqc
from fpucore.paper import figures_stability as stab
from fpucore.paper import figures_wave as fw
from fpucore.paper.figure import Clock, FigureResult


@dataclass(frozen=True)
class Figure:
    """One figure of the paper: ``label`` (LaTeX, without ``fig:``), ``number`` (its order in the
    paper), ``section``, ``caption`` (plain text), ``run`` (reduced) → (panels, comparisons,
    params, notes), ``cost`` (a rough full-size wall time on one core, s, for scheduling)."""

    label: str
    number: int
    section: str
    caption: str
    run: Callable
    cost: float

    def compute(self, reduced: bool = False) -> FigureResult:
        clock = Clock()
        panels, comps, params, notes = self.run(bool(reduced))
        return FigureResult(
            label=self.label,
            params=dict(params),
            panels=tuple(panels),
            comparisons=tuple(comps),
            reduced=bool(reduced),
            elapsed_s=clock.s,
            notes=notes,
        )


_F = [
    (
        "superkink",
        "§2",
        fqc.fig_superkink,
        0.1,
        "Interaction force f(w) (red) and the Rayleigh line (black) connecting (w₊, f(w₊)) and "
        "(w₋, f(w₋)). The strain w* marks the transition from the hardening (convex) to softening "
        "(concave) regime. A superkink with limiting states w± and supersonic velocity V_SK exists "
        "when the two areas cut by the Rayleigh line (slope V²) are equal. The associated solitary "
        "waves have c₊² < V² < V_SK² or V_SK² < V² < c₋², the slopes of the lines through "
        "(w₊, f(w₊)) tangent to f at w₊ and w₋ˢ.",
    ),
    (
        "pplane",
        "§3",
        fqc.fig_pplane,
        0.3,
        "Phase portraits for eq. (TW_QC_gen2) with the cubic f(w), w₊ = 1 and "
        "(a) V = V_SK − 0.001; (b) V = V_SK; (c) V = V_SK + 0.005. Here V_SK = 2√65/3, "
        "w₋ = 17/3. The coloured trajectories are a tensile solitary wave in (a), superkinks "
        "in (b) and a compressive solitary wave in (c).",
    ),
    (
        "cubic",
        "§4",
        fqc.fig_cubic,
        0.1,
        "(a) The limiting strains w± of a superkink as functions of V_SK for the cubic "
        "nonlinearity with a = −1, b = 10 (symmetric about the vertical axis). (b) Strain "
        "profiles for the QC model at different velocity values.",
    ),
    (
        "SWvelocities_cubic",
        "§4",
        fqc.fig_SWvelocities_cubic,
        0.1,
        "Velocities of the solitary waves as a function of the state w₊ ahead of the associated "
        "superkink: the superkink limit V_SK and the sonic limits c₊, c₋; tensile (TSW) and "
        "compressive (CSW) solitary waves between them. Symmetric about the horizontal axis. "
        "a = −1, b = 10.",
    ),
    (
        "SWs_cubic",
        "§4",
        fqc.fig_SWs_cubic,
        0.1,
        "(a) Tensile solitary waves in the QC model at c₊ < V < V_SK; (b) compressive ones at "
        "V_SK < V < c₋; (c) solitary waves just below and just above V_SK with kink and antikink "
        "fronts. w₊ = 1, a = −1, b = 10: V_SK = 2√65/3, w₋ = 17/3, c₊ = 3√2, c₋ = 11/2.",
    ),
    (
        "SWamp_energy_QCcubic",
        "§4",
        fqc.fig_SWamp_energy_QCcubic,
        0.1,
        "(a) Amplitude and (b) renormalized energy against V for QC solitary waves at w₊ = 1 "
        "(a = −1, b = 10); the superkink limit V_SK = 2√65/3 is dashed. Sonic limits c₊ = 3√2, "
        "c₋ = 11/2.",
    ),
    (
        "TWcubic",
        "§5",
        fw.fig_TWcubic,
        2.0,
        "Superkinks w_n(0) = w(n) of the discrete problem (circles) and the QC superkinks w(x) "
        "(curves) at t = 0, a = −1, b = 10.",
    ),
    (
        "SWs_cubic_DvsQC",
        "§5",
        fw.fig_SWs_cubic_DvsQC,
        3.0,
        "Solitary waves of the discrete problem (circles) and of the QC model (curves) at t = 0: "
        "(a) tensile below and (b) compressive above V_SK at w₊ = 1 (V_SK = 2√65/3, c₊ = 3√2, "
        "c₋ = 11/2); (c) compressive below and (d) tensile above V_SK at w₊ = 6 (V_SK = 7√5/3, "
        "c₊ = √13, c₋ = √29).",
    ),
    (
        "SWamp_cubic_DvsQC",
        "§5",
        fw.fig_SWamp_cubic_DvsQC,
        6.0,
        "Amplitude w_amp = |w(0) − w₊| against V, discrete (dots) and QC (curves): (a) w₊ = 1; "
        "(b) w₊ = 6; the superkink limit dashed; TSW / CSW tensile and compressive waves.",
    ),
    (
        "SWenergy_cubic_DvsQC",
        "§5",
        fw.fig_SWenergy_cubic_DvsQC,
        6.0,
        "Renormalized energy E_ren (eqs. Eren_D, Eren_QC) against V, discrete (dots) and QC "
        "(curves): (a) w₊ = 1; (b) w₊ = 6; the superkink limit dashed.",
    ),
    (
        "floquet_SK",
        "§6.1",
        stab.fig_floquet_SK,
        20.0,
        "Maximum modulus of the Floquet multipliers for superkinks, a = −1, b = 10 (N = 500).",
    ),
    (
        "Floquet_example",
        "§6.1",
        stab.fig_Floquet_example,
        2.0,
        "(a) Floquet multipliers μ of the superkink at V = 5.2; (b) enlarged: multipliers with "
        "|μ| > 1, mild oscillatory instabilities. The unit circle in red. a = −1, b = 10.",
    ),
    (
        "stabSK",
        "§6.1",
        dyn.fig_stabSK,
        2.0,
        "Space–time strain evolution initiated by computed superkinks with (a) V = 4.8; "
        "(b) V = 5.2. a = −1, b = 10.",
    ),
    (
        "Riemann1",
        "§6.1",
        dyn.fig_Riemann1,
        4.0,
        "Riemann data w^l = 4.6, w^r = 0, L = 3600: (a) strain at t = 300; (c) superkink with "
        "V = −5.7209 and w_100(t); (d) solitary wave V = −5.6159, w_B = 2.0667 and w_200(t); "
        "(e) solitary wave V = 4.6404, w_B = 0 and w_3000(t). a = −1, b = 10.",
    ),
    (
        "floquet_cubicSW",
        "§6.2",
        stab.fig_floquet_cubicSW,
        25.0,
        "Maximum modulus of the Floquet multipliers for solitary waves: (a) w₊ = 1; (b) w₊ = 6; "
        "the dashed lines mark V_SK. a = −1, b = 10.",
    ),
    (
        "stabSW",
        "§6.2",
        dyn.fig_stabSW,
        4.0,
        "Space–time strain evolution initiated by solitary waves slightly below and slightly above "
        "the superkink limit: (a) V = 5.21749194749 (compressive); (b) V = 5.2174919476 (tensile). "
        "w₊ = 6, V_SK = 7√5/3 = 5.21749194749951, a = −1, b = 10.",
    ),
    (
        "SWdyn",
        "§6.2",
        dyn.fig_SWdyn,
        8.0,
        "Initial and final strain for Gaussian data (eq. GaussIC): (a) w_B = 1, A = 6, L = 2400; "
        "(b) w_B = 6, A = −6, L = 3000. a = −1, b = 10.",
    ),
]

FIGURES: dict[str, Figure] = {
    label: Figure(label, i + 1, section, caption, run, cost)
    for i, (label, section, run, cost, caption) in enumerate(_F)
}
LABELS = tuple(FIGURES)


def figure(label: str) -> Figure:
    """The registry entry of ``label`` (a ParameterError naming the valid labels otherwise)."""
    if not isinstance(label, str) or label not in FIGURES:
        raise ParameterError("figure", label, "one of " + ", ".join(LABELS))
    return FIGURES[label]


def compute(label: str, reduced: bool = False) -> FigureResult:
    """Compute figure ``label`` (see :meth:`Figure.compute`)."""
    return figure(label).compute(reduced)
