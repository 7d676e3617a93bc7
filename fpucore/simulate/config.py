"""Configuration of a chain simulation, before anything is allocated: every option validated
(ParameterError naming it), the memory of the whole request estimated from all its sizes and
refused above the budget (:mod:`fpucore.budget`), and the work estimated (steps × sites,
seconds).  The output schedule (the stops of the stepper): :mod:`fpucore.simulate.schedule`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from fpucore.budget import fmt_bytes, require_memory, require_time_budget
from fpucore.errors import ParameterError, require_finite, require_in, require_int
from fpucore.law import HardeningSofteningLaw, require_law
from fpucore.simulate.steppers import H_OMEGA_AT_1E10, METHODS, PWL_STEPPERS, STEPPERS

BOUNDARIES = ("fixed_particles", "fixed_strain", "free")
GUARDS = ("convex", "bounded")
MAX_L = 10_000_000
MAX_PROBE_T = 10_000_000
# Seconds per site-force evaluation of the whole pipeline (stepper, observer, guard), measured on
# the paper's Riemann run (benchmarks/bench_simulate.py: 0.64 s / (58 786 × 3600)): the time
# part of the work estimate, good to a factor ~2 on an idle machine.
SECONDS_PER_SITE_EVAL = 3.0e-9


def require_positive(name: str, x, hi: float = 1e9) -> float:
    x = require_finite(name, x)
    if not (0.0 < x <= hi):
        raise ParameterError(name, x, f"(0, {hi:g}]")
    return x


def require_L(L) -> int:
    """The chain length: an integer in [16, MAX_L]."""
    return require_int("L", L, 16, MAX_L)


def detection_threshold(threshold, scale: float) -> float:
    """Wave-tracker detection threshold (strain units): the given value (> 0), else 2 % of the
    disturbance's scale (1e-3 where that scale is 0)."""
    if threshold is not None:
        return require_positive("threshold", threshold)
    return 0.02 * scale or 1e-3


#: the keywords every driver passes on to :func:`configure`
CONFIG_OPTIONS = (
    "method", "rtol", "atol", "dt", "n_snapshots", "max_sites_out", "probes", "n_probe_t",
    "late_fraction", "max_steps", "estimate_error", "track", "guard", "time_budget_s",
    "memory_budget",
)  # fmt: skip


def split_options(kw: dict) -> tuple[dict, dict]:
    """(options of :func:`configure`, options of the engine's run_chain) from a driver's
    keywords; TypeError for any other keyword."""
    bad = set(kw) - set(CONFIG_OPTIONS) - {"progress"}
    if bad:
        raise TypeError(f"unexpected keyword arguments {sorted(bad)}")
    run = {"progress": kw.pop("progress")} if "progress" in kw else {}
    return kw, run


