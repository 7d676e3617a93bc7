"""Integration engine of the chain simulations (paper §6).

The scenario drivers (:func:`fpucore.simulate.riemann`, ``gaussian``, ``seeded``) call, in order:

1. :func:`fpucore.simulate.config.configure` — every option validated (ParameterError naming
   it), the memory of the whole request estimated from all its sizes *before* anything is
   allocated and refused above the budget (:mod:`fpucore.budget`), and a work estimate;
2. :func:`run_chain` with the initial data, which builds the output schedule
   (:func:`fpucore.simulate.schedule.output_schedule`: snapshots ∪ tracking window ∪ extra times),
   starts the stepper of the method from the table :data:`fpucore.simulate.steppers.STEPPERS`,
   integrates stop by stop in slices of bounded work (the time budget and the progress callback
   are checked between slices), and writes the status message
   (:func:`fpucore.simulate.messages.status_message`).

See :mod:`fpucore.simulate.scenarios` for the end conditions, guards and conserved energies.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np

from fpucore.budget import Deadline
from fpucore.errors import ParameterError
from fpucore.law import HardeningSofteningLaw, interval_note
from fpucore.simulate import kernels as ck
from fpucore.simulate import tracking
from fpucore.simulate.chain_energy import ENERGY_NAME, energy_terms
from fpucore.simulate.config import RunConfig, restoring_interval
from fpucore.simulate.layout import Chain, Control
from fpucore.simulate.messages import Outcome, status_message
from fpucore.simulate.observer_arrays import finalize_events, make_observer, null_observer
from fpucore.simulate.schedule import output_schedule

ST_TIME_BUDGET = 6  # set here (between slices), never by a kernel
_STATUS = {
    ck.ST_OK: "ok",
    ck.ST_BUDGET: "budget",
    ck.ST_LEFT_CONVEX: "left_convex",
    ck.ST_STEP_UNDERFLOW: "step_underflow",
    ck.ST_NONFINITE: "nonfinite",
    ST_TIME_BUDGET: "time_budget",
}
# A stepper call does at most this many site-force evaluations (~0.1 s) before control returns
# here for the time budget and the progress callback; resuming changes no number (the kernels
# stop between steps and hand back (t, h)).
SLICE_SITE_EVALS = 3e7


# --------------------------------------------------------------------------- helpers
def _advance(
    stepper,
    state,
    y,
    t,
    stop,
    h,
    ctl,
    chain,
    work,
    obs,
    max_steps,
    slice_steps,
    deadline: Deadline,
    on_slice,
):
    """Step from t to ``stop`` in slices of at most ``slice_steps`` steps; between slices check
    the deadline (→ ST_TIME_BUDGET) and call ``on_slice(t)``.  Returns (t, h, status)."""
    stats = work.stats
    while True:
        limit = min(max_steps, int(stats[0]) + slice_steps)
        t, h, status = stepper.advance(state, y, t, stop, h, limit, ctl, chain, work, obs)
        if status != ck.ST_BUDGET or stats[0] >= max_steps:
            return t, h, status
        if deadline.expired():  # a slice ended, not the step budget
            return t, h, ST_TIME_BUDGET
        on_slice(t)


def _slice_steps(stepper, L: int) -> int:
    return max(1, int(SLICE_SITE_EVALS / (stepper.evals_per_step() * (L + 1))))


# --------------------------------------------------------------------------- the runner
def _clipped_note(law, guard: tuple[float, float]) -> str:
    """The represented interval of a smooth law when it is an end of the guard interval."""
    iv = getattr(law, "interval", None)
    if iv and (guard[0] == iv[0] or guard[1] == iv[1]):
        return interval_note(law)
    return ""


def _guard_interval(law, w0: np.ndarray, v0: np.ndarray, cfg: RunConfig):
    """(convex interval, restoring interval, guard interval) after checking the initial data
    against the guard and the end condition (ParameterError)."""
    conv = (float(law.alpha), float(law.beta))
    rest = restoring_interval(law)
    lo, hi = conv if cfg.guard == "convex" else rest
    for name, x in (("initial strain min", w0.min()), ("initial strain max", w0.max())):
        if not (lo < x < hi):
            raise ParameterError(
                name,
                float(x),
                f"({lo:.10g}, {hi:.10g})",
                "initial strains must lie in the convex interval (alpha, beta); guard='bounded' "
                "allows strains up to the zeros of f"
                if cfg.guard == "convex"
                else "initial strains must lie where the force is restoring",
            )
    if cfg.boundary == "fixed_particles" and (v0[0] != 0.0 or v0[-1] != 0.0):
        raise ParameterError(
            "boundary",
            cfg.boundary,
            "fixed_strain | free",
            "the initial data move the end particles (v_0 or v_L ≠ 0), they cannot be held",
        )
    return conv, rest, (lo, hi)


def run_chain(
    law: HardeningSofteningLaw,
    scenario: str,
    w0: np.ndarray,
    v0: np.ndarray,
    cfg: RunConfig,
    w_ends: tuple[float, float],
    origin: float,
    threshold: float,
    extra_times: Sequence[float] = (),
    level: float | None = None,
    progress: Callable[[float], None] | None = None,
):
    """Integrate the chain from (w0 (L,), v0 (L+1,)) under the configuration ``cfg`` (from
    :func:`configure`, for the same L).  Returns (fields of SimulationResult, internals) with
    internals = {ext_t, ext_w, events, cr} for the scenario's own checks."""
    deadline = Deadline(cfg.time_budget_s)
    t_start = deadline.start
    L = w0.size
    if L != cfg.L:
        raise ValueError(f"configured for L = {cfg.L}, data have {L} sites")
    if progress is not None and not callable(progress):
        raise ParameterError("progress", progress, "None or a callable progress(fraction)")
    t_end, boundary, method = cfg.t_end, cfg.boundary, cfg.method
    conv, rest, (lo, hi) = _guard_interval(law, w0, v0, cfg)
    if boundary == "fixed_strain":
        fL, fR = float(law.f(w_ends[0])), float(law.f(w_ends[1]))
    else:
        fL = fR = 0.0
    bc_code = ck.BC_FIXED_PARTICLES if boundary == "fixed_particles" else ck.BC_LOAD
    chain = Chain(L, law.law_id, law.params, bc_code, fL, fR)
    ctl = Control(cfg.rtol, cfg.atol, lo, hi)

    sch = output_schedule(
        t_end, cfg.n_snapshots, cfg.late_fraction, cfg.n_track, cfg.track, extra_times
    )
    if L <= cfg.max_sites_out:
        site_idx = np.arange(L)
    else:
        site_idx = np.unique(np.linspace(0, L - 1, cfg.max_sites_out).round().astype(np.int64))

    y = np.zeros(2 * L + 2)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    thr_ev = 0.5 * threshold
    level = float(law.w_star) if level is None else float(level)
    obs = make_observer(
        L, w0, thr_ev, level, cfg.n_events, cfg.probe_idx, np.linspace(0.0, t_end, cfg.n_probe_t)
    )
    snaps = np.full((sch.t_out.size, site_idx.size), np.nan)
    snaps[0] = w0[site_idx]
    energy = np.full(sch.t_out.size, np.nan)
    H0, E_scale = energy_terms(law, y, L, boundary, fL, fR)
    energy[0] = H0
    trk_w = np.full((sch.t_trk.size, L), np.nan)
    ext_w = np.full((sch.t_extra.size, L), np.nan)

    stepper = cfg.stepper
    state, work, h = stepper.start(law, y, chain, cfg)
    stats = work.stats
    slice_steps = _slice_steps(stepper, L)

    def on_slice(t_now: float) -> None:
        if progress is not None:
            progress(t_now / t_end)

    t = 0.0
    status = ck.ST_OK
    for stop in sch.stops:
        t, h, status = _advance(
            stepper,
            state,
            y,
            t,
            float(stop),
            h,
            ctl,
            chain,
            work,
            obs,
            cfg.max_steps,
            slice_steps,
            deadline,
            on_slice,
        )
        if status != ck.ST_OK:
            break
        key = float(stop)
        if key in sch.out:
            k = sch.out[key]
            snaps[k] = y[site_idx]
            energy[k] = energy_terms(law, y, L, boundary, fL, fR)[0]
        if key in sch.trk:
            trk_w[sch.trk[key]] = y[:L]
        if key in sch.ext:
            ext_w[sch.ext[key]] = y[:L]
        on_slice(t)
        if t < t_end and deadline.expired():
            status = ST_TIME_BUDGET
            break

    st = _STATUS.get(status, "failed")
    finalize_events(y, L, thr_ev, obs)
    done = np.isfinite(energy)
    dE = np.abs(energy[done] - H0)
    drift_abs = float(dE.max()) if dE.size else 0.0
    drift = drift_abs / E_scale if E_scale > 0 else drift_abs
    if not stepper.adaptive:  # the fixed-step method's error: step doubling
        err_est = math.nan
        if cfg.estimate_error and st == "ok":
            err_est, st2 = _step_doubling(
                law, w0, v0, sch.t_out, chain, cfg, snaps, site_idx, deadline
            )
            if st2 == ST_TIME_BUDGET:
                st = "time_budget"
    else:
        err_est = float(stats[3])

    zz = obs.zz
    w_min, w_max = float(zz[1].min()), float(zz[2].max())  # the strain range over all steps
    outcome = Outcome(
        st,
        float(t),
        int(stats[0]),
        int(stats[1]),
        float(work.bad[0]),
        int(work.bad[1]),
        (w_min, w_max),
        conv,
        (lo, hi),
        rest,
        _clipped_note(law, (lo, hi)),
    )
    msg = status_message(outcome, cfg, deadline)
    if st == "time_budget" and t >= t_end:
        msg += " (the run itself reached t_end; the step-doubling error estimate was cut)"

    # a run stopped early returns only the times it reached: no NaN rows for times never computed
    keep = np.isfinite(energy) & np.all(np.isfinite(snaps), axis=1)
    t_out, snaps, energy = sch.t_out[keep], snaps[keep], energy[keep]
    probe_t, probe_out = obs.probe_t, obs.probe_out
    if probe_out.size:
        pk = np.all(np.isfinite(probe_out), axis=0)
        probe_t, probe_out = probe_t[pk], probe_out[:, pk]

    waves = []
    if cfg.track and st == "ok" and deadline.expired():  # tracking would run past the budget
        msg += (
            "; wave tracking skipped: the time budget ran out as the run reached t_end "
            "(raise time_budget_s, CLI: --time-budget)"
        )
    elif cfg.track and st == "ok":
        waves = tracking.track(
            law,
            sch.t_trk,
            trk_w,
            origin=origin,
            threshold=threshold,
            events=(obs.ev_t, obs.ev_w, obs.ev_s),
            crossings=(obs.cr_t, obs.cr_s),
            level=level,
        )

    res = dict(
        scenario=scenario,
        L=L,
        boundary=boundary,
        method=method,
        rtol=cfg.rtol,
        dt=cfg.dt,
        t=t_out,
        sites=site_idx + 1,
        snapshots=snaps,
        probe_sites=cfg.probe_idx + 1,
        probe_t=probe_t,
        probe_series=probe_out,
        energy=energy,
        energy_drift=drift,
        energy_drift_abs=drift_abs,
        energy_name=ENERGY_NAME[boundary],
        error_estimate=err_est,
        n_steps=int(stats[0]),
        n_rejected=int(stats[1]),
        n_rhs=int(stats[2]),
        t_final=float(t),
        final_w=y[:L].copy(),
        waves=waves,
        stop_reason=st,
        message=msg,
        elapsed_s=time.perf_counter() - t_start,
    )
    res["details"] = {
        "guard": cfg.guard,
        "guard_interval": [lo, hi],
        "strain_range": [w_min, w_max],
        "left_convex_interval": bool(w_min <= conv[0] or w_max >= conv[1]),
        "work_estimate": dict(cfg.work),
        "memory_estimate_bytes": cfg.memory_bytes,
        "time_budget_s": cfg.time_budget_s,
    }
    if cfg.pwl:  # event location at the breakpoints (fpucore.simulate.pwl_rkn)
        n_cross, resid, n_tan = stepper.event_counts(state)
        res["details"].update(
            breakpoint_crossings=n_cross,
            location_residual=resid,
            unlocated_tangencies=n_tan,
            event_location=bool(stepper.locate),
        )
    internals = dict(
        ext_t=sch.t_extra,
        ext_w=ext_w,
        events=(obs.ev_t, obs.ev_w, obs.ev_s),
        cr=(obs.cr_t, obs.cr_s),
    )
    return res, internals


