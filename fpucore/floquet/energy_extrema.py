"""Location of the extrema of E_ren(V) from samples (the method of
:mod:`fpucore.floquet.energy`): parabola vertices with their stencil and energy-noise error
bars, the QC closed form on a grid and its extrema refined by a bounded minimisation, and the
E_ren error bar of one discrete wave."""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar

from fpucore import qc

END_MARGIN = 1e-4  # relative distance from the interval ends (sonic / V_SK) on the QC grid


def wave_energy_error(r) -> float:
    """The wave's E_ren error bar: ``r.energy_error`` when the result carries one, else the
    indicator N·δw·(1 + max|f(w)| + max|v|), δw = max(residual, tail_error, integrator_error)
    (each of the N summands of eq. Eren_D moves by ≤ (|f| + |v|)·δw)."""
    e = float(getattr(r, "energy_error", math.nan))
    if math.isfinite(e):
        return e
    dw = max(float(r.residual), float(r.tail_error), float(r.integrator_error or 0.0))
    scale = 1.0 + float(np.max(np.abs(r.law.f(r.w)))) + float(np.max(np.abs(r.v)))
    return r.N * dw * scale


def _vertex(v: np.ndarray, e: np.ndarray) -> tuple[float, float]:
    """(V*, E″) of the parabola through three points."""
    c2, c1, _ = np.polyfit(v - v[1], e, 2)
    return float(v[1] - c1 / (2.0 * c2)), float(2.0 * c2)


def locate_extrema(V: np.ndarray, E: np.ndarray, dE: np.ndarray) -> list[tuple]:
    """Extrema of sampled E(V) (V ascending, one velocity interval): list of
    (V*, δV*, E*, "min" | "max") from sign changes of successive differences (see module doc)."""
    out = []
    d = np.diff(E)
    for i in range(1, V.size - 1):
        if d[i - 1] == 0.0 or np.sign(d[i - 1]) == np.sign(d[i]):
            continue
        sl = slice(i - 1, i + 2)
        v_star, e2 = _vertex(V[sl], E[sl])
        alts = []
        if i + 2 < V.size:
            alts.append(_vertex(V[i : i + 3], E[i : i + 3])[0])
        if i - 2 >= 0:
            alts.append(_vertex(V[i - 2 : i + 1], E[i - 2 : i + 1])[0])
        stencil = max((abs(a - v_star) for a in alts), default=float(V[i + 1] - V[i - 1]))
        noise = 2.0 * math.sqrt(float(np.max(dE[sl])) / abs(e2)) if e2 != 0 else math.inf
        e_star = float(np.polyval(np.polyfit(V[sl] - V[i], E[sl], 2), v_star - V[i]))
        # kind from the curvature (a tie d[i] == 0 next to the extremum must not flip it)
        out.append((v_star, stencil + noise, e_star, "min" if e2 > 0 else "max"))
    return out


def qc_energy_grid(law, w_plus: float, lo: float, hi: float, n: int):
    """(V, E_ren^QC, its error bound) on n points of (lo, hi) (one velocity interval, the ends
    moved in by END_MARGIN of its width).  The cubic: all at once by the closed form
    (:func:`fpucore.qc.solitary_closed_form`, the formulas of :func:`fpucore.qc.solitary`;
    background w₊ below V_SK, w_S(V) above it); other laws point by point."""
    span = hi - lo
    V = np.linspace(lo + END_MARGIN * span, hi - END_MARGIN * span, n)
    if qc.is_closed_form(law):
        v_sk = qc.sound_speeds(law, w_plus)[1]
        w_B = np.full_like(V, w_plus) if hi <= v_sk else qc.w_S(law, w_plus, V)
        _, _, _, E, dE, ok = qc.solitary_closed_form(law, w_B, V)
        if np.all(ok):
            return V, np.asarray(E, float), np.asarray(dE, float)
    sols = [qc.solitary(law, w_plus, float(v)) for v in V]
    return V, np.array([s.energy for s in sols]), np.array([s.energy_error for s in sols])


def qc_interval_extrema(law, w_plus: float, lo: float, hi: float, n: int):
    """QC grid on (lo, hi) and its extrema refined by a bounded minimisation: (V, E_ren^QC,
    [(V*, δV*, E*, "min" | "max"), ...])."""
    V, E, dE = qc_energy_grid(law, w_plus, lo, hi, n)
    ext = []
    for v0, _, _, kind in locate_extrema(V, E, dE):
        j = int(np.clip(np.searchsorted(V, v0), 1, V.size - 1))
        a, b = float(V[max(j - 2, 0)]), float(V[min(j + 1, V.size - 1)])
        sgn = 1.0 if kind == "min" else -1.0
        res = minimize_scalar(
            lambda v, s=sgn: s * qc.solitary(law, w_plus, v).energy,
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-12 * b},
        )
        h = 1e-3 * (b - a)
        es = [qc.solitary(law, w_plus, float(res.x) + k * h).energy for k in (-1, 0, 1)]
        e2 = (es[0] - 2 * es[1] + es[2]) / (h * h)
        de = qc.solitary(law, w_plus, float(res.x)).energy_error
        dv = 1e-12 * b + (2.0 * math.sqrt(de / abs(e2)) if e2 != 0 else math.inf)
        ext.append((float(res.x), dv, float(es[1]), kind))
    return V, E, ext
