"""Integration engine of the chain simulations (paper §6).

The scenario drivers (:func:`fpucore.simulate.riemann`, ``gaussian``, ``seeded``) call, in order:

1. :func:`configure` — every option validated (ParameterError naming it), the memory of the whole
   request estimated from all its sizes *before* anything is allocated and refused above the
   budget (:mod:`fpucore.budget`), and a work estimate (steps × sites, seconds);
2. :func:`run_chain` with the initial data, which builds the output schedule
   (:func:`output_schedule`: snapshots ∪ tracking window ∪ extra times), starts the stepper of
   the method from the table :data:`STEPPERS`, integrates stop by stop in slices of bounded work
   (the time budget and the progress callback are checked between slices), and writes the status
   message (:func:`status_message`).

See :mod:`fpucore.simulate.scenarios` for the end conditions, guards and conserved energies.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from fpucore.budget import Deadline, fmt_bytes, require_memory, require_time_budget
from fpucore.errors import ParameterError, require_finite
from fpucore.law import HardeningSofteningLaw
from fpucore.simulate import kernels as ck
from fpucore.simulate import rkn as crk
from fpucore.simulate import tracking
from fpucore.simulate.layout import Chain, Control, ErkPair, Observer, RknPair, Work
from fpucore.tableaux import rkn as rkn_tableaux
from fpucore.tableaux.embedded import get as get_embedded

BOUNDARIES = ("fixed_particles", "fixed_strain", "free")
GUARDS = ("convex", "bounded")
MAX_L = 10_000_000
MAX_PROBE_T = 10_000_000
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
# Seconds per site-force evaluation of the whole pipeline (stepper, observer, guard), measured on
# the paper's Riemann run (benchmarks/bench_simulate.py: 0.64 s / (58 786 × 3600)): the time
# part of the work estimate, good to a factor ~2 on an idle machine.
SECONDS_PER_SITE_EVAL = 3.0e-9


def require_positive(name: str, x, hi: float = 1e9) -> float:
    x = require_finite(name, x)
    if not (0.0 < x <= hi):
        raise ParameterError(name, x, f"(0, {hi:g}]")
    return x


def require_int(name: str, x, lo: int, hi: int) -> int:
    """An integer in [lo, hi] (a float with an integer value is accepted; bools are not)."""
    valid = f"an integer in [{lo}, {hi}]"
    if isinstance(x, bool):
        raise ParameterError(name, x, valid)
    try:
        xi = int(x)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(name, x, valid) from None
    if xi != x or not (lo <= xi <= hi):
        raise ParameterError(name, x, valid)
    return xi


def restoring_interval(law: HardeningSofteningLaw) -> tuple[float, float]:
    """The zeros of f adjacent to 0, (w_lo, w_hi) ⊃ (α, β): inside, f(w) has the sign of w (the
    spring resists); beyond them the potential Φ decreases without bound for the cubic law, so a
    strain that passes them runs away.  Cubic a = −1, b = 10: (5 − √26, 5 + √26)."""
    out = []
    for edge, sgn in ((law.beta, 1.0), (law.alpha, -1.0)):
        step = max(abs(edge), 1e-3)
        x = edge
        for _ in range(200):  # bounded search for a sign change of f beyond the edge
            nxt = x + sgn * step
            if sgn * float(law.f(nxt)) <= 0.0:
                out.append(brentq(lambda z: float(law.f(z)), x, nxt, xtol=1e-14))
                break
            x, step = nxt, 2 * step
        else:
            out.append(sgn * math.inf)
    return (out[1], out[0])


# --------------------------------------------------------------------------- stepper table
class ErkStepper:
    """Embedded explicit RK pair on the first-order form (:func:`kernels.erk_chunk`)."""

    def __init__(self, method: str):
        tab = get_embedded(method)
        self.name, self.tab, self.stages = method, tab, tab.stages
        self.order = tab.err_order
        self.adaptive = True

    def floats_per_site(self) -> float:
        """Work floats per site: y, K (s+1 rows) and W (5 rows) over the 2L+2 state."""
        return 2.0 * (1 + self.stages + 1 + 5)

    def evals_per_step(self) -> float:
        return 2.0 * self.stages  # s force evaluations on a state twice the length of q

    def start(self, law, y: np.ndarray, chain: Chain, cfg: RunConfig):
        n = y.size
        tab = self.tab
        K = np.zeros((tab.stages + 1, n))
        W = np.zeros((5, n))
        work = Work(K, W, np.zeros(chain.L + 2), np.zeros(6), np.zeros(2))
        ck.rhs(y, chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, K[0])
        h = _initial_step(y, K[0], cfg.rtol, cfg.atol, cfg.t_end)
        pair = ErkPair(tab.A, tab.B, tab.E5, tab.E3, tab.dual, -1.0 / (tab.err_order + 1))
        return (pair, None), work, h

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        pair, _ = state
        return ck.erk_chunk(y, t, stop, h, limit, pair, ctl, chain, work, obs)


class RknStepper:
    """Embedded RKN pair on the second-order form (:func:`rkn.rkn_chunk`); the first-order state
    y is rebuilt after every call (snapshots, energy and events read y)."""

    def __init__(self, method: str):
        rk = rkn_tableaux.get(method)
        self.name, self.rk, self.stages = method, rk, rk.stages
        self.order = rk.err_order
        self.adaptive = True

    def floats_per_site(self) -> float:
        """y (2 per site) + q, K (s+3 rows), W (7 rows) over L+1."""
        return 2.0 + 1 + self.stages + 3 + 7

    def evals_per_step(self) -> float:
        return float(self.stages)

    def start(self, law, y: np.ndarray, chain: Chain, cfg: RunConfig):
        L, rk = chain.L, self.rk
        s = rk.stages
        qv = np.zeros(L + 1)
        K = np.zeros((s + 3, L + 1))  # K[0] = F(q), K[s+1] = q̇ (see rkn.rkn_chunk)
        W = np.zeros((7, L + 1))
        work = Work(K, W, np.zeros(L + 2), np.zeros(6), np.zeros(2))
        crk.y_to_rkn(y, L, qv, K[s + 1])
        crk.accel(qv, L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, K[0])
        h = _initial_step(np.concatenate([qv, K[s + 1]]), np.concatenate([K[s + 1], K[0]]),
                          cfg.rtol, cfg.atol, cfg.t_end)  # fmt: skip
        pair = RknPair(rk.c, rk.A, rk.b, rk.bp, rk.e, rk.ep, rk.fsal, -1.0 / (rk.err_order + 1))
        return (pair, qv), work, h

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        pair, qv = state
        out = crk.rkn_chunk(qv, t, stop, h, limit, pair, ctl, chain, work, obs)
        crk.rkn_to_y(qv, work.K[self.stages + 1], chain.L, y)
        return out


class YoshidaStepper:
    """4th-order Yoshida composition of velocity Verlet, fixed step dt
    (:func:`kernels.yoshida_chunk`)."""

    name, stages, order, adaptive = "symplectic", 3, 4, False

    def floats_per_site(self) -> float:
        """y, K (2 rows) and W (3 rows) over 2L+2; twice with the step-doubling companion run."""
        return 2.0 * (1 + 2 + 3)

    def evals_per_step(self) -> float:
        return 3.0

    def start(self, law, y: np.ndarray, chain: Chain, cfg: RunConfig):
        n = y.size
        work = Work(np.zeros((2, n)), np.zeros((3, n)), np.zeros(chain.L + 2), np.zeros(6),
                    np.zeros(2))  # fmt: skip
        ck.rhs(y, chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, work.K[0])
        return None, work, cfg.dt

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        return ck.yoshida_chunk(y, t, stop, h, limit, ctl, chain, work, obs)


STEPPERS = {
    "rkn12": RknStepper("rkn12"),
    "dop853": ErkStepper("dop853"),
    "dopri5": ErkStepper("dopri5"),
    "rkn8": RknStepper("rkn8"),
    "symplectic": YoshidaStepper(),
}
METHODS = tuple(STEPPERS)
RKN_METHODS = tuple(m for m, s in STEPPERS.items() if isinstance(s, RknStepper))
# h·ω_max of each adaptive method at rtol = 1e-10 on the paper's Riemann run (ω_max = 2 c_max,
# the top of the chain's linear spectrum): 3458 / 8881 / 50 821 / 15 265 steps over t = 300
# (benchmarks/README.md); the work estimate scales it as rtol^(1/(q+1)).
H_OMEGA_AT_1E10 = {"rkn12": 1.0, "dop853": 0.40, "dopri5": 0.069, "rkn8": 0.23}


# --------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class RunConfig:
    """The validated options of one run (see :func:`configure`); ``memory_bytes`` and
    ``work`` (steps, site_evals, seconds) are the estimates made before allocation."""

    L: int
    t_end: float
    boundary: str
    method: str
    rtol: float
    atol: float
    dt: float | None
    n_snapshots: int
    max_sites_out: int
    probe_idx: np.ndarray
    n_probe_t: int
    late_fraction: float
    n_track: int
    max_steps: int
    estimate_error: bool
    track: bool
    n_events: int
    guard: str
    time_budget_s: float | None
    memory_bytes: float
    work: dict

    @property
    def stepper(self):
        return STEPPERS[self.method]


def _probe_sites(probes, L: int) -> np.ndarray:
    """0-based indices from 1-based site numbers in [1, L]."""
    valid = f"site numbers in [1, {L}]"
    try:
        sites = list(probes)
    except TypeError:
        raise ParameterError("probes", probes, valid) from None
    out = []
    for s in sites:
        if isinstance(s, bool):
            raise ParameterError("probes", sites, valid)
        try:
            si = int(s)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError("probes", sites, valid) from None
        if si != s or not (1 <= si <= L):
            raise ParameterError("probes", sites, valid)
        out.append(si - 1)
    return np.array(out, dtype=np.int64)


def memory_estimate(
    L: int,
    method: str,
    n_snapshots: int,
    n_sites_out: int,
    n_probes: int,
    n_probe_t: int,
    n_track: int,
    n_extra: int,
    n_events: int,
    estimate_error: bool,
) -> dict[str, tuple[float, str]]:
    """Bytes of one run by the argument that sets them: {name: (bytes, what)}.

    "L": the state, the stepper's work arrays, the per-site observer (events n_events per site,
    4 crossings), the tracking window (n_track full profiles, twice), extra full profiles, the
    initial data and temporaries (checked against tracemalloc in tests/simulate/test_budgets.py);
    "n_snapshots": the output field (n_snapshots × sites kept, and its copy when a stopped run
    is trimmed); "n_probe_t": the probe series ((probes + 1) × n_probe_t, twice)."""
    st = STEPPERS[method]
    per_site = st.floats_per_site()
    if method == "symplectic" and estimate_error:
        per_site *= 2
    per_site += 1 + 3 + 1 + 1  # g, zz, zt, final_w
    per_site += 2 * n_events + n_events / 8 + 1 + 4 + 0.5 + 1  # events, crossings, counts
    # the tracking window and the tracker's temporaries (2 × n_track profiles, measured), extra
    # profiles, w0 and v0, temporaries of the energy (Φ(w), v², …; measured with tracemalloc)
    per_site += 2 * n_track + n_extra + 2 + 10
    return {
        "L": (8.0 * per_site * L, f"{per_site:.0f} floats per site × L={L}"),
        "n_snapshots": (
            16.0 * n_snapshots * n_sites_out,
            f"snapshots {n_snapshots} × {n_sites_out} sites kept (max_sites_out)",
        ),
        "n_probe_t": (16.0 * (n_probes + 1) * n_probe_t, f"{n_probes} probes × {n_probe_t} times"),
    }


def work_estimate(
    law,
    L: int,
    t_end: float,
    method: str,
    rtol: float,
    dt,
    estimate_error: bool = True,
    n_stops: int = 240,
) -> dict:
    """Rough work of a run before it starts: {"steps", "site_evals", "seconds"}.  Fixed step:
    t_end/dt plus one shortened step per output stop (``n_stops``; + half as many for the
    step-doubling companion); adaptive: t_end·ω_max/(h·ω) with the measured h·ω of
    :data:`H_OMEGA_AT_1E10` scaled as rtol^(1/(q+1)) (a factor ~3 either way: the data, not only
    the law, set the step)."""
    st = STEPPERS[method]
    if method == "symplectic":
        steps = (t_end / dt + n_stops) * (1.5 if estimate_error else 1.0)
    else:
        omega = 2.0 * law.c_max
        h_omega = H_OMEGA_AT_1E10[method] * (rtol / 1e-10) ** (1.0 / (st.order + 1))
        steps = t_end * omega / h_omega
    site_evals = steps * st.evals_per_step() * L
    return {
        "steps": float(math.ceil(steps)),
        "site_evals": float(site_evals),
        "seconds": float(site_evals * SECONDS_PER_SITE_EVAL),
    }


def configure(
    law: HardeningSofteningLaw,
    L: int,
    t_end: float,
    boundary: str,
    method: str,
    rtol: float,
    atol: float | None = None,
    dt: float | None = None,
    n_snapshots: int = 200,
    max_sites_out: int = 1000,
    probes: Sequence[int] = (),
    n_probe_t: int = 4001,
    late_fraction: float = 1.0 / 3.0,
    n_track: int = 41,
    max_steps: int = 20_000_000,
    estimate_error: bool = True,
    track: bool = True,
    n_events: int = 16,
    guard: str = "convex",
    time_budget_s: float | None = None,
    memory_budget: str | float | None = None,
    n_extra: int = 0,
) -> RunConfig:
    """Validate every option of a run of L sites to ``t_end`` and estimate its memory (refused
    above the budget, ParameterError naming the argument whose size dominates) and work, before
    anything is allocated.  ``n_extra``: full-resolution profiles requested at extra times."""
    t_end = require_positive("t_end", t_end, 1e7)
    if boundary not in BOUNDARIES:
        raise ParameterError("boundary", boundary, " | ".join(BOUNDARIES))
    if method not in STEPPERS:
        raise ParameterError("method", method, " | ".join(METHODS))
    rtol = require_finite("rtol", rtol)
    if not (1e-14 <= rtol <= 1e-2):
        raise ParameterError("rtol", rtol, "[1e-14, 1e-2]")
    atol = rtol if atol is None else require_positive("atol", atol, 1.0)
    if method == "symplectic":
        dt = 0.02 if dt is None else require_positive("dt", dt, 0.1)
    n_snapshots = require_int("n_snapshots", n_snapshots, 2, 100_000)
    max_sites_out = require_int("max_sites_out", max_sites_out, 2, 10_000_000)
    probe_idx = _probe_sites(probes, L)
    n_probe_t = require_int("n_probe_t", n_probe_t, 2, MAX_PROBE_T)
    late_fraction = require_finite("late_fraction", late_fraction)
    if not (0.0 < late_fraction <= 1.0):
        raise ParameterError(
            "late_fraction", late_fraction, "(0, 1]", "the tracking window ends at t_end"
        )
    n_track = require_int("n_track", n_track, 3, 10_000)
    max_steps = require_int("max_steps", max_steps, 1, 10**12)
    n_events = require_int("n_events", n_events, 1, 1000)
    if guard not in GUARDS:
        raise ParameterError("guard", guard, " | ".join(GUARDS))
    time_budget_s = require_time_budget(time_budget_s)
    estimate_error, track = bool(estimate_error), bool(track)

    sizes = memory_estimate(
        L, method, n_snapshots, min(L, max_sites_out), probe_idx.size, n_probe_t,
        n_track if track else 0, n_extra, n_events, estimate_error,
    )  # fmt: skip
    total = sum(b for b, _ in sizes.values())
    name = max(sizes, key=lambda k: sizes[k][0])
    values = {"L": L, "n_snapshots": n_snapshots, "n_probe_t": n_probe_t}
    detail = "estimate: " + "; ".join(f"{what}: {fmt_bytes(b)}" for b, what in sizes.values())
    require_memory(name, total, detail, value=values[name], budget=memory_budget)
    n_stops = n_snapshots + (n_track if track else 0) + n_extra
    work = work_estimate(law, L, t_end, method, rtol, dt, estimate_error, n_stops)
    return RunConfig(
        L, t_end, boundary, method, rtol, atol, dt if method == "symplectic" else None,
        n_snapshots, max_sites_out, probe_idx, n_probe_t, late_fraction, n_track, max_steps,
        estimate_error, track, n_events, guard, time_budget_s, total, work,
    )  # fmt: skip


# --------------------------------------------------------------------------- output schedule
@dataclass(frozen=True)
class Schedule:
    """Output times of a run: t_out (n_snapshots,) from 0 to t_end; t_trk (n_track,) the tracking
    window [t_end (1 − late_fraction), t_end]; t_extra full-resolution profiles; ``stops`` the
    sorted union of them (> 0), each a stop of the stepper; out/trk/ext map a stop to its row."""

    t_out: np.ndarray
    t_trk: np.ndarray
    t_extra: np.ndarray
    stops: np.ndarray
    out: dict
    trk: dict
    ext: dict


def output_schedule(
    t_end: float,
    n_snapshots: int,
    late_fraction: float,
    n_track: int,
    track: bool,
    extra_times: Sequence[float] = (),
) -> Schedule:
    """The stops of a run.  An extra time within rounding of t_end (relative 1e-12: e.g. K·(1/V)
    for t_end = K/V, one ulp above it for ~9 % of velocities) is taken at t_end; one beyond it,
    or ≤ 0, is an error of the caller (ValueError), never silently dropped."""
    t_out = np.linspace(0.0, t_end, n_snapshots)
    t_a = t_end * (1.0 - late_fraction)
    t_trk = np.linspace(t_a, t_end, n_track) if track else np.empty(0)
    extra = []
    for x in extra_times:
        x = float(x)
        if x > t_end and x <= t_end * (1.0 + 1e-12):
            x = t_end
        if not (0.0 < x <= t_end):
            raise ValueError(f"extra output time {x!r} outside (0, t_end = {t_end!r}]")
        extra.append(x)
    t_extra = np.asarray(sorted(extra), dtype=float)
    stops = np.unique(np.concatenate([t_out[1:], t_trk, t_extra]))
    stops = stops[stops > 0]
    return Schedule(
        t_out, t_trk, t_extra, stops,
        {float(x): k for k, x in enumerate(t_out)},
        {float(x): k for k, x in enumerate(t_trk)},
        {float(x): k for k, x in enumerate(t_extra)},
    )  # fmt: skip


# --------------------------------------------------------------------------- helpers
def _energy_terms(law, y: np.ndarray, L: int, bc: str, fL: float, fR: float):
    """(H, E_scale) for the state y; see the module docstring of scenarios for H per boundary."""
    w = y[:L]
    v = y[L : 2 * L + 1]
    phi = law.phi(w)
    kin = 0.5 * v * v
    if bc == "fixed_particles":
        kin = kin[1:-1]
    terms = [kin.sum(), phi.sum()]
    scale = float(np.abs(kin).sum() + np.abs(phi).sum())
    if bc == "fixed_strain":
        u0 = y[2 * L + 1]
        lin = -fR * w.sum()
        load = (fL - fR) * u0
        terms += [lin, load]
        scale += abs(lin) + abs(load)
    return float(math.fsum(terms)), scale


def _finalize_events(y, L, thr, obs: Observer) -> None:
    """Confirm the pending extremum candidate of every site if the strain has since moved away
    from it by more than the prominence threshold (otherwise a wave that passed a site shortly
    before the end, with no later opposite extremum, would be missed)."""
    K = obs.ev_t.shape[1]
    zz, ev_n = obs.zz, obs.ev_n
    for n in np.nonzero(obs.zdir)[0]:
        if ev_n[n] < K and abs(zz[0, n] - y[n]) > thr:
            k = ev_n[n]
            obs.ev_t[n, k], obs.ev_w[n, k], obs.ev_s[n, k] = obs.zt[n], zz[0, n], obs.zdir[n]
            ev_n[n] += 1


def _initial_step(y: np.ndarray, dy: np.ndarray, rtol: float, atol: float, t_end: float) -> float:
    """Hairer's starting step h = 0.01 ‖y‖/‖ẏ‖ in the scaled RMS norm, capped at 0.1 and t_end."""
    sc = atol + rtol * np.abs(y)
    d0 = np.sqrt(np.mean((y / sc) ** 2))
    d1 = np.sqrt(np.mean((dy / sc) ** 2))
    h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h, 0.1, t_end)


