"""Discrete superkinks and solitary waves (paper §5) as fixed points of the one-period-and-shift
map (eqs. period, nonlin_map, nonlin_system, fixedBCs).

    r = solve_superkink(law, V, branch="lower", N=None, tol=1e-12)
    r = solve_solitary(law, w_plus, V, N=None, tol=1e-12)

Route: QC closed form (eqs. SKsoln_cubic, SWsoln_cubic) → initial guess w_n(0) = w_QC(n), ẇ_n(0) =
−V w_QC′(n) (ansatz ξ = n − V t) → damped Newton with the exact banded Jacobian
(:mod:`fpucore.wave.system`).  If that fails: solve on the shorter automatic chain and grow N, then
continuation in V from a velocity where the QC guess converges (:mod:`fpucore.wave.continuation`).
N=None picks N from the wave's width (:mod:`fpucore.wave.tails`).  The RK step count m is chosen by
step doubling so the integrator error stays at the tolerance, and re-checked at the solution."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from dataclasses import replace as _replace
from typing import ClassVar

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.law import require_law
from fpucore.result import Result, status_of
from fpucore.wave import period_map as pm
from fpucore.wave import plateau as wp
from fpucore.wave import tails as wt
from fpucore.wave.continuation import continue_to
from fpucore.wave.setup import (
    M_STEPS,
    Spec,
    build_system,
    choose_K,
    choose_m,
    choose_N,
    qc_guess,
    required_N,
    resize,
    solitary_spec,
    superkink_spec,
)
from fpucore.wave.system import NewtonOutcome, WaveSystem, newton


@dataclass(frozen=True)
class WaveResult(Result):
    """A discrete traveling wave at t = 0 and its error budget.

    kind : "superkink" | "tensile" | "compressive".  V : velocity.  N : sites n = −N/2 … N/2−1.
    n : (N,) int64 site indices; w, wdot : (N,) w_n(0), ẇ_n(0).  w_left, w_right : the fixed
    boundary strains w_{−N/2−1}, w_{N/2} (eq. fixedBCs).  w_plus : state ahead (the superkink's
    w₊ for solitary waves, whose background is w_B = w_left = w_right).
    residual : max-norm of eq. nonlin_system; dropped_residual : |ẇ_{N/2}(T) − ẇ_{N/2−1}(0)|.
    tail_error : |w − w_∞|, |ẇ| at the 3 outermost sites per end (truncation by finite N).
    integrator_error : step-doubling |Φ_m − Φ_2m| at the solution (m RK steps per period).
    jacobian_truncation : largest tangent-window edge value (neglected Jacobian entries < it).
    amplitude : |w(0) − w_B| (solitary, paper's w_amp) or |w_left − w_right| (superkink).
    energy : E_ren^D of eq. Eren_D (solitary waves; NaN for superkinks, whose two backgrounds
    differ).  qc_max_deviation : max_n |w_n − w_QC(n)|.  route : how it converged.
    """

    kind: str
    V: float
    N: int
    n: np.ndarray
    w: np.ndarray
    wdot: np.ndarray
    w_left: float
    w_right: float
    w_plus: float
    law: object
    residual: float
    dropped_residual: float
    converged: bool
    iterations: int
    residual_history: tuple
    elapsed_s: float
    message: str
    amplitude: float
    energy: float
    qc_max_deviation: float
    tail_error: float
    integrator_error: float
    jacobian_truncation: float
    m: int
    K: int
    jacobian: str
    route: str
    v: np.ndarray
    branch: str | None = None
    front_uncertainty: float = math.nan  # sites; flat-top waves near V_SK only (wave_plateau)

    ERROR_FIELDS: ClassVar = (
        "residual",
        "dropped_residual",
        "tail_error",
        "integrator_error",
        "jacobian_truncation",
    )
    DERIVED: ClassVar = ("status",)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def T(self) -> float:
        return 1.0 / self.V

    def as_dict(self, profile: bool = True, arrays: bool | None = None) -> dict:
        """Every field (see :meth:`fpucore.result.Result.as_dict`); ``profile=False`` leaves out the
        arrays n, w, wdot, v."""
        return Result.as_dict(self, arrays=profile if arrays is None else arrays)


# =============================================================================== solver core
def _solve(law, spec: Spec, N, tol, jacobian, max_iter, time_budget_s, predictor=None):
    t0 = time.perf_counter()
    N = choose_N(law, spec, N, tol)
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    # residual and integrator tolerances are relative to the strain scale: the round-off floor of
    # eq. nonlin_system grows with |w| (b = 100 or a = -0.01 stagnate at ~3e-14 x scale > 1e-12)
    int_tol = res_tol = tol * scale
    x0 = predictor(N) if predictor is not None else qc_guess(spec, N)
    m = choose_m(law, spec, x0, N, int_tol)
    K = choose_K(law, spec, x0, m)
    sysN = build_system(law, spec, N, m, K)
    hist: list = []
    routes: list[str] = []

    tail_ok = 1e-5 * spec.amplitude_qc + 1e3 * tol * scale
    bad_tails: list[float] = []

    def run(sys_, x, budget_left):
        o = newton(sys_, x, res_tol, max_iter, jacobian, max(1.0, budget_left))
        hist.extend(o.residual_history)
        if o.converged:  # a fixed point whose tails miss the boundary states is another wave
            te = wt.tail_error(o.x[0::2], o.x[1::2], spec.w_left, spec.w_right)
            if te > tail_ok:
                bad_tails.append(te)
                o = _replace(
                    o,
                    converged=False,
                    message=f"converged to a wave whose tails miss "
                    f"the boundary states (tail error {te:.3g}); try a larger N",
                )
        return o

    left = lambda: time_budget_s - (time.perf_counter() - t0)  # noqa: E731
    gx = _half_plateau(spec) if predictor is None else 0.0
    if gx >= wp.GX_DIRECT:  # flat top near V_SK: the fixed-V system cannot fix the plateau length
        out, note = _plateau_route(law, spec, N, m, K, tol, max_iter, left, run)
        routes.append(note)
    else:
        out = _solve_ordinary(
            law, spec, N, m, K, tol, jacobian, max_iter, predictor, x0, sysN, run, left, routes
        )
        if not out.converged and gx >= wp.GX_FALLBACK and left() > 0:
            out2, note = _plateau_route(law, spec, N, m, K, tol, max_iter, left, run)
            routes.append(note)
            out = out2 if out2.converged else out
    # integrator error at the solution; refine m if the guess-based choice was optimistic
    x = out.x
    ierr = _integrator_error(law, spec, x, m)
    while out.converged and ierr > 10 * int_tol and m < M_STEPS[-1] and left() > 0:
        m = next(mm for mm in M_STEPS if mm > m)
        sysN = build_system(law, spec, N, m, K)
        out = run(sysN, x, left())
        x = out.x
        ierr = _integrator_error(law, spec, x, m)
        routes.append(f"m->{m}")
    extra, fu = "", math.nan
    if gx >= wp.GX_FALLBACK:
        extra, fu = _plateau_note(spec, sysN, out, res_tol, gx)
        if fu > wp.FRONT_MAX:  # residual ≤ tol, but the plateau length is not determined
            v_sk = qc.sound_speeds(law, spec.w_plus)[1]
            d_ok = 2.0 * abs(spec.V - v_sk) * fu / wp.FRONT_MAX  # σ_min ∝ |V − V_SK|
            v_ok = v_sk + math.copysign(d_ok, spec.V - v_sk)
            out = _replace(
                out,
                converged=False,
                message=f"plateau length undetermined: front position +-{fu:.2g} sites "
                f"(> {wp.FRONT_MAX:g}) although the residual is {out.residual:.2g}. Near "
                f"V_SK = {v_sk!r} the wave is a flat-top kink-antikink bundle whose plateau "
                "length is only exponentially weakly tied to V (the Jacobian's smallest "
                "singular value falls like |V - V_SK|); the nearest solvable V is about "
                f"{v_ok!r}",
            )
    return _result(law, spec, N, m, K, out, hist, ierr, jacobian, "; ".join(routes), t0, extra, fu)


def _solve_ordinary(
    law, spec, N, m, K, tol, jacobian, max_iter, predictor, x0, sysN, run, left, routes
):
    """The default route: QC guess (or predictor), then rescues 1–3."""
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    out = run(sysN, x0, left())
    routes.append("predictor" if predictor is not None else "qc-guess")
    # rescue 1: far-field directions are nearly null at large N: converge short, then grow N
    N_s = required_N(law, spec, 0.1 * tol * scale)
    if not out.converged and left() > 0 and N_s < N:
        o_s = run(
            build_system(law, spec, N_s, m, K),
            resize(x0, N, N_s, spec.w_left, spec.w_right),
            left(),
        )
        if o_s.converged:
            out = run(sysN, resize(o_s.x, N_s, N, spec.w_left, spec.w_right), left())
            routes.append(f"grow-N from {N_s}")
    # rescue 2: a short chain can trap Newton on a wave clipped by the ends: solve long, cut
    N_b = max(4 * N, 256)
    if not out.converged and left() > 0 and N < 256 and predictor is None:
        o_b = run(build_system(law, spec, N_b, m, K), qc_guess(spec, N_b), left())
        if o_b.converged:
            out = run(sysN, resize(o_b.x, N_b, N, spec.w_left, spec.w_right), left())
            routes.append(f"cut-N from {N_b}")
    # rescue 3: continuation in V from the family's easy end
    if not out.converged and left() > 0 and predictor is None:
        x_c, N_c, note = continue_to(law, spec, tol, jacobian, left(), max_iter)
        routes.append(note)
        if x_c is not None:
            out = run(sysN, resize(x_c, N_c, N, spec.w_left, spec.w_right), left())
    return out


# =============================================================================== flat tops
def _half_plateau(spec: Spec) -> float:
    """QC γ·x_f for solitary waves (how long the flat top is), 0 for superkinks."""
    if spec.kind == "superkink":
        return 0.0
    return wp.qc_half_plateau(spec.qcw)


def _plateau_route(law, spec: Spec, N, m, K, tol, max_iter, left, run):
    """Continuation in plateau mass (:mod:`fpucore.wave.plateau`) from a short-plateau wave on
    the same side of V_SK, then a polish at fixed V with the ordinary pinning.
    Returns (NewtonOutcome, note)."""
    v_sk = qc.sound_speeds(law, spec.w_plus)[1]
    sgn = 1.0 if spec.V > v_sk else -1.0
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    t_end = time.perf_counter() + left()
    r0 = None
    for g in wp.GX_START:
        if left() <= 0:
            break
        d0 = wp.start_delta(law, spec.w_plus, v_sk, sgn, g)
        if d0 <= abs(spec.V - v_sk):
            continue
        sp0 = solitary_spec(law, spec.w_plus, v_sk + sgn * d0)
        r0 = _solve(law, sp0, N, tol, "exact", max_iter, max(1.0, left()), None)
        if r0.converged:
            break
    x_best = qc_guess(spec, N)
    if r0 is None or not r0.converged:
        return run(build_system(law, spec, N, m, K), x_best, min(left(), 1.0)), (
            "plateau route: no converged short-plateau start wave"
        )
    x0 = np.empty(2 * N)
    x0[0::2], x0[1::2] = r0.w, r0.wdot
    path = wp.continue_in_mass(law, spec.w_plus, spec.V, x0, r0.V, N, m, K, tol * scale, t_end)
    note = f"plateau route from |V-V_SK|={r0.V - v_sk:+.2g}: {path.note}"
    x_p = path.x if path.x is not None else x_best
    out = run(build_system(law, spec, N, m, K), x_p, max(1.0, left()))
    if not out.converged:
        out = _replace(out, message=_plateau_refusal(out.message, path, v_sk))
    return out, note


def _plateau_refusal(msg: str, path, v_sk: float) -> str:
    near = f"; the nearest solvable V is about {path.V!r}" if path.x is not None else ""
    return (
        f"{msg}. Near V_SK = {v_sk!r} the wave is a flat-top kink-antikink bundle whose plateau "
        "length is only exponentially weakly tied to V (the Jacobian's smallest singular value "
        "falls like |V - V_SK|, its singular vector moves the two fronts apart), so the "
        f"residual cannot fix the plateau in double precision{near}"
    )


def _plateau_note(spec: Spec, sys_: WaveSystem, out, res_tol, gx):
    """Front-position error bar along the near-null direction (see wave_plateau)."""
    if not out.converged:
        return "", math.nan
    u = wp.front_uncertainty(sys_, out.x, res_tol)
    if u is None:
        return "", math.nan
    f = wp.half_plateau(out.x[0::2], spec.w_left)
    return (
        f"; flat top (QC gamma*x_f = {gx:.1f}): fronts at +-{f:.3f} sites, plateau-length "
        f"uncertainty +-{u.sites:.2g} sites from round-off (residual {u.residual_2:.2g} / "
        f"sigma_min {u.sigma_min:.2g}; +-{u.sites_at_tol:.2g} at the acceptance tolerance)",
        u.sites,
    )


def _integrator_error(law, spec: Spec, x: np.ndarray, m: int) -> float:
    return pm.step_doubling_error(law, x[0::2], x[1::2], 1.0 / spec.V, m, spec.w_left, spec.w_right)


def particle_velocities(w: np.ndarray, wdot: np.ndarray, V: float, w_left: float) -> np.ndarray:
    """Particle velocities v_n(0) for n = −N/2−1 … N/2−1 (N+1 values) of a traveling wave.

    Derivation: eq. FPUsystem gives ẇ_n = v_n − v_{n−1} at every t, so at t = 0
        v_n = v_{−N/2−1} + Σ_{k=−N/2}^{n} ẇ_k(0).
    The boundary strain w_{−N/2−1} is held fixed, so particle −N/2−1 moves with the constant
    far-field velocity v_−.  The traveling-wave ansatz u_n(t) = U(n − Vt) gives v = −V U′ and
    w(ξ) = U(ξ) − U(ξ−1), which fixes v only up to a Galilean constant; the Rankine–Hugoniot
    condition (eq. RHconds) −V(w₊ − w₋) = v₊ − v₋ holds for v_± = −V w_±, the normalisation the
    paper's renormalisation (−½V² w_B², eqs. Eren_QC, Eren_D) assumes.  Hence
    v_{−N/2−1} = −V w_left; the other end then returns v_{N/2−1} ≈ −V w_right up to the tail
    error (checked in tests).
    """
    v = np.empty(w.size + 1)
    v[0] = -V * w_left
    v[1:] = v[0] + np.cumsum(wdot)
    return v


def renormalized_energy(law, w, wdot, V, w_left, w_right, w_B) -> float:
    """E_ren^D (eq. Eren_D): Σ_n {½v_n² + ½(Φ(w_n) + Φ(w_{n+1})) − Φ(w_B) − ½V²w_B²} over the
    particles n = −N/2−1 … N/2−1 (particle n sits between springs w_n and w_{n+1}); beyond the
    chain the summand vanishes to the tail error."""
    v = particle_velocities(w, wdot, V, w_left)
    ws = np.concatenate([[w_left], w, [w_right]])
    ph = law.phi(ws)
    terms = 0.5 * v**2 + 0.5 * (ph[:-1] + ph[1:]) - float(law.phi(w_B)) - 0.5 * V * V * w_B**2
    return float(math.fsum(terms))


def _result(
    law, spec, N, m, K, out: NewtonOutcome, hist, ierr, jacobian, route, t0, extra="", fu=math.nan
):
    x = out.x
    w, wd = x[0::2].copy(), x[1::2].copy()
    n = np.arange(N, dtype=np.int64) - N // 2
    with np.errstate(over="ignore"):
        dev = float(np.max(np.abs(w - spec.qcw.profile(n.astype(float)))))
    if spec.kind == "superkink":
        amp, energy = abs(spec.w_left - spec.w_right), math.nan
    else:
        amp = abs(w[N // 2] - spec.w_left)
        energy = renormalized_energy(law, w, wd, spec.V, spec.w_left, spec.w_right, spec.w_left)
    v = particle_velocities(w, wd, spec.V, spec.w_left)
    msg = out.message
    if out.converged:
        msg = f"converged: residual {out.residual:.3g} in {len(hist) - 1} iterations ({route})"
        msg += extra
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
        law=law,
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
        integrator_error=ierr,
        jacobian_truncation=out.jacobian_truncation,
        m=m,
        K=K,
        jacobian=jacobian,
        route=route,
        v=v,
        branch=spec.branch,
        front_uncertainty=fu,
    )


def _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor):
    require_law(law)
    if predictor is not None and not callable(predictor):
        raise ParameterError("predictor", type(predictor).__name__, "None or a callable N -> x0")
    tol = require_finite("tol", tol)
    if not (1e-15 <= tol <= 1e-3):
        raise ParameterError("tol", tol, "[1e-15, 1e-3]")
    if not isinstance(jacobian, str) or jacobian not in ("exact", "fd"):
        raise ParameterError("jacobian", jacobian, "'exact' or 'fd'")
    require_int("max_iter", max_iter, 1, 1000)
    time_budget_s = require_finite("time_budget_s", time_budget_s)
    if time_budget_s <= 0:
        raise ParameterError("time_budget_s", time_budget_s, "> 0")
    return tol, time_budget_s


# =============================================================================== public API
def solve_superkink(
    law,
    V: float,
    branch: str = "lower",
    N: int | None = None,
    tol: float = 1e-12,
    jacobian: str = "exact",
    max_iter: int = 40,
    time_budget_s: float = 300.0,
    predictor=None,
) -> WaveResult:
    """Discrete superkink with velocity V (paper §5), pinned by w_1(T) = w* (eq. nonlin_system).

    V must lie in the superkink interval of eq. V_bounds_cubic; branch "lower" (w₊ < w* < w₋,
    a front with w′ < 0) or "upper" (mirror image).  Boundary strains: w_left = w₋, w_right = w₊
    (eq. fixedBCs, w± from eq. wpm_cubic).  N=None: automatic from the wave's width.
    jacobian="fd" uses the paper's finite-difference Jacobian (dense; slow, for comparison).
    tol: Newton stops at residual <= tol x max(1, |w_left|, |w_right|) (relative to the strain
    scale); the step count m keeps the step-doubling error below the same bound.
    Non-convergence returns converged=False with the reason in ``message``.
    """
    tol, time_budget_s = _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor)
    spec = superkink_spec(law, require_finite("V", V), branch)
    return _solve(law, spec, N, tol, jacobian, max_iter, time_budget_s, predictor)


def solve_solitary(
    law,
    w_plus: float,
    V: float,
    N: int | None = None,
    tol: float = 1e-12,
    jacobian: str = "exact",
    max_iter: int = 40,
    time_budget_s: float = 300.0,
    predictor=None,
) -> WaveResult:
    """Discrete solitary wave for the state w₊ ahead of the associated superkink (paper §5).

    V in (c₊, V_SK) (background w_B = w₊) or (V_SK, c₋) (w_B = w_S(V), eq. wB); pinning
    ẇ_1(T) = 0 puts the extremum at n = 0; boundary strains w_left = w_right = w_B.
    tol is relative to the strain scale, as in :func:`solve_superkink`.
    """
    tol, time_budget_s = _check_common(law, tol, jacobian, max_iter, time_budget_s, predictor)
    spec = solitary_spec(law, require_finite("w_plus", w_plus), require_finite("V", V))
    return _solve(law, spec, N, tol, jacobian, max_iter, time_budget_s, predictor)


def warm(law) -> None:
    """Compile/load every jitted route used here (for ``fpucore.warm``): one small superkink."""
    lo, hi = qc.superkink_velocity_bounds(law)
    solve_superkink(law, 0.5 * (lo + hi), N=64)
