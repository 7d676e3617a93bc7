"""Continuation in V for discrete traveling waves, and whole families (paper §5, Figs. TWcubic,
SWs_cubic_DvsQC, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC).

Predictor.  From a converged wave x(V₀) the guess at V₁ is x(V₀) + [x_QC(V₁) − x_QC(V₀)]: the QC
closed form carries the large, known change of the profile (width, boundary states, w_S(V)) and
the discrete correction x − x_QC, which varies slowly in V, is carried over.  States on chains
of different N are re-centred and padded with the tail states (:func:`fpucore.wave.setup.resize`).

:func:`continue_to` is the rescue used by ``wave.solve_*`` when Newton from the QC guess fails:
find a nearby velocity (towards the middle of the family's interval) where the QC guess converges,
then march to the target with adaptive steps (halve on failure, grow on success).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from fpucore import qc
from fpucore.wave.setup import (
    Spec,
    Tolerances,
    build_system,
    choose_K,
    choose_m,
    qc_guess,
    required_N,
    resize,
    spec_of,
)
from fpucore.wave.system import newton


def family_interval(law, spec) -> tuple[float, float]:
    if spec.kind == "superkink":
        return qc.superkink_velocity_bounds(law, spec.branch)  # branches differ for a general law
    (a, b), (c, d) = qc.solitary_intervals(law, spec.w_plus)
    return (a, b) if spec.V < b else (c, d)


def respec(law, spec: Spec, V: float) -> Spec:
    """The same wave (kind, branch or w₊) at another velocity."""
    return spec_of(law, spec.kind, spec.row, V)


def qc_shift_predictor(law, spec_new, x_old: np.ndarray, N_old: int, spec_old):
    """Callable N ↦ predicted interleaved state at spec_new.V on N sites (see module doc)."""

    def predict(N: int) -> np.ndarray:
        x = resize(x_old, N_old, N, spec_old.w_left, spec_old.w_right)
        return x + qc_guess(spec_new, N) - qc_guess(spec_old, N)

    return predict


def neighbour_predictor(law, prev, spec: Spec):
    """The QC-shift predictor at spec from its converged neighbour prev = (wave, its spec), or
    None when there is none or it lies on another velocity interval of the family."""
    if prev is None:
        return None
    r_prev, sp_prev = prev
    if family_interval(law, sp_prev) != family_interval(law, spec):
        return None
    x_prev = np.empty(2 * r_prev.N)
    x_prev[0::2], x_prev[1::2] = r_prev.w, r_prev.wdot
    return qc_shift_predictor(law, spec, x_prev, r_prev.N, sp_prev)


def solve_from_neighbour(law, spec: Spec, prev, solve):
    """One step of a family walk (wave families, atlas rows): ``solve(predictor)`` from the
    neighbour's predictor (:func:`neighbour_predictor`), again from the QC guess
    (``solve(None)``) if there is none or it does not converge."""
    pred = neighbour_predictor(law, prev, spec)
    r = solve(pred) if pred is not None else None
    if r is None or not r.converged:
        r = solve(None)
    return r


def _easy_end(law, spec) -> float:
    """The end of the family's V interval where the QC guess is accurate: the sonic limit for
    solitary waves (small amplitude), the upper velocity bound for superkinks (weak, wide)."""
    lo, hi = family_interval(law, spec)
    if spec.kind == "superkink":
        return hi
    (a, b), _ = qc.solitary_intervals(law, spec.w_plus)
    return lo if (lo, hi) == (a, b) else hi


def continue_to(
    law,
    spec,
    tols: Tolerances,
    jacobian,
    left: Callable[[], float],
    max_iter: int = 40,
    max_steps: int = 80,
    N_cap: int = 4000,
):
    """March in V from a velocity where the QC guess converges to spec.V.

    Start candidates lie towards the family's easy end (:func:`_easy_end`), then towards the middle
    of the interval.  The path runs on the shortest chain that holds both ends (automatic N,
    at most N_cap sites).  tols : the solve's tolerances (:class:`Tolerances` of spec; its
    residual, step-count and tail tolerances serve every point of the path); left() : the
    seconds left of the solve's time budget.  Returns (x, N, note) with x the interleaved state
    at spec.V on N sites, or (None, 0, note) on failure.
    """

    lo, hi = family_interval(law, spec)
    easy, mid = _easy_end(law, spec), 0.5 * (lo + hi)
    N_t = required_N(law, spec, tols.tail_tol)
    start = None
    for target, frac in ((easy, 0.3), (easy, 0.6), (easy, 0.85), (mid, 0.3), (mid, 0.7)):
        if left() <= 0:
            break
        Vs = spec.V + frac * (target - spec.V)
        if not lo < Vs < hi:
            continue
        sp = respec(law, spec, Vs)
        N = max(N_t, required_N(law, sp, tols.tail_tol))
        if N > N_cap:
            continue
        x0 = qc_guess(sp, N)
        # choose_m, not the main route's choose_m_floor: on stiff laws (b = 1000) the floor picks
        # fewer steps and the path (not the converged wave's accuracy) changes; kept as it was
        m = choose_m(law, sp, x0, N, tols.int_tol)
        K = choose_K(law, sp, x0, m)
        o = newton(
            build_system(law, sp, N, m, K), x0, tols.res_tol, max_iter, jacobian, max(1.0, left())
        )
        if o.converged:
            start = (sp, o.x, N, m, K)
            break
    if start is None:
        return None, 0, "continuation: no converged start velocity found"
    sp, x, N, m, K = start
    V_start = sp.V
    # march in s = log|V − V_SK| for solitary waves (the profile changes like log|V − V_SK| near
    # the superkink limit), in s = V for superkinks; secant predictor once two points exist
    if spec.kind == "superkink":
        to_s, to_V = (lambda V: V), (lambda s_: s_)
    else:
        vsk = qc.sound_speeds(law, spec.w_plus)[1]
        sgn = 1.0 if spec.V > vsk else -1.0
        to_s = lambda V: np.log(abs(V - vsk))  # noqa: E731
        to_V = lambda s_: vsk + sgn * np.exp(s_)  # noqa: E731
    s0, s_t = to_s(sp.V), to_s(spec.V)
    ds = (s_t - s0) / 4.0
    prev = None  # (s, x) of the point before the current one
    steps = 0
    while steps < max_steps and left() > 0:
        last = abs(s_t - s0) <= abs(ds)
        s1 = s_t if last else s0 + ds
        V1 = spec.V if last else float(to_V(s1))
        sp1 = respec(law, spec, V1)
        if prev is not None:
            pred = x + (x - prev[1]) * ((s1 - s0) / (s0 - prev[0]))
        else:
            pred = qc_shift_predictor(law, sp1, x, N, sp)(N)
        o = newton(
            build_system(law, sp1, N, m, K),
            pred,
            tols.res_tol,
            min(25, max_iter),
            jacobian,
            max(1.0, left()),
        )
        steps += 1
        if o.converged:
            prev = (s0, x)
            sp, x, s0 = sp1, o.x, s1
            if last:
                return x, N, f"continuation from V={V_start:.6g} in {steps} steps on N={N}"
            ds *= 1.5
        else:
            ds *= 0.5
            if abs(ds) < 1e-9 * abs(s_t - to_s(V_start)):
                break
    return None, 0, f"continuation stalled at V={sp.V:.8g} after {steps} steps"