def _observer(L: int, w0: np.ndarray, thr: float, level: float, n_events: int, probe_idx,
              probe_t) -> Observer:  # fmt: skip
    zz = np.empty((3, L))  # per site: extremum candidate, running min, running max
    zz[:] = w0
    probe_out = np.full((probe_idx.size, probe_t.size), np.nan)
    probe_out[:, 0] = w0[probe_idx]
    return Observer(
        thr, level, zz, np.zeros(L), np.zeros(L, np.int8),
        np.full((L, n_events), np.nan), np.full((L, n_events), np.nan),
        np.zeros((L, n_events), np.int8), np.zeros(L, np.int64),
        np.full((L, 4), np.nan), np.zeros((L, 4), np.int8), np.zeros(L, np.int64),
        probe_idx, probe_t, probe_out, np.ones(1, np.int64), np.zeros(8),
    )  # fmt: skip


def _null_observer(L: int) -> Observer:
    """An observer that records nothing (infinite prominence, NaN level, no probes)."""
    e = np.zeros((L, 1))
    ei = np.zeros((L, 1), np.int8)
    en = np.zeros(L, np.int64)
    zz = np.zeros((3, L))
    zz[1] = -np.inf
    zz[2] = np.inf
    return Observer(
        np.inf, np.nan, zz, np.zeros(L), np.zeros(L, np.int8), e, e, ei, en, e, ei, en,
        np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 0)), np.zeros(1, np.int64), np.zeros(8),
    )  # fmt: skip


