"""Figures of the soft–hard–soft trilinear family (companion study, arXiv 2406.06437): the law
and the existence diagram from the QC closed forms, plus the laws and closed forms shared with
fpucore.paper.figures_trilinear_waves (flat tops, compact waves, Floquet sweep).  Each
``fig_tri_<name>(reduced)`` returns (panels, comparisons, params, notes) as the paper's figures
do (fpucore.paper.registry).  The references are the trilinear closed forms written out here
from their formulas (fpucore.qc.piecewise's docstring, fpucore.wave.compact's derivation),
independently of the code that computes ``ours``.
"""

from __future__ import annotations

import math

import numpy as np

from fpucore import qc
from fpucore.law import TrilinearLaw
from fpucore.paper.common import roundoff
from fpucore.paper.compare import compare
from fpucore.paper.figure import Clock, Panel, series

W1, W2, E1, E2, E3 = 0.5, 1.5, 1.0, 4.0, 0.2
LAW = TrilinearLaw(W1, W2, E1, E2, E3)  # the general (E₁ > 0) example
DEGENERATE = TrilinearLaw(W1, W2, 0.0, E2, E3)  # E₁ = 0: compact slow waves
W_PLUS = 0.3  # the state ahead of the superkink / solitary waves (lower branch, w₊ < w₁)
W_B = 0.2  # the background of the compact waves (inside the zero-modulus regime)


def _f(w: float, e1: float = E1, e3: float = E3) -> float:
    """The trilinear force written out piece by piece."""
    if w <= W1:
        return e1 * w
    if w <= W2:
        return e1 * W1 + E2 * (w - W1)
    return e1 * W1 + E2 * (W2 - W1) + e3 * (w - W2)


def closed_forms(w_plus: float = W_PLUS, e1: float = E1, e3: float = E3) -> dict[str, float]:
    """w₋, V_SK, c₊, c₋ of the trilinear law for w₊ < w₁ (lower branch): the equal-area partner
    w₋ = [A w₁(w₁ − w₊) − B w₂(w₂ − w₊)] / [A(w₁ − w₊) − B(w₂ − w₊)] (A = E₂ − E₁, B = E₂ − E₃),
    V_SK² the chord slope (eq. Rline), c₊² = E₁ (eq. cplus), c₋² the chord slope to the corner
    w₂ (eq. cminus)."""
    A, B = E2 - e1, E2 - e3
    wm = (A * W1 * (W1 - w_plus) - B * W2 * (W2 - w_plus)) / (A * (W1 - w_plus) - B * (W2 - w_plus))
    fp = _f(w_plus, e1, e3)
    return {
        "w_minus": wm,
        "V_SK": math.sqrt((_f(wm, e1, e3) - fp) / (wm - w_plus)),
        "c_plus": math.sqrt(e1),
        "c_minus": math.sqrt((_f(W2, e1, e3) - fp) / (W2 - w_plus)),
    }


NAMES = {"V_SK": "V_SK", "w_minus": "w₋", "c_plus": "c₊", "c_minus": "c₋"}
FORMULAS = {
    "w_minus": "[Aw₁(w₁−w₊) − Bw₂(w₂−w₊)]/[A(w₁−w₊) − B(w₂−w₊)]",
    "V_SK": "√((f(w₋) − f(w₊))/(w₋ − w₊))",
    "c_plus": "√E₁",
    "c_minus": "√((f(w₂) − f(w₊))/(w₂ − w₊))",
}


def speed_rows(label: str, w_plus: float = W_PLUS) -> list:
    """V_SK, w₋, c₊, c₋ at w₊ from fpucore.qc against :func:`closed_forms` (8 ulp round-off
    plus the superkink's Rayleigh residual)."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, w_plus)
    c_plus, _, c_minus = qc.sound_speeds(LAW, w_plus)
    ours = {"V_SK": sk.V, "w_minus": sk.w_minus, "c_plus": c_plus, "c_minus": c_minus}
    t = clock.s
    ref = closed_forms(w_plus)
    return [
        compare(
            label,
            f"{NAMES[k]} at w₊ = {w_plus:g}",
            FORMULAS[k],
            ref[k],
            ours[k],
            roundoff(ref[k], 16) + sk.rayleigh_residual,
            rounding=0,
            elapsed_s=t,
            source=f"qc.{'superkink_from_w_plus' if k in ('V_SK', 'w_minus') else 'sound_speeds'}"
            f"(law, {w_plus:g})",
        )
        for k in ("V_SK", "w_minus", "c_plus", "c_minus")
    ]


def fig_tri_law(reduced: bool):
    """The trilinear law f(w) with its corners (w₁, f(w₁)), (w₂, f(w₂)) and the equal-area
    (Maxwell) line of the superkink from w₊ = 0.3: the Rayleigh line of slope V_SK² cutting
    equal areas.  ∫_{w₊}^{w₋}(f − R) dw is exact by the trapezoid rule on the nodes w₊, w₁, w₂, w₋
    (f − R is linear between them)."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    w = np.linspace(-0.5, 3.0, 351)
    fp = float(LAW.f(W_PLUS))
    ray = fp + sk.V**2 * (w - W_PLUS)
    corners = [W1, W2]
    panels = (
        Panel(
            f"trilinear f(w), w₁ = {W1:g}, w₂ = {W2:g}, E = ({E1:g}, {E2:g}, {E3:g})",
            "w",
            "f(w)",
            (
                series("f(w)", w, LAW.f(w)),
                series("equal-area line, slope V_SK²", w, ray, "dashed"),
                series("corners w₁, w₂", corners, LAW.f(np.array(corners)), "points"),
                series(
                    "w₊, w₋",
                    [sk.w_plus, sk.w_minus],
                    LAW.f(np.array([sk.w_plus, sk.w_minus])),
                    "points",
                ),
                series("E₁ = 0 (degenerate)", w, DEGENERATE.f(w), "dashed"),
            ),
        ),
    )
    t = clock.s
    nodes = np.array([W_PLUS, W1, W2, sk.w_minus])
    gap = LAW.f(nodes) - (fp + sk.V**2 * (nodes - W_PLUS))
    area = float(np.sum(0.5 * (gap[1:] + gap[:-1]) * np.diff(nodes)))
    scale = float(np.sum(np.abs(0.5 * (gap[1:] + gap[:-1]) * np.diff(nodes))))
    comps = [
        compare(
            "tri_law",
            f"f at the corner w{k + 1}",
            f"{form}",
            _f(c),
            float(LAW.f(c)),
            roundoff(_f(c), 8),
            source=f"law.f({c:g})",
            elapsed_s=t,
            rounding=0,
        )
        for k, (c, form) in enumerate(zip(corners, ("E₁w₁", "E₁w₁ + E₂(w₂ − w₁)")))
    ]
    comps.append(
        compare(
            "tri_law",
            "equal areas: ∫(f − R) dw from w₊ to w₋ (eq. zero_G)",
            "0",
            0.0,
            area,
            roundoff(scale, 64),
            rounding=0,
            elapsed_s=t,
            source="qc.superkink_from_w_plus(law, 0.3): V, w₋",
        )
    )
    comps += speed_rows("tri_law")
    params = {"w1": W1, "w2": W2, "E1": E1, "E2": E2, "E3": E3, "w_plus": W_PLUS}
    return panels, comps, params, ""


