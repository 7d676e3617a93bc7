"""Discrete superkinks and solitary waves (paper §5) as fixed points of the one-period-and-shift
map (eqs. period, nonlin_map, nonlin_system, fixedBCs).

    r = solve_superkink(law, V, branch="lower", N=None, tol=1e-12)
    r = solve_solitary(law, w_plus, V, N=None, tol=1e-12)

Route: QC closed form (eqs. SKsoln_cubic, SWsoln_cubic) → initial guess w_n(0) = w_QC(n), ẇ_n(0) =
−V w_QC′(n) (ansatz ξ = n − V t) → damped Newton with the exact banded Jacobian
(:mod:`fpucore.wave.system`), stopping on the size of the correction.  If that fails: solve on the
shorter automatic chain and grow N (or, on a short chain, solve long and cut), then continuation
in V from a velocity where the QC guess converges (:mod:`fpucore.wave.continuation`); flat tops
near V_SK by continuation in plateau mass (:mod:`fpucore.wave.plateau`) — the attempt logic is
:class:`fpucore.wave.attempt.WaveSolve`, everything derived from the wave alone (tolerances, N,
m, K, the system) is a method of its :class:`fpucore.wave.setup.Spec`.
Error bounds against the infinite chain's exact wave: :mod:`fpucore.wave.bounds`.
N=None picks N from the wave's width (:mod:`fpucore.wave.tails`).  The RK step count m is chosen by
step doubling so the integrator error stays at the tolerance, and re-checked at the solution."""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np

from fpucore import qc
from fpucore.budget import require_time_budget
from fpucore.errors import ParameterError, require_finite, require_int, require_tol
from fpucore.law import require_law
from fpucore.parallel.threads import on_budget
from fpucore.wave import bounds as wb
from fpucore.wave import period_map as pm
from fpucore.wave import tails as wt
from fpucore.wave.attempt import Solved, WaveSolve
from fpucore.wave.observables import particle_velocities, renormalized_energy
from fpucore.wave.setup import Spec, solitary_spec, superkink_spec
from fpucore.wave.wave_result import WaveResult

if TYPE_CHECKING:
    from collections.abc import Callable

    from fpucore.law.base import HardeningSofteningLaw


# =============================================================================== solver core
def _solve(spec: Spec, N, tol, jacobian, max_iter, time_budget_s, predictor=None):
    t0 = time.perf_counter()
    done = WaveSolve(spec, N, tol, jacobian, max_iter, time_budget_s, predictor).solve()
    return _result(spec, done, jacobian, tol, t0)


def _bounds(spec: Spec, done: Solved):
    """Error bounds at the solution (:mod:`.bounds`); without a factorisation (Newton stopped
    before one) only the integrator error is known and the bounds are infinite."""
    out, S = done.out, done.system
    solitary = spec.kind != "superkink"
    if done.bounds is not None:
        return done.bounds
    if out.factorization is None:
        x = out.x
        ierr = pm.step_doubling_error(S.law, x[0::2], x[1::2], S.T, S.m, spec.w_left, spec.w_right)
        e = (
            renormalized_energy(
                S.law, x[0::2], x[1::2], S.V, spec.w_left, spec.w_right, spec.w_left
            )
            if solitary
            else math.nan
        )
        inf = math.inf
        return wb.WaveBounds(
            inf, inf if solitary else 0.0, inf if solitary else math.nan, e, ierr, inf, inf, inf
        )
    return wb.error_bounds(S, out.x, out.factorization, solitary)


def newton_count(iterations: int) -> str:
    """How the residual was reached: "in 3 iterations", "in 1 iteration", or, when the start
    wave (the route's construction: QC guess, continuation, plateau) met the tolerance as it
    was, "with no Newton step: the start wave met the tolerance"."""
    if iterations == 0:
        return "with no Newton step: the start wave met the tolerance"
    return f"in {iterations} iteration" + ("" if iterations == 1 else "s")


def crossing_note(spec: Spec, w: np.ndarray, wd: np.ndarray, m: int) -> str:
    """For a piecewise-linear law: how many breakpoint crossings one period of the wave locates
    and how transversal they are (the smallest |ẇ| of a site at its crossing, against V × the
    amplitude); "" for a smooth law.  A crossing slower than 1e-3 of that scale is named as
    near-tangential: the located map's order is not guaranteed there (integrator_error, step
    doubling, still measures it)."""
    if not hasattr(spec.law, "breakpoints"):
        return ""
    r = pm.integrate(spec.law, w, wd, 1.0 / spec.V, m, spec.w_left, spec.w_right)
    if r.crossings == 0:
        return "; no breakpoint crossing in a period"
    scale = spec.V * max(spec.amplitude_qc, abs(spec.w_left - spec.w_right))
    note = (
        f"; {r.crossings} breakpoint crossings located per period, smallest |wdot| at a "
        f"crossing {r.crossing_speed:.3g}"
    )
    if r.crossing_speed < 1e-3 * scale:
        return note + " (near-tangential: the located map's order is not guaranteed there)"
    return note + " (transversal)"


