"""Shared pieces of the figure computations: the paper's law (a = −1, b = 10), its printed
closed-form numbers (evaluated here from the paper's own formulas, independently of fpucore.qc),
and small helpers that turn an fpucore result into comparisons.
"""

from __future__ import annotations

import math

import numpy as np

from fpucore import qc
from fpucore.law import CubicLaw
from fpucore.paper.compare import Comparison, compare
from fpucore.paper.figure import Clock

A, B = -1.0, 10.0
LAW = CubicLaw(A, B)
EPS = np.finfo(float).eps

# The numbers printed in the captions (Figs. pplane, SWs_cubic, SWamp_energy_QCcubic,
# SWs_cubic_DvsQC, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC): (printed text, value).
PRINTED_SPEEDS = {
    1.0: {
        "V_SK": ("2√65/3", 2.0 * math.sqrt(65.0) / 3.0),
        "w_minus": ("17/3", 17.0 / 3.0),
        "c_plus": ("3√2", 3.0 * math.sqrt(2.0)),
        "c_minus": ("11/2", 11.0 / 2.0),
    },
    6.0: {
        "V_SK": ("7√5/3", 7.0 * math.sqrt(5.0) / 3.0),
        "c_plus": ("√13", math.sqrt(13.0)),
        "c_minus": ("√29", math.sqrt(29.0)),
    },
}
NAMES = {"V_SK": "V_SK", "w_minus": "w₋", "c_plus": "c₊", "c_minus": "c₋"}


def roundoff(x: float, ulps: float = 8.0) -> float:
    """Error bar of a closed form evaluated in double precision: a few ulp of |x|."""
    return ulps * EPS * max(abs(float(x)), EPS)


def caption_speeds(figure: str, w_plus: float, keys=None) -> list[Comparison]:
    """The caption's V_SK, (w₋,) c₊, c₋ at w₊ against fpucore.qc's closed forms (eqs.
    cubic_cond2, cubic_cond1, cplus, cminus_cubic); error bar: round-off (8 ulp) plus the
    superkink's own Rayleigh / zero-G residuals."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, w_plus)
    c_plus, _, c_minus = qc.sound_speeds(LAW, w_plus)
    ours = {"V_SK": sk.V, "w_minus": sk.w_minus, "c_plus": c_plus, "c_minus": c_minus}
    t = clock.s
    out = []
    for key, (printed, value) in PRINTED_SPEEDS[w_plus].items():
        if keys is not None and key not in keys:
            continue
        src = (
            f"qc.superkink_from_w_plus(law, {w_plus:g})"
            if key in ("V_SK", "w_minus")
            else f"qc.sound_speeds(law, {w_plus:g})"
        )
        err = roundoff(ours[key])
        if key in ("V_SK", "w_minus"):
            err += sk.rayleigh_residual
        out.append(
            compare(
                figure,
                f"{NAMES[key]} at w₊ = {w_plus:g}",
                printed,
                value,
                ours[key],
                err,
                source=src,
                elapsed_s=t,
                rounding=0.0,
            )
        )
    return out