ASYM_E3 = (0.0, 0.5, 2.0)  # E₃ of the checked rows: zero modulus, E₃ < E₁, E₃ > E₁


def fig_tri_existence(reduced: bool):
    """Existence diagram: (a) c₊, V_SK, c₋ against w₊ on both branches (w₊ < w₁ and w₂ < w₊ <
    the upper branch's end; fpucore.qc's PL closed forms); (b) the same at w₊ = 0.3 against the
    asymmetry E₃ of the softer regime after the hard one (E₃ = E₁ = 1: equal soft moduli).
    Solitary waves exist for c₊ < V < V_SK and V_SK < V < c₋; superkinks bifurcate at w₊ → w₁
    with V_SK → √E₂ (fpucore.qc.piecewise)."""
    clock = Clock()
    # each branch by the PL closed forms (qc.sound_speeds); qc.diagram.existence_diagram samples
    # the general quadrature route for non-cubic laws, whose V_SK is off by up to 4% here
    n = 60 if reduced else 300
    hi = qc.superkink_w_plus_range(LAW, "upper")[1]
    a_ser: list = []
    for name, grid in (
        ("lower", np.linspace(-6.0, W1, n + 1)[:-1]),
        ("upper", np.linspace(W2, hi, n + 1)[1:-1]),
    ):
        sp = np.array([qc.sound_speeds(LAW, float(w)) for w in grid])
        first = name == "lower"
        a_ser += [
            series("V_SK (superkink limit)" if first else "", grid, sp[:, 1]),
            series("c₊ (sonic)" if first else "", grid, sp[:, 0], "dashed"),
            series("c₋ (sonic)" if first else "", grid, sp[:, 2], "dashed"),
        ]
    a_ser += [
        series("hard regime [w₁, w₂]", [W1], [0.0], "vline"),
        series("", [W2], [0.0], "vline"),
    ]
    # w₊ = 0.3 has a partner while E₃ < 3.5 (w₊ > w₁ − (E₂ − E₃)(w₂ − w₁)/(E₃ − E₁))
    e3 = np.linspace(0.0, 3.4, 18 if reduced else 69)
    sp_e3 = [qc.sound_speeds(TrilinearLaw(W1, W2, E1, E2, float(e)), W_PLUS) for e in e3]
    b_ser = tuple(
        series(name, e3, [s[i] for s in sp_e3], style)
        for i, (name, style) in enumerate((("c₊", "dashed"), ("V_SK", "line"), ("c₋", "dashed")))
    )
    panels = (
        Panel("(a) velocities of solitary waves against w₊", "w₊", "V", tuple(a_ser)),
        Panel(f"(b) against the asymmetry E₃ at w₊ = {W_PLUS:g}", "E₃", "V", b_ser),
    )
    t = clock.s
    lo, hi = qc.superkink_velocity_bounds(LAW)
    comps = [
        compare(
            "tri_existence",
            f"superkink velocity {name} bound, lower branch",
            pr,
            ref,
            ours,
            roundoff(ref, 64),
            source="qc.superkink_velocity_bounds(law)",
            elapsed_s=t,
            rounding=0,
        )
        for name, pr, ref, ours in (
            ("lower", "√E₁ (w₊ → −∞)", math.sqrt(E1), lo),
            ("upper", "√E₂ (w₊ → w₁)", math.sqrt(E2), hi),
        )
    ]
    for e in ASYM_E3:
        law = TrilinearLaw(W1, W2, E1, E2, e)
        ours = qc.superkink_from_w_plus(law, W_PLUS)
        ref = closed_forms(W_PLUS, E1, e)["V_SK"]
        comps.append(
            compare(
                "tri_existence",
                f"V_SK at w₊ = {W_PLUS:g}, E₃ = {e:g}",
                FORMULAS["V_SK"],
                ref,
                ours.V,
                roundoff(ref, 16) + ours.rayleigh_residual,
                rounding=0,
                elapsed_s=t,
                source=f"qc.superkink_from_w_plus(E3={e:g} law, 0.3)",
            )
        )
    params = {"E3": tuple(e3.tolist()), "w_plus": W_PLUS, "n": n}
    return panels, comps, params, ""
