"""One discrete-wave solve as an object: the attempt logic of :mod:`.driver` (paper §5).

:class:`~fpucore.wave.setup.Tolerances` holds every tolerance of a solve, derived in one place
(:meth:`Spec.tolerances <fpucore.wave.setup.Spec.tolerances>`) from the user's relative ``tol``
and the strain scale.  :class:`WaveSolve` holds what one solve works with (the spec, which
carries the law; N, m, K, the tolerances, the time budget, the Newton history, the routes
taken) and has one method per route or rescue:

    solve()          the whole solve: ordinary() or plateau(), then refine_m(), check_plateau()
    embedded()       flat tops on a chain longer than they need: solved on the N they need,
                     padded with the background state (the user's N is served, bounds kept)
    ordinary()       QC guess (or a predictor), then grow_N(), cut_N(), continue_in_V()
    plateau()        flat tops near V_SK: continuation in plateau mass (:mod:`.plateau`)
    newton()         one Newton run on a system, with the tail check every route shares

Stiff laws.  The round-off level of eq. nonlin_system grows with |w|, |ẇ| and |f(w)|
(:meth:`WaveSystem.residual_floor`; at b = 1000 the ẇ rows carry ~3e-10 of round-off, above
tol·scale = 1.7e-10).  Newton and the step-count choice therefore aim at
max(tolerance, FLOOR_FACTOR × round-off level) — the achievable tolerance — and the result
reports it (``residual_floor``) instead of failing; the error bounds (:mod:`.bounds`) say what
that costs in the profile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from dataclasses import replace as _replace

import numpy as np

from fpucore.budget import work_clock
from fpucore.wave import bounds as wb
from fpucore.wave import period_map as pm
from fpucore.wave import plateau as wp
from fpucore.wave import tails as wt
from fpucore.wave.continuation import continue_to
from fpucore.wave.setup import FLOOR_FACTOR, M_STEPS, Spec, Tolerances, resize
from fpucore.wave.system import NewtonOutcome, WaveSystem, newton

#: flat tops (QC γ·x_f ≥ wp.GX_FALLBACK) are solved to at least this tol: their plateau length
#: is fixed only by the last digits of the residual (σ_min ∝ |V − V_SK|); measured at
#: V_SK − 1e-11, N = 64: tol 1e-10 gives profile_error 0.65, tol 1e-12 gives 0.05
FLAT_TOP_TOL = 1e-12


@dataclass(frozen=True)
class Solved:
    """What :meth:`WaveSolve.solve` hands to the driver: the final Newton outcome on the final
    system, the Newton history, routes, the step count actually used, the plateau note."""

    out: NewtonOutcome
    system: WaveSystem
    history: tuple
    route: str
    m: int
    K: int
    N: int
    residual_floor: float
    note: str = ""
    front_uncertainty: float = math.nan
    bounds: object = None  # wb.WaveBounds computed by the route itself (embedded flat tops)


@dataclass
class WaveSolve:
    """One solve of eq. nonlin_system for the wave ``spec`` (which carries the law); see the
    module doc.  ``predictor``: a callable N ↦ initial state (continuation), else the QC guess.
    ``time_budget_s``: seconds from construction (:attr:`deadline`)."""

    spec: Spec
    N_req: int | None
    tol: float
    jacobian: str
    max_iter: int
    time_budget_s: float
    predictor: object = None
    # filled in __post_init__ / as the solve proceeds
    tols: Tolerances = field(init=False)
    t0: float = field(init=False)
    N: int = field(init=False)
    m: int = field(init=False)
    K: int = field(init=False)
    x0: np.ndarray = field(init=False, repr=False)
    system: WaveSystem = field(init=False, repr=False)
    history: list = field(init=False, default_factory=list)
    routes: list = field(init=False, default_factory=list)
    floor: float = field(init=False, default=0.0)
    start: str = field(init=False, default="qc-guess")  # what x0 is: route name

    def __post_init__(self):
        self.t0 = work_clock()
        self.gx = 0.0 if self.spec.kind == "superkink" else wp.qc_half_plateau(self.spec.qcw)
        if self.gx >= wp.GX_FALLBACK and self.tol > FLAT_TOP_TOL:
            self.tol = FLAT_TOP_TOL  # said in the route (see FLAT_TOP_TOL)
            self.routes.append(f"flat top: tol tightened to {FLAT_TOP_TOL:g}")
        self.tols = self.spec.tolerances(self.tol)
        self.N = self.spec.choose_N(self.N_req, self.tol)
        pred = self.predictor
        if pred is not None:
            self.x0, self.start = pred(self.N), "predictor"
        else:
            self.x0, self.start = self.spec.first_guess(self.N)
        self.m = self.spec.choose_m_floor(self.x0, self.tols.int_tol)
        self.K = self.spec.choose_K(self.x0, self.m)
        self.system = self.build(self.N)

    # ------------------------------------------------------------------ helpers
    @property
    def law(self):
        return self.spec.law

    @property
    def deadline(self) -> float:
        """End of the time budget on the :func:`~fpucore.budget.work_clock` (CPU seconds of this
        thread: the solve's path does not depend on the machine's load)."""
        return self.t0 + self.time_budget_s

    def left(self) -> float:
        """Seconds left of the time budget."""
        return self.time_budget_s - (work_clock() - self.t0)

    def build(self, N: int) -> WaveSystem:
        return self.spec.system(N, self.m, self.K)

    def resized(self, x: np.ndarray, N_old: int, N_new: int) -> np.ndarray:
        return resize(x, N_old, N_new, self.spec.w_left, self.spec.w_right)

    def newton(self, sys_: WaveSystem, x: np.ndarray, budget: float | None = None) -> NewtonOutcome:
        """Newton on sys_ from x (stopping on the correction, :func:`system.newton`) at the
        achievable residual tolerance; a fixed point whose tails miss the boundary states is
        rejected (it is another wave)."""
        budget = self.left() if budget is None else budget
        floor = FLOOR_FACTOR * sys_.residual_floor(x)
        self.floor = max(self.floor, floor)
        res_tol = max(self.tols.res_tol, floor)
        o = newton(
            sys_,
            x,
            res_tol,
            self.max_iter,
            self.jacobian,
            max(1.0, budget),
            step_tol=self.tols.step_tol,
        )
        self.history.extend(o.residual_history)
        if o.converged:
            te = wt.tail_error(o.x[0::2], o.x[1::2], self.spec.w_left, self.spec.w_right)
            if te > self.tols.tail_ok:
                o = _replace(
                    o,
                    converged=False,
                    message=f"converged to a wave whose tails miss "
                    f"the boundary states (tail error {te:.3g}); try a larger N",
                )
        return o

    # ------------------------------------------------------------------ the solve
    def solve(self) -> Solved:
        gx = self.gx if self.predictor is None else 0.0
        if gx >= wp.GX_FALLBACK and self.N > self.n_work():
            done = self.embedded()
            if done is not None:
                return done
        if gx >= wp.GX_DIRECT:  # flat top near V_SK: fixed-V Newton cannot fix the plateau
            out, note = self.plateau()
            self.routes.append(note)
        else:
            out = self.ordinary()
            if not out.converged and gx >= wp.GX_FALLBACK and self.left() > 0:
                out2, note = self.plateau()
                self.routes.append(note)
                out = out2 if out2.converged else out
        out = self.refine_m(out)
        note, fu = "", math.nan
        if gx >= wp.GX_FALLBACK:
            out, note, fu = self.check_plateau(out, gx)
        return Solved(
            out,
            self.system,
            tuple(self.history),
            "; ".join(self.routes),
            self.m,
            self.K,
            self.N,
            self.floor,
            note,
            fu,
        )

    def n_work(self) -> int:
        """The chain a flat top needs: its tails reach tail_tol (at least N_MIN)."""
        return max(wt.N_MIN, self.spec.required_N(self.tols.tail_tol))

    def embedded(self) -> Solved | None:
        """A flat top on a chain longer than it needs (the explorer's N = 500): solve it on
        n_work() sites, pad with the background state, check the residual on the user's N.

        Why: on the long chain the plateau mode's smallest singular value is measured 22×
        smaller (N = 64: 1.2e-13, N = 500: 5.4e-15, at V_SK − 1e-11), so the residual's
        round-off fixes the plateau to only ±53 sites there against ±0.03 on 64 sites.  The
        padded state is the same wave: Newton on N takes no step (else None: the caller's
        route), and its bounds against the infinite chain's wave are those of the short solve
        (which include its truncation by finite N) and, on the padded sites, the tail deviation
        at the short chain's ends (:func:`fpucore.wave.bounds.embedded`)."""
        N_w = self.n_work()
        sub = WaveSolve(
            self.spec, N_w, self.tol, self.jacobian, self.max_iter, max(1.0, self.left())
        ).solve()
        if not sub.out.converged or sub.out.factorization is None:
            return None
        x = self.resized(sub.out.x, N_w, self.N)
        kept = (self.m, self.K, self.system)
        self.m, self.K = sub.m, sub.K
        self.system = self.build(self.N)
        out = self.newton(self.system, x, max(1.0, self.left()))
        if not out.converged or not np.array_equal(out.x, x):
            self.m, self.K, self.system = kept  # the caller's route starts as it would have
            self.routes.append(f"padding the N = {N_w} solution moved it on N = {self.N}")
            return None
        xs = sub.out.x
        b = wb.error_bounds(sub.system, xs, sub.out.factorization, True)
        b = wb.embedded(
            b, self.law, xs[0::2], xs[1::2], self.spec.V, self.spec.w_left, self.spec.w_right
        )
        route = (
            f"{sub.route}; solved on N = {N_w} (the chain the flat top needs), padded with "
            f"w_B to N = {self.N}: residual on N = {self.N} checked, bounds from N = {N_w} "
            "plus the tails"
        )
        hist = tuple(sub.history) + tuple(self.history)
        floor = max(sub.residual_floor, self.floor)
        return Solved(
            out,
            self.system,
            hist,
            route,
            self.m,
            self.K,
            self.N,
            floor,
            sub.note,
            sub.front_uncertainty,
            b,
        )

    def refine_m(self, out: NewtonOutcome) -> NewtonOutcome:
        """Step-doubling error at the solution; more RK steps if the guess-based m was optimistic
        (up to the round-off level of the map)."""
        x, spec = out.x, self.spec
        T = 1.0 / spec.V
        while out.converged and self.m < M_STEPS[-1] and self.left() > 0:
            ierr = pm.step_doubling_error(
                self.law, x[0::2], x[1::2], T, self.m, spec.w_left, spec.w_right
            )
            floor = max(pm.roundoff_level(self.law, x[0::2], x[1::2], T, 2 * self.m))
            if ierr <= 10 * max(self.tols.int_tol, FLOOR_FACTOR * floor):
                break
            self.m = next(mm for mm in M_STEPS if mm > self.m)
            self.system = self.build(self.N)
            out = self.newton(self.system, x)
            x = out.x
            self.routes.append(f"m->{self.m}")
        return out

    # ------------------------------------------------------------------ ordinary route
    def ordinary(self) -> NewtonOutcome:
        """The default route: QC guess (or predictor), then the rescues."""
        out = self.newton(self.system, self.x0)
        self.routes.append(self.start)
        for rescue in (self.grow_N, self.cut_N, self.continue_in_V):
            if out.converged or self.left() <= 0:
                break
            out = rescue(out)
        return out

    def grow_N(self, out: NewtonOutcome) -> NewtonOutcome:
        """Rescue 1: far-field directions are nearly null at large N: converge short, grow N."""
        N_s = self.spec.required_N(self.tols.tail_tol)
        if N_s >= self.N:
            return out
        o_s = self.newton(self.build(N_s), self.resized(self.x0, self.N, N_s))
        if not o_s.converged:
            return out
        self.routes.append(f"grow-N from {N_s}")
        return self.newton(self.system, self.resized(o_s.x, N_s, self.N))

    def cut_N(self, out: NewtonOutcome) -> NewtonOutcome:
        """Rescue 2: a short chain can trap Newton on a wave clipped by the ends: solve long,
        cut."""
        if self.N >= 256 or self.predictor is not None:
            return out
        N_b = max(4 * self.N, 256)
        o_b = self.newton(self.build(N_b), self.spec.first_guess(N_b)[0])
        if not o_b.converged:
            return out
        self.routes.append(f"cut-N from {N_b}")
        return self.newton(self.system, self.resized(o_b.x, N_b, self.N))

    def continue_in_V(self, out: NewtonOutcome) -> NewtonOutcome:
        """Rescue 3: continuation in V from the family's easy end."""
        if self.predictor is not None:
            return out
        x_c, N_c, note = continue_to(
            self.spec, self.tols, self.jacobian, self.deadline, self.max_iter
        )
        self.routes.append(note)
        if x_c is None:
            return out
        return self.newton(self.system, self.resized(x_c, N_c, self.N))

    # ------------------------------------------------------------------ flat tops
    def plateau(self) -> tuple[NewtonOutcome, str]:
        """Continuation in plateau mass (:mod:`fpucore.wave.plateau`) from a short-plateau wave
        on the same side of V_SK, then a polish at fixed V with the ordinary pinning."""
        spec = self.spec
        v_sk = spec.v_sk
        sgn = 1.0 if spec.V > v_sk else -1.0
        t_end = work_clock() + self.left()
        start = None
        for g in wp.GX_START:
            if self.left() <= 0:
                break
            d0 = wp.start_delta(spec, sgn, g)
            if d0 <= abs(spec.V - v_sk):
                continue
            sp0 = spec.at(v_sk + sgn * d0)
            start = WaveSolve(
                sp0, self.N, self.tol, "exact", self.max_iter, max(1.0, self.left())
            ).solve()
            if start.out.converged:
                break
        x_best = spec.qc_guess(self.N)
        if start is None or not start.out.converged:
            return self.newton(self.system, x_best, min(self.left(), 1.0)), (
                "plateau route: no converged short-plateau start wave"
            )
        path = wp.continue_in_mass(
            spec,
            start.out.x,
            start.system.V,
            self.N,
            self.m,
            self.K,
            self.tols.res_tol,
            t_end,
        )
        note = (
            f"plateau route from a start wave at V - V_SK = {start.system.V - v_sk:+.2g} to "
            f"V - V_SK = {spec.V - v_sk:+.2g}: {path.note}"
        )
        x_p = path.x if path.x is not None else x_best
        out = self.newton(self.system, x_p, max(1.0, self.left()))
        if not out.converged:
            out = _replace(out, message=plateau_refusal(out.message, path, v_sk))
        return out, note

    def check_plateau(self, out: NewtonOutcome, gx: float):
        """Front-position error bar along the near-null direction; a wave whose plateau length
        the residual does not determine (> wp.FRONT_MAX sites) is reported as not converged.
        Returns (outcome, note, front uncertainty in sites)."""
        if not out.converged:
            return out, "", math.nan
        u = wp.front_uncertainty(self.system, out.x, self.tols.res_tol)
        if u is None:
            return out, "", math.nan
        f = wp.half_plateau(out.x[0::2], self.spec.w_left)
        note = (
            f"; flat top (QC gamma*x_f = {gx:.1f}): fronts at +-{f:.3f} sites, plateau-length "
            f"uncertainty +-{u.sites:.2g} sites from round-off (residual {u.residual_2:.2g} / "
            f"sigma_min {u.sigma_min:.2g}; +-{u.sites_at_tol:.2g} at the acceptance tolerance)"
        )
        fu = u.sites
        if fu > wp.FRONT_MAX:  # residual ≤ tol, but the plateau length is not determined
            v_sk = self.spec.v_sk
            d_ok = 2.0 * abs(self.spec.V - v_sk) * fu / wp.FRONT_MAX  # σ_min ∝ |V − V_SK|
            v_ok = v_sk + math.copysign(d_ok, self.spec.V - v_sk)
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
        return out, note, fu


def plateau_refusal(msg: str, path, v_sk: float) -> str:
    near = f"; the nearest solvable V is about {path.V!r}" if path.x is not None else ""
    return (
        f"{msg}. Near V_SK = {v_sk!r} the wave is a flat-top kink-antikink bundle whose plateau "
        "length is only exponentially weakly tied to V (the Jacobian's smallest singular value "
        "falls like |V - V_SK|, its singular vector moves the two fronts apart), so the "
        f"residual cannot fix the plateau in double precision{near}"
    )
