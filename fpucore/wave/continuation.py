"""Continuation in V for discrete traveling waves (paper §5, Figs. TWcubic, SWs_cubic_DvsQC,
SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC).

Predictor.  From a converged wave x(V₀) the guess at V₁ is x(V₀) + [x_QC(V₁) − x_QC(V₀)]
(:meth:`fpucore.wave.setup.Spec.shifted`): the QC closed form carries the large, known change of
the profile and the discrete correction x − x_QC, which varies slowly in V, is carried over.

:func:`solve_from_neighbour` is the one step of every family walk (:mod:`.family`, the atlas
rows).  :func:`continue_to` is the rescue used by ``wave.solve_*`` when Newton from the QC guess
fails: find a nearby velocity (towards the family's easy end, then the middle of its interval)
where the QC guess converges, then march to the target with adaptive steps (halve on failure,
grow on success).
"""

from __future__ import annotations

import numpy as np

from fpucore.budget import work_clock
from fpucore.wave.setup import Spec, Tolerances
from fpucore.wave.system import newton


def solve_from_neighbour(spec: Spec, prev, solve):
    """One step of a family walk (wave families, atlas rows): ``solve(predictor)`` from the
    neighbour's predictor (:meth:`Spec.neighbour_predictor`, prev = (wave, its spec) or None),
    again from the QC guess (``solve(None)``) if there is none or it does not converge."""
    pred = spec.neighbour_predictor(prev)
    r = solve(pred) if pred is not None else None
    if r is None or not r.converged:
        r = solve(None)
    return r


def continue_to(
    spec: Spec,
    tols: Tolerances,
    jacobian: str,
    deadline: float,
    max_iter: int = 40,
    max_steps: int = 80,
    N_cap: int = 4000,
):
    """March in V from a velocity where the QC guess converges to spec.V.

    Start candidates lie towards the family's easy end (:meth:`Spec.easy_end`), then towards the
    middle of V's interval.  The path runs on the shortest chain that holds both ends
    (automatic N, at most N_cap sites).  tols : the solve's tolerances (its residual, step-count
    and tail tolerances serve every point of the path); deadline : the solve's time limit on
    the :func:`~fpucore.budget.work_clock` (CPU s).  Returns (x, N, note) with x the interleaved
    state at spec.V on N sites, or (None, 0, note) on failure.
    """

    def left() -> float:
        return deadline - work_clock()

    lo, hi = spec.interval()
    easy, mid = spec.easy_end(), 0.5 * (lo + hi)
    N_t = spec.required_N(tols.tail_tol)
    start = None
    tries = [(easy, 0.3), (easy, 0.6), (easy, 0.85), (mid, 0.3), (mid, 0.7)]
    if hasattr(spec.law, "breakpoints"):  # PL solitary waves: only close to V_SK (Spec.easy_end)
        tries.insert(3, (easy, 0.95))
    for target, frac in tries:
        if left() <= 0:
            break
        Vs = spec.V + frac * (target - spec.V)
        if not lo < Vs < hi:
            continue
        sp = spec.at(Vs)
        N = max(N_t, sp.required_N(tols.tail_tol))
        if N > N_cap:
            continue
        x0 = sp.first_guess(N)[0]
        # choose_m, not the solve's choose_m_floor: on stiff laws (b = 1000) that moves the path's
        # waves by 1e-9..1e-6 (within their error bars); kept bit-identical to earlier releases
        m = sp.choose_m(x0, tols.int_tol)
        K = sp.choose_K(x0, m)
        o = newton(sp.system(N, m, K), x0, tols.res_tol, max_iter, jacobian, max(1.0, left()))
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
        vsk = spec.v_sk
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
        sp1 = spec.at(V1)
        if prev is not None:
            pred = x + (x - prev[1]) * ((s1 - s0) / (s0 - prev[0]))
        else:
            pred = sp1.shifted(x, N, sp)(N)
        o = newton(
            sp1.system(N, m, K), pred, tols.res_tol, min(25, max_iter), jacobian, max(1.0, left())
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