def _result(spec: Spec, done: Solved, jacobian: str, tol: float, t0: float) -> WaveResult:
    out, N, hist, route = done.out, done.N, done.history, done.route
    bd = _bounds(spec, done)
    x = out.x
    w, wd = x[0::2].copy(), x[1::2].copy()
    n = np.arange(N, dtype=np.int64) - N // 2
    with np.errstate(over="ignore"):
        dev = float(np.max(np.abs(w - spec.qcw.profile(n.astype(float)))))
    if spec.kind == "superkink":
        amp, energy = abs(spec.w_left - spec.w_right), math.nan
    else:
        amp, energy = abs(w[N // 2] - spec.w_left), bd.energy_value
    v = particle_velocities(w, wd, spec.V, spec.w_left)
    msg = out.message
    if out.converged:
        msg = f"converged: residual {out.residual:.3g} {newton_count(len(hist) - 1)} ({route})"
        if done.residual_floor > spec.tolerances(tol).res_tol:
            msg += (
                f"; the requested tol is below the round-off floor of this law: residual "
                f"accepted at {done.residual_floor:.2g} (achievable), profile error "
                f"{bd.profile:.2g}"
            )
        msg += done.note + crossing_note(spec, w, wd, done.m)
    else:
        msg = f"NOT converged ({route}): {msg}"
    return WaveResult(
        kind=spec.kind,
        V=spec.V,
        N=N,
        n=n,
        w=w,
        wdot=wd,
        w_left=spec.w_left,
        w_right=spec.w_right,
        w_plus=spec.w_plus,
        law=spec.law,
        residual=out.residual,
        dropped_residual=out.dropped_residual,
        converged=out.converged,
        iterations=len(hist) - 1,
        residual_history=tuple(hist),
        elapsed_s=time.perf_counter() - t0,
        message=msg,
        amplitude=amp,
        energy=energy,
        qc_max_deviation=dev,
        tail_error=wt.tail_error(w, wd, spec.w_left, spec.w_right),
        integrator_error=bd.integrator_error,
        jacobian_truncation=out.jacobian_truncation,
        profile_error=bd.profile,
        amplitude_error=bd.amplitude,
        energy_error=bd.energy,
        residual_floor=done.residual_floor,
        m=done.m,
        K=done.K,
        jacobian=jacobian,
        route=route,
        v=v,
        branch=spec.branch,
        front_uncertainty=done.front_uncertainty,
    )


def _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor):
    require_law(law)
    if predictor is not None and not callable(predictor):
        raise ParameterError("predictor", type(predictor).__name__, "None or a callable N -> x0")
    tol = require_tol(tol)
    if not isinstance(jacobian, str) or jacobian not in ("exact", "fd"):
        raise ParameterError("jacobian", jacobian, "'exact' or 'fd'")
    require_int("max_iter", max_iter, 1, 1000)
    return tol, require_time_budget(time_budget_s, none_ok=False)


# =============================================================================== public API
@on_budget
def solve_superkink(
    law: HardeningSofteningLaw,
    V: float,
    branch: str = "lower",
    N: int | None = None,
    tol: float = 1e-12,
    jacobian: str = "exact",
    max_iter: int = 40,
    time_budget_s: float = 300.0,
    predictor: Callable[[int], np.ndarray] | None = None,
) -> WaveResult:
    """Discrete superkink with velocity V (paper §5), pinned by w_1(T) = w* (eq. nonlin_system).

    V must lie in the superkink interval of eq. V_bounds_cubic; branch "lower" (w₊ < w* < w₋,
    a front with w′ < 0) or "upper" (mirror image).  Boundary strains: w_left = w₋, w_right = w₊
    (eq. fixedBCs, w± from eq. wpm_cubic).  N=None: automatic from the wave's width.
    jacobian="fd" uses the paper's finite-difference Jacobian (dense; slow, for comparison).
    tol: relative to the strain scale s = max(1, |w_left|, |w_right|) — Newton accepts residual
    <= tol·s and then steps on until its next correction is <= tol·s or stops shrinking
    (round-off); the step count m keeps the step-doubling error below the same bound
    (:class:`fpucore.wave.setup.Tolerances`).  Where round-off exceeds tol·s (stiff laws) the
    achievable level is used and reported (``residual_floor``, ``message``).  The result carries
    bounds against the infinite chain's exact wave (``profile_error`` …, :mod:`.bounds`).
    Non-convergence returns converged=False with the reason in ``message``.
    time_budget_s : CPU seconds of the solving thread (:func:`fpucore.budget.work_clock`), so
    that a busy machine takes longer but computes the same wave.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w) = a w³ + b w² + w (or another hardening–softening law).
    V : float
        Wave velocity, sites per unit time, inside the superkink interval (eq. V_bounds_cubic).
    branch : {"lower", "upper"}
        Which superkink of the pair at V.
    N : int or None
        Number of sites (even, in [N_MIN, N_MAX] of :mod:`fpucore.wave.tails` and wide enough
        for the tails); None chooses N from the wave's width.
    tol : float
        Relative tolerance in [1e-15, 1e-3], relative to the strain scale s (see above).
    jacobian : {"exact", "fd"}
        Exact banded Jacobian from the tangent flow, or the paper's finite differences.
    max_iter : int
        Newton iterations, in [1, 1000].
    time_budget_s : float
        CPU seconds of the solving thread, in (0, 1e9].
    predictor : callable or None
        ``predictor(N) -> x0``, an initial interleaved state (w_n, ẇ_n) of shape (2N,); None
        uses the QC profile.

    Returns
    -------
    WaveResult
        The wave on N sites (``w``, ``wdot`` of shape (N,), period T = 1/V in time units), its
        error bounds, run time, ``converged`` and ``message``.

    Raises
    ------
    ParameterError
        When ``law``, ``V``, ``branch``, ``N``, ``tol``, ``jacobian``, ``max_iter``,
        ``time_budget_s`` or ``predictor`` is out of range (V also when the wave is too wide
        for N_MAX sites).
    """
    tol, time_budget_s = _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor)
    spec = superkink_spec(law, require_finite("V", V), branch)
    return _solve(spec, N, tol, jacobian, max_iter, time_budget_s, predictor)