def _step_doubling(
    law, w0, v0, t_out, chain: Chain, cfg: RunConfig, snaps, site_idx, deadline: Deadline
) -> tuple[float, int]:
    """(max |w_h − w_2h| / (2⁴ − 1) over the output snapshots, status): the companion run at
    step 2·dt (Yoshida is 4th order), under the same time budget (NaN if it did not finish)."""
    L = w0.size
    y = np.zeros(2 * L + 2)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    stepper = cfg.stepper
    _, work, _ = stepper.start(law, y, chain, cfg)
    ctl = Control(cfg.rtol, cfg.atol, law.alpha, law.beta)
    obs = null_observer(L)
    slice_steps = _slice_steps(stepper, L)
    worst = 0.0
    t = 0.0
    for k in range(1, t_out.size):
        t, _, status = _advance(
            stepper,
            None,
            y,
            t,
            float(t_out[k]),
            2.0 * cfg.dt,  # type: ignore[operator]
            ctl,
            chain,
            work,
            obs,
            cfg.max_steps,
            slice_steps,
            deadline,
            lambda _t: None,
        )
        if status != ck.ST_OK:
            return math.nan, status
        worst = max(worst, float(np.max(np.abs(y[site_idx] - snaps[k]))))
        if k < t_out.size - 1 and deadline.expired():
            return math.nan, ST_TIME_BUDGET
    return worst / 15.0, ck.ST_OK