def restoring_interval(law: HardeningSofteningLaw) -> tuple[float, float]:
    """The zeros of f adjacent to 0, (w_lo, w_hi) ⊃ (α, β): inside, f(w) has the sign of w (the
    spring resists); beyond them the potential Φ decreases without bound for the cubic law, so a
    strain that passes them runs away.  Cubic a = −1, b = 10: (5 − √26, 5 + √26).  For a smooth
    law, clipped to its represented interval (``law.interval``: its kernels return NaN beyond).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).

    Returns
    -------
    tuple of (float, float)
        (w_lo, w_hi), strain units (±inf where f has no zero beyond the edge, and for a
        piecewise-linear law).

    Raises
    ------
    ParameterError
        When ``law`` is not a law.
    """
    law = require_law(law)
    if getattr(law, "breakpoints", ()):  # PL: moduli >= 0, f nondecreasing, Φ convex everywhere
        return (-math.inf, math.inf)
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
    iv = getattr(law, "interval", None)  # a smooth law: its kernels end at the represented ends
    if iv:
        return (max(out[1], iv[0]), min(out[0], iv[1]))
    return (out[1], out[0])


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
    pwl: bool = False  # a piecewise-linear law: event location at its breakpoints

    @property
    def stepper(self):
        return PWL_STEPPERS[self.method] if self.pwl else STEPPERS[self.method]


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
    is trimmed); "n_probe_t": the probe series ((probes + 1) × n_probe_t, twice).

    Parameters
    ----------
    L : int
        Number of sites.
    method : str
        Integrator, one of :data:`fpucore.simulate.METHODS` (not validated here).
    n_snapshots, n_sites_out : int
        Stored field times and sites kept per snapshot.
    n_probes, n_probe_t : int
        Number of probes and times of each probe series.
    n_track : int
        Profiles of the tracking window.
    n_extra : int
        Full-resolution profiles at extra times.
    n_events : int
        Events stored per site.
    estimate_error : bool
        Whether a fixed-step method runs its step-doubling companion (doubles its state).

    Returns
    -------
    dict of str to (float, str)
        {"L", "n_snapshots", "n_probe_t"}: (bytes, what sets them).
    """
    st = STEPPERS[method]
    per_site = st.floats_per_site()
    if not st.adaptive and estimate_error:  # the step-doubling companion run
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
    law: HardeningSofteningLaw,
    L: int,
    t_end: float,
    method: str,
    rtol: float,
    dt: float | None,
    estimate_error: bool = True,
    n_stops: int = 240,
) -> dict:
    """Rough work of a run before it starts: {"steps", "site_evals", "seconds"}.  Fixed step:
    t_end/dt plus one shortened step per output stop (``n_stops``; + half as many for the
    step-doubling companion); adaptive: t_end·ω_max/(h·ω) with the measured h·ω of
    :data:`H_OMEGA_AT_1E10` scaled as rtol^(1/(q+1)) (a factor ~3 either way: the data, not only
    the law, set the step).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law (its largest sound speed c_max, sites per unit time).
    L : int
        Number of sites, in [1, 10¹²].
    t_end : float
        Final time (time units), in (0, 1e7].
    method : str
        Integrator, one of :data:`fpucore.simulate.METHODS`.
    rtol : float
        Relative tolerance of an adaptive method, in [1e-16, 1].
    dt : float or None
        Step (time units) of a fixed-step method, in (0, 1e3].
    estimate_error : bool
        Whether a fixed-step method runs its step-doubling companion.
    n_stops : int
        Output stops (each shortens one fixed step).

    Returns
    -------
    dict
        {"steps": float, "site_evals": float, "seconds": float (wall seconds, rough)}.

    Raises
    ------
    ParameterError
        When ``law``, ``method``, ``L``, ``t_end``, ``rtol`` or ``dt`` is invalid.
    """
    law = require_law(law)
    if method not in STEPPERS:
        raise ParameterError("method", method, " | ".join(METHODS))
    L = require_int("L", L, 1, 10**12)
    t_end = require_positive("t_end", t_end, 1e7)
    st = STEPPERS[method]
    if not st.adaptive:
        dt = require_positive("dt", dt, 1e3)
        steps = (t_end / dt + n_stops) * (1.5 if estimate_error else 1.0)
    else:
        rtol = require_in("rtol", rtol, 1e-16, 1.0)
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
    pwl = bool(getattr(require_law(law), "breakpoints", ()))
    t_end = require_positive("t_end", t_end, 1e7)
    if boundary not in BOUNDARIES:
        raise ParameterError("boundary", boundary, " | ".join(BOUNDARIES))
    if method not in STEPPERS:
        raise ParameterError("method", method, " | ".join(METHODS))
    if pwl and method not in PWL_STEPPERS:
        raise ParameterError(
            "method", method, " | ".join(PWL_STEPPERS),
            "a piecewise-linear law is integrated with event location at its breakpoints, "
            "implemented for the RKN pairs",
        )  # fmt: skip
    rtol = require_finite("rtol", rtol)
    if not (1e-14 <= rtol <= 1e-2):
        raise ParameterError("rtol", rtol, "[1e-14, 1e-2]")
    atol = rtol if atol is None else require_positive("atol", atol, 1.0)
    if not STEPPERS[method].adaptive:
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
        L, t_end, boundary, method, rtol, atol, None if STEPPERS[method].adaptive else dt,
        n_snapshots, max_sites_out, probe_idx, n_probe_t, late_fraction, n_track, max_steps,
        estimate_error, track, n_events, guard, time_budget_s, total, work, pwl,
    )  # fmt: skip