@on_budget
def solve_solitary(
    law: HardeningSofteningLaw,
    w_plus: float,
    V: float,
    N: int | None = None,
    tol: float = 1e-12,
    jacobian: str = "exact",
    max_iter: int = 40,
    time_budget_s: float = 300.0,
    predictor: Callable[[int], np.ndarray] | None = None,
) -> WaveResult:
    """Discrete solitary wave for the state w₊ ahead of the associated superkink (paper §5).

    V in (c₊, V_SK) (background w_B = w₊) or (V_SK, c₋) (w_B = w_S(V), eq. wB); pinning
    ẇ_1(T) = 0 puts the extremum at n = 0; boundary strains w_left = w_right = w_B.
    tol is relative to the strain scale, as in :func:`solve_superkink`.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ ahead of the associated superkink (selects the family).
    V : float
        Wave velocity, sites per unit time, in (c₊, V_SK) ∪ (V_SK, c₋).
    N : int or None
        Number of sites (even, in [N_MIN, N_MAX], wide enough for the tails); None: automatic.
    tol : float
        Relative tolerance in [1e-15, 1e-3], relative to the strain scale.
    jacobian : {"exact", "fd"}
        Exact banded Jacobian, or the paper's finite differences.
    max_iter : int
        Newton iterations, in [1, 1000].
    time_budget_s : float
        CPU seconds of the solving thread, in (0, 1e9].
    predictor : callable or None
        ``predictor(N) -> x0``, an initial interleaved state (w_n, ẇ_n) of shape (2N,); None
        uses the QC profile.

    Returns
    -------
    WaveResult
        The wave on N sites (``w``, ``wdot`` of shape (N,)), its error bounds, run time,
        ``converged`` and ``message``.

    Raises
    ------
    ParameterError
        When ``law``, ``w_plus``, ``V``, ``N``, ``tol``, ``jacobian``, ``max_iter``,
        ``time_budget_s`` or ``predictor`` is out of range.
    """
    tol, time_budget_s = _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor)
    spec = solitary_spec(law, require_finite("w_plus", w_plus), require_finite("V", V))
    return _solve(spec, N, tol, jacobian, max_iter, time_budget_s, predictor)


def warm(law: HardeningSofteningLaw) -> None:
    """Compile/load every jitted route used here (for ``fpucore.warm``): one small superkink.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The law whose superkink at the middle of its velocity interval is solved on N = 64 sites.

    Returns
    -------
    None
    """
    lo, hi = qc.superkink_velocity_bounds(law)
    solve_superkink(law, 0.5 * (lo + hi), N=64)