def _advance(stepper, state, y, t, stop, h, ctl, chain, work, obs, max_steps, slice_steps,
             deadline: Deadline, on_slice):  # fmt: skip
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


# --------------------------------------------------------------------------- status messages
@dataclass(frozen=True)
class Outcome:
    """What the status message needs to know about a finished (or stopped) run."""

    status: str
    t: float
    n_steps: int
    n_rejected: int
    bad_value: float
    bad_site: int
    strain_range: tuple[float, float]
    convex: tuple[float, float]
    guard_interval: tuple[float, float]
    restoring: tuple[float, float]


def _msg_ok(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    msg = f"reached t = {o.t:.6g} in {o.n_steps} steps ({o.n_rejected} rejected)"
    (a, b), (w_min, w_max), (lo, hi) = o.convex, o.strain_range, o.guard_interval
    if w_min <= a or w_max >= b:
        msg += (
            f"; strains went outside the convex interval ({a:.6g}, {b:.6g}): "
            f"range [{w_min:.6g}, {w_max:.6g}] (guard 'bounded' allows ({lo:.6g}, {hi:.6g}))"
        )
    return msg


def _msg_left(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    lo, hi = o.guard_interval
    head = f"stopped at t = {o.t:.6g}: strain w_{o.bad_site + 1} = {o.bad_value:.6g} left the "
    if cfg.guard == "convex":
        r0, r1 = o.restoring
        return head + (
            f"convex interval (alpha, beta) = ({lo:.6g}, {hi:.6g}) (guard='convex'). "
            f"Beyond it f' < 0, and beyond the zeros of f ({r0:.6g}, {r1:.6g}) "
            "the cubic potential is unbounded. Suggestion: guard='bounded' to continue "
            "through transient excursions (stops only outside the zeros of f); for a "
            "Riemann run use boundary='fixed_particles' or 'fixed_strain'"
        )
    return head + (
        f"interval between the zeros of f ({lo:.6g}, {hi:.6g}); beyond it the "
        "cubic potential has no restoring force and the strain runs away. Suggestion: "
        "smaller data, boundary='fixed_particles' or 'fixed_strain', or a longer chain"
    )


def _msg_budget(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    return (
        f"step budget max_steps={cfg.max_steps} exhausted at t = {o.t:.6g}; suggestion: loosen "
        "rtol or raise max_steps"
    )


def _msg_time(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    est = cfg.work["seconds"]
    return deadline.message(
        f"at t = {o.t:.6g} of t_end = {cfg.t_end:.6g} ({o.n_steps} steps; the whole run was "
        f"estimated at ~{est:.3g} s); the result holds the times reached",
        "raise time_budget_s (CLI: --time-budget), or shorten t_end / L",
    )


def _msg_failed(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    return f"integration failed ({o.status}) at t = {o.t:.6g}; suggestion: loosen rtol / reduce dt"


MESSAGES: dict[str, Callable[[Outcome, RunConfig, Deadline], str]] = {
    "ok": _msg_ok,
    "left_convex": _msg_left,
    "budget": _msg_budget,
    "time_budget": _msg_time,
}


def status_message(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    """The message of a run by its stop reason (what happened, and what to change)."""
    return MESSAGES.get(o.status, _msg_failed)(o, cfg, deadline)


# --------------------------------------------------------------------------- the runner
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
    if boundary == "fixed_particles" and (v0[0] != 0.0 or v0[-1] != 0.0):
        raise ParameterError(
            "boundary",
            boundary,
            "fixed_strain | free",
            "the initial data move the end particles (v_0 or v_L ≠ 0), they cannot be held",
        )
    if boundary == "fixed_strain":
        fL, fR = float(law.f(w_ends[0])), float(law.f(w_ends[1]))
    else:
        fL = fR = 0.0
    bc_code = ck.BC_FIXED_PARTICLES if boundary == "fixed_particles" else ck.BC_LOAD
    chain = Chain(L, law.law_id, law.params, bc_code, fL, fR)
    ctl = Control(cfg.rtol, cfg.atol, lo, hi)

    sch = output_schedule(t_end, cfg.n_snapshots, cfg.late_fraction, cfg.n_track, cfg.track,
                          extra_times)  # fmt: skip
    if L <= cfg.max_sites_out:
        site_idx = np.arange(L)
    else:
        site_idx = np.unique(np.linspace(0, L - 1, cfg.max_sites_out).round().astype(np.int64))

    y = np.zeros(2 * L + 2)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    thr_ev = 0.5 * threshold
    level = float(law.w_star) if level is None else float(level)
    obs = _observer(L, w0, thr_ev, level, cfg.n_events, cfg.probe_idx,
                    np.linspace(0.0, t_end, cfg.n_probe_t))  # fmt: skip
    snaps = np.full((sch.t_out.size, site_idx.size), np.nan)
    snaps[0] = w0[site_idx]
    energy = np.full(sch.t_out.size, np.nan)
    H0, E_scale = _energy_terms(law, y, L, boundary, fL, fR)
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
        t, h, status = _advance(stepper, state, y, t, float(stop), h, ctl, chain, work, obs,
                                cfg.max_steps, slice_steps, deadline, on_slice)  # fmt: skip
        if status != ck.ST_OK:
            break
        key = float(stop)
        if key in sch.out:
            k = sch.out[key]
            snaps[k] = y[site_idx]
            energy[k] = _energy_terms(law, y, L, boundary, fL, fR)[0]
        if key in sch.trk:
            trk_w[sch.trk[key]] = y[:L]
        if key in sch.ext:
            ext_w[sch.ext[key]] = y[:L]
        on_slice(t)
        if t < t_end and deadline.expired():
            status = ST_TIME_BUDGET
            break

    st = _STATUS.get(status, "failed")
    _finalize_events(y, L, thr_ev, obs)
    done = np.isfinite(energy)
    dE = np.abs(energy[done] - H0)
    drift_abs = float(dE.max()) if dE.size else 0.0
    drift = drift_abs / E_scale if E_scale > 0 else drift_abs
    if method == "symplectic":
        err_est = math.nan
        if cfg.estimate_error and st == "ok":
            err_est, st2 = _step_doubling(law, w0, v0, sch.t_out, chain, cfg, snaps, site_idx,
                                          deadline)  # fmt: skip
            if st2 == ST_TIME_BUDGET:
                st = "time_budget"
    else:
        err_est = float(stats[3])

    zz = obs.zz
    w_min, w_max = float(zz[1].min()), float(zz[2].max())  # the strain range over all steps
    outcome = Outcome(
        st, float(t), int(stats[0]), int(stats[1]), float(work.bad[0]), int(work.bad[1]),
        (w_min, w_max), conv, (lo, hi), rest,
    )  # fmt: skip
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
    if cfg.track and st == "ok":
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
        energy_name=_ENERGY_NAME[boundary],
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
    internals = dict(
        ext_t=sch.t_extra,
        ext_w=ext_w,
        events=(obs.ev_t, obs.ev_w, obs.ev_s),
        cr=(obs.cr_t, obs.cr_s),
    )
    return res, internals


_ENERGY_NAME = {
    "fixed_particles": "H = sum_{j=1}^{L-1} v_j^2/2 + sum_n Phi(w_n) (end particles at rest)",
    "free": "H = sum_{j=0}^{L} v_j^2/2 + sum_n Phi(w_n)",
    "fixed_strain": (
        "H = sum_{j=0}^{L} v_j^2/2 + sum_n [Phi(w_n) - f(w_right) w_n] "
        "+ (f(w_left) - f(w_right)) u_0 (dead-load potential included)"
    ),
}


def _step_doubling(law, w0, v0, t_out, chain: Chain, cfg: RunConfig, snaps, site_idx,
                   deadline: Deadline) -> tuple[float, int]:  # fmt: skip
    """(max |w_h − w_2h| / (2⁴ − 1) over the output snapshots, status): the companion run at
    step 2·dt (Yoshida is 4th order), under the same time budget (NaN if it did not finish)."""
    L = w0.size
    y = np.zeros(2 * L + 2)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    stepper = STEPPERS["symplectic"]
    _, work, _ = stepper.start(law, y, chain, cfg)
    ctl = Control(cfg.rtol, cfg.atol, law.alpha, law.beta)
    obs = _null_observer(L)
    slice_steps = _slice_steps(stepper, L)
    worst = 0.0
    t = 0.0
    for k in range(1, t_out.size):
        t, _, status = _advance(stepper, None, y, t, float(t_out[k]), 2.0 * cfg.dt, ctl, chain,
                                work, obs, cfg.max_steps, slice_steps, deadline,
                                lambda _t: None)  # fmt: skip
        if status != ck.ST_OK:
            return math.nan, status
        worst = max(worst, float(np.max(np.abs(y[site_idx] - snaps[k]))))
        if k < t_out.size - 1 and deadline.expired():
            return math.nan, ST_TIME_BUDGET
    return worst / 15.0, ck.ST_OK
