"""Direct numerical simulation of the FPU chain (paper §6: eqs. FPUsystem, Riemann_data, GaussIC,
and the runs seeded with computed traveling waves, Figs. stabSK, Riemann1, stabSW, SWdyn).

Drivers :func:`riemann`, :func:`gaussian`, :func:`seeded` build the initial state, integrate it
(:func:`fpucore.simulate.engine.run_chain` over the Numba kernels of
:mod:`fpucore.simulate.kernels`) and return a :class:`SimulationResult` carrying the space-time
field (decimated), probe time series, the conserved energy and its drift, the integrator's own
error estimate, wall time, and the waves found by :mod:`fpucore.simulate.tracking`.

Chain: L springs (sites n = 1…L, strain w_n) between particles 0…L (velocity v_j); eq.
FPUsystem ẇ_n = v_n − v_{n−1}, v̇_j = f(w_{j+1}) − f(w_j).  End conditions (``boundary``):

``"fixed_particles"`` (default for Riemann and Gaussian data)
    the end particles are held at rest, v_0 = v_L = 0 — in the strain form of eq. FPUstrain a zero
    strain gradient at the ends (w_0 = w_1, w_{L+1} = w_L).  Conserved energy
    H = Σ_{j=1}^{L−1} v_j²/2 + Σ_{n=1}^{L} Φ(w_n).
``"fixed_strain"`` (default for seeded runs; the paper's eq. fixedBCs)
    ghost strains w_0 = w_left, w_{L+1} = w_right held constant: a dead load f(w_left) on
    particle 0 and f(w_right) on particle L.  Conserved energy (with the load potential)
    H = Σ_{j=0}^{L} v_j²/2 + Σ_n [Φ(w_n) − f(w_right) w_n] + (f(w_left) − f(w_right)) u_0.
``"free"``
    literally free (stress-free) ends, f(w_0) = f(w_{L+1}) = 0.  H = Σ_{j=0}^{L} v_j²/2 + Σ Φ(w_n).
    With the paper's Riemann data the released end spring is driven below α and the run is
    stopped (stop_reason ``"left_convex"``) — see docs/simulation.md.

Methods (adaptive ones take the tolerance ``rtol``; atol defaults to rtol):

``"rkn12"`` (default)
    Dormand–El-Mikkawy–Prince Runge–Kutta–Nyström 12(10) on the second-order strain form
    ẅ = F(w) (:mod:`fpucore.simulate.rkn`): one force evaluation per stage on half the state of the
    first-order form, and order 12.  On the paper's Riemann run at rtol 1e-10 it takes 2.6x fewer
    steps than DOP853 and its final strains are 100x closer to a converged reference
    (benchmarks/bench_simulate.py).
``"rkn8"``
    the 8(6) member of the same family (FSAL, 8 evaluations per step).
``"dop853"``, ``"dopri5"``
    the first-order Dormand–Prince pairs on (w, v); ``"dopri5"`` is the paper's ode45 pair.
``"symplectic"``
    4th-order Yoshida composition of velocity Verlet with fixed step ``dt`` (bounded energy
    error on long runs).

Guard (``guard``): after every step all strains are checked.  ``"convex"`` (default) stops the run
(stop_reason ``"left_convex"``, with a message) as soon as a strain leaves (α, β); ``"bounded"``
only stops it outside the zeros of f around 0 (:func:`restoring_interval`), beyond which the cubic
potential has no restoring force and the strain runs away; excursions outside (α, β) are then
reported in ``message`` and ``details["strain_range"]``.  A run never returns infinities.

Budgets (:mod:`fpucore.budget`): the memory of a run is estimated from all its sizes (L, the
snapshots × sites kept, probes × probe times, the tracking window) before anything is allocated
and refused above the memory budget (``memory_budget``, FPU_MEMORY_BUDGET, default 25 % of RAM).
``details["work_estimate"]`` holds the estimated steps, site-force evaluations and seconds;
``time_budget_s`` stops a run cleanly (stop_reason ``"time_budget"``, status ``"stopped"``) with
the times it reached; ``max_steps`` bounds the steps (stop_reason ``"budget"``)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.law import HardeningSofteningLaw
from fpucore.parallel.threads import on_budget
from fpucore.result import Result, status_of
from fpucore.simulate import tracking
from fpucore.simulate.config import (
    BOUNDARIES,
    GUARDS,
    MAX_L,
    configure,
    require_positive,
    restoring_interval,
)
from fpucore.simulate.engine import run_chain
from fpucore.simulate.steppers import METHODS

__all__ = [
    "SimulationResult",
    "TrackedWave",
    "riemann",
    "gaussian",
    "seeded",
    "restoring_interval",
    "BOUNDARIES",
    "GUARDS",
    "METHODS",
    "MAX_L",
]


@dataclass(frozen=True)
class SimulationResult(Result):
    """Outcome of one chain simulation.

    t : (n_t,) snapshot times; sites : (n_sites_out,) 1-based site numbers n kept in the output;
    snapshots : (n_t, n_sites_out) strains w_n(t_k); probe_sites : (P,) 1-based sites;
    probe_t : (M,) and probe_series : (P, M) strains at the probe sites on a uniform time grid
    (degree-7 Hermite interpolation between steps); energy : (n_t,) conserved energy H (see the
    module docstring for which H per boundary) at the snapshot times; energy_drift :
    max_k |H(t_k) − H(0)| / E_scale (relative; E_scale = Σ of the absolute values of the terms of H
    at t = 0), energy_drift_abs the same unscaled; error_estimate : the integrator's own error
    estimate — for adaptive RK the accumulated local error estimates (absolute, RMS over the
    state: (w, v) for the first-order pairs, (w, ẇ) for the RKN pairs), for the symplectic
    method the step-doubling difference of the strains, max|w_h − w_2h| / 15, at the snapshot
    times; waves : tracked waves (:class:`TrackedWave`);
    stop_reason : "ok" | "left_convex" | "budget" (max_steps) | "time_budget" (time_budget_s) |
    "step_underflow" | "nonfinite" (why the run ended);
    converged : it reached t_end (stop_reason == "ok"); status : "ok" | "stopped" (the
    common vocabulary of :mod:`fpucore.result`); message : human-readable summary (reason +
    suggestion on failure).
    final_w : (L,) strains at t_final (full resolution).  details : scenario-specific numbers
    (seeded runs: prescribed/measured velocity, phase and shape errors).
    """

    scenario: str
    L: int
    boundary: str
    method: str
    rtol: float
    dt: float | None
    t: np.ndarray
    sites: np.ndarray
    snapshots: np.ndarray
    probe_sites: np.ndarray
    probe_t: np.ndarray
    probe_series: np.ndarray
    energy: np.ndarray
    energy_drift: float
    energy_drift_abs: float
    energy_name: str
    error_estimate: float
    n_steps: int
    n_rejected: int
    n_rhs: int
    t_final: float
    final_w: np.ndarray
    waves: list
    stop_reason: str
    message: str
    elapsed_s: float
    details: dict = field(default_factory=dict)

    ERROR_FIELDS: ClassVar = ("error_estimate", "energy_drift")
    DERIVED: ClassVar = ("status", "converged")

    @property
    def converged(self) -> bool:
        return self.stop_reason == "ok"

    @property
    def success(self) -> bool:  # the name used before the result protocol
        return self.converged

    @property
    def status(self) -> str:
        return status_of(self.converged, stopped=True)

    def summary(self) -> dict:
        """JSON-friendly summary: :meth:`as_dict` without the arrays."""
        return self.as_dict(arrays=False)


TrackedWave = tracking.TrackedWave


# --------------------------------------------------------------------------- validation
def _require_L(L) -> int:
    return require_int("L", L, 16, MAX_L)


def _threshold(threshold, scale: float) -> float:
    """Wave-tracker detection threshold (strain units): the given value (> 0), else 2 % of the
    disturbance's scale (1e-3 where that scale is 0)."""
    if threshold is not None:
        return require_positive("threshold", threshold)
    return 0.02 * scale or 1e-3


# --------------------------------------------------------------------------- scenarios
CONFIG_OPTIONS = (
    "method", "rtol", "atol", "dt", "n_snapshots", "max_sites_out", "probes", "n_probe_t",
    "late_fraction", "max_steps", "estimate_error", "track", "guard", "time_budget_s",
    "memory_budget",
)  # fmt: skip


def _split_kwargs(kw: dict) -> tuple[dict, dict]:
    """(options of :func:`configure`, options of :func:`run_chain`) from a driver's keywords."""
    bad = set(kw) - set(CONFIG_OPTIONS) - {"progress"}
    if bad:
        raise TypeError(f"unexpected keyword arguments {sorted(bad)}")
    run = {"progress": kw.pop("progress")} if "progress" in kw else {}
    return kw, run


@on_budget
def riemann(
    law: HardeningSofteningLaw,
    w_left: float,
    w_right: float,
    L: int,
    t_end: float,
    method: str = "rkn12",
    rtol: float = 1e-10,
    boundary: str = "fixed_particles",
    n_snapshots: int = 200,
    max_sites_out: int = 1000,
    probes: Sequence[int] = (),
    n_probe_t: int = 4001,
    threshold: float | None = None,
    **kw,
) -> SimulationResult:
    """Riemann initial data (eq. Riemann_data): w_n(0) = w_left for n ≤ L/2, w_right for
    n > L/2, ẇ_n(0) = 0 (all particles at rest).  L even.  ``threshold`` (strain units) is the
    detection threshold of the wave tracker, default 2 % of |w_left − w_right|.

    Further keywords (all drivers): atol, dt, late_fraction, max_steps, estimate_error, track,
    guard, ``time_budget_s`` (wall seconds; None = no limit: past it the run stops with
    stop_reason "time_budget" and the times it reached), ``memory_budget`` (bytes or "2GiB";
    default FPU_MEMORY_BUDGET or 25 % of RAM, see :mod:`fpucore.budget`) and ``progress``
    (a callable receiving the fraction of t_end done)."""
    opts, run = _split_kwargs(kw)
    L = _require_L(L)
    if L % 2:
        raise ParameterError("L", L, "an even integer", "the Riemann jump sits at n = L/2")
    wl = law.require_convex("w_left", w_left)
    wr = law.require_convex("w_right", w_right)
    thr = _threshold(threshold, abs(wl - wr))
    cfg = configure(
        law,
        L,
        t_end,
        boundary,
        method,
        rtol,
        n_snapshots=n_snapshots,
        max_sites_out=max_sites_out,
        probes=probes,
        n_probe_t=n_probe_t,
        **opts,
    )
    w0 = np.full(L, wr)
    w0[: L // 2] = wl
    v0 = np.zeros(L + 1)
    res, _ = run_chain(law, "riemann", w0, v0, cfg, (wl, wr), origin=L / 2 - 0.5, threshold=thr,
                       **run)  # fmt: skip
    res["details"].update({"w_left": wl, "w_right": wr, "threshold": thr})
    return SimulationResult(**res)


@on_budget
def gaussian(
    law: HardeningSofteningLaw,
    w_B: float,
    A: float,
    L: int,
    t_end: float,
    method: str = "rkn12",
    rtol: float = 1e-10,
    boundary: str = "fixed_particles",
    n_snapshots: int = 200,
    max_sites_out: int = 1000,
    probes: Sequence[int] = (),
    n_probe_t: int = 4001,
    threshold: float | None = None,
    **kw,
) -> SimulationResult:
    """Gaussian initial data (eq. GaussIC): w_n(0) = w_B + A exp(−(n − L/2)²/2), ẇ_n(0) = 0,
    n = 1…L.  w_B must lie in the convex interval (α, β); w_B + A in it too unless
    ``guard="bounded"`` (the paper's w_B = 1, A = 6 starts at w = 7 > β, and w_B = 6, A = −6
    reaches w ≈ 6.94 > β: both need guard="bounded", see docs/simulation.md).  ``threshold``
    (tracker detection threshold) default 2 % of |A|.  Further keywords as for :func:`riemann`."""
    opts, run = _split_kwargs(kw)
    L = _require_L(L)
    wB = law.require_convex("w_B", w_B)
    A = require_finite("A", A)
    lo, hi = restoring_interval(law)
    if not (lo < wB + A < hi):
        raise ParameterError(
            "A",
            A,
            f"({lo - wB:.10g}, {hi - wB:.10g})",
            "the peak strain w_B + A must lie between the zeros of f, where the spring restores",
        )
    thr = _threshold(threshold, abs(A))
    cfg = configure(
        law,
        L,
        t_end,
        boundary,
        method,
        rtol,
        n_snapshots=n_snapshots,
        max_sites_out=max_sites_out,
        probes=probes,
        n_probe_t=n_probe_t,
        **opts,
    )
    nn = np.arange(1, L + 1, dtype=float)
    w0 = wB + A * np.exp(-0.5 * (nn - L / 2) ** 2)
    v0 = np.zeros(L + 1)
    res, _ = run_chain(law, "gaussian", w0, v0, cfg, (wB, wB), origin=L / 2 - 1.0, threshold=thr,
                       **run)  # fmt: skip
    res["details"].update({"w_B": wB, "A": A, "threshold": thr})
    return SimulationResult(**res)


WAVE_ATTRIBUTES = ("V", "law", "N", "w", "wdot", "w_left", "w_right", "kind")


def _require_wave(r) -> None:
    """A converged traveling wave with the attributes seeded reads (ParameterError 'r')."""
    valid = "a converged traveling wave from fpucore.wave.solve_superkink / solve_solitary"
    value = None if r is None else f"<{type(r).__name__}>"
    missing = [a for a in WAVE_ATTRIBUTES if not hasattr(r, a)]
    if r is None or missing:
        reason = f"missing {', '.join(missing)}" if r is not None else ""
        raise ParameterError("r", value, valid, reason)
    if not getattr(r, "converged", True):
        raise ParameterError("r", value, valid, f"the wave did not converge: {r.message}")
    N = require_int("r.N", r.N, 8, MAX_L)
    for name in ("w", "wdot"):
        x = np.asarray(getattr(r, name), dtype=float)
        if x.shape != (N,) or not np.all(np.isfinite(x)):
            raise ParameterError(f"r.{name}", f"<array {x.shape}>", f"{N} finite numbers")


def whole_periods(t_end: float, T: float) -> tuple[int, float]:
    """(K, t_K): the number K of whole periods T in t_end and their time t_K = K·T ≤ t_end up to
    rounding.  t_end = K/V computed in floating point can fall an ulp short of K·(1/V) (for ~9 %
    of velocities): such a t_end counts as K periods, and t_K (≤ t_end (1 + 1e-12)) is taken at
    t_end by the output schedule (:func:`fpucore.simulate.config.output_schedule`)."""
    t_end, T = require_finite("t_end", t_end), require_finite("T", T)
    if not T > 0.0:
        raise ParameterError("T", T, "a period T > 0", "there are no whole periods of length 0")
    if not t_end >= 0.0:
        raise ParameterError("t_end", t_end, "t_end >= 0")
    K = int(math.floor(t_end / T + 1e-9))
    if K >= 1 and K * T > t_end * (1.0 + 1e-12):
        K -= 1  # t_end more than rounding short of K periods: the last whole one is K − 1
    return K, K * T


@on_budget
def seeded(
    r,
    L: int | None = None,
    t_end: float | None = None,
    method: str = "rkn12",
    rtol: float = 1e-12,
    boundary: str = "fixed_strain",
    n_snapshots: int = 200,
    max_sites_out: int = 1000,
    probes: Sequence[int] = (),
    n_probe_t: int = 4001,
    threshold: float | None = None,
    margin: int = 100,
    **kw,
) -> SimulationResult:
    """Run seeded with a computed discrete traveling wave ``r`` (from fpucore.wave.solve_superkink
    / solve_solitary): w_n(0) = r.w, ẇ_n(0) = r.wdot on the N computed sites, placed ``margin``
    sites from the left end of a chain of L sites; outside, the limiting strains r.w_left /
    r.w_right at rest relative to their side.  Particle velocities from ẇ with v_L = 0.
    Default end condition: the paper's fixed boundary strains (eq. fixedBCs).

    t_end default: 50 periods T = 1/V.  L default: N + ⌈V t_end⌉ + 2·margin.  ``details`` holds
    V_prescribed, V_measured (fit of the passage times t_k at the sites k = 1…K the wave passes —
    crossings of w* for a superkink, of the half-height of the leading flank for a solitary wave;
    t_k = t_0 + k/V exactly for a traveling wave, eq. period), velocity_error, phase_error_max
    (max_k |t_k − t_0 − k/V|), periods, shape_error (max_n |w_{n+K}(KT) − w_n(0)|, K whole periods,
    :func:`whole_periods`).  Further keywords as for :func:`riemann`.
    """
    opts, run = _split_kwargs(kw)
    _require_wave(r)
    V = require_finite("r.V", r.V)
    if V <= 0:
        raise ParameterError("r.V", V, "V > 0")
    law = r.law
    N = int(r.N)
    T = 1.0 / V
    t_end = 50.0 * T if t_end is None else require_positive("t_end", t_end, 1e7)
    margin = require_int("margin", margin, 10, MAX_L)
    L_min = N + int(math.ceil(V * t_end)) + 2 * margin
    if L is None and L_min > MAX_L:
        raise ParameterError(
            "t_end", t_end, f"(0, {(MAX_L - N - 2 * margin) / V:.6g}]",
            f"the wave's path V·t_end needs a chain longer than L = {MAX_L}",
        )  # fmt: skip
    L = L_min if L is None else _require_L(L)
    if L < L_min:
        raise ParameterError(
            "L", L, f">= {L_min}", "the chain must hold the wave and its path plus margins"
        )
    L = _require_L(L)
    K_per, t_K = whole_periods(t_end, T)
    extra = (t_K,) if K_per >= 1 else ()
    thr_scale = abs(float(getattr(r, "amplitude", 0.0)) or abs(r.w_left - r.w_right) or 1.0)
    if r.kind == "superkink":
        thr_scale = abs(r.w_left - r.w_right)
    thr = _threshold(threshold, thr_scale)
    cfg = configure(law, L, t_end, boundary, method, rtol, n_snapshots=n_snapshots,
                    max_sites_out=max_sites_out, probes=probes, n_probe_t=n_probe_t,
                    n_extra=len(extra), **opts)  # fmt: skip
    wl, wr = float(r.w_left), float(r.w_right)
    i0 = margin  # chain index of the first computed site (n = −N/2)
    w0 = np.full(L, wr)
    w0[:i0] = wl
    w0[i0 : i0 + N] = np.asarray(r.w, float)
    wd = np.zeros(L)
    wd[i0 : i0 + N] = np.asarray(r.wdot, float)
    v0 = np.zeros(L + 1)
    v0[:L] = -np.cumsum(wd[::-1])[::-1]  # v_{j} = v_{j+1} − ẇ_{j+1}, v_L = 0
    site0 = i0 + N // 2  # chain index of the wave's site n = 0
    # passage level timed at every site: w* for a superkink (w(0) = w*), the half-height of the
    # leading flank for a solitary wave (a crossing time is sharper than an extremum time)
    if r.kind == "superkink":
        level = float(law.w_star)
    else:
        wM = float(np.asarray(r.w)[N // 2])
        level = 0.5 * (wM + wr)
    res, internals = run_chain(
        law, "seeded", w0, v0, cfg, (wl, wr), origin=float(i0 - 1), threshold=thr,
        extra_times=extra, level=level, **run,
    )  # fmt: skip
    details = {"kind": r.kind, "V_prescribed": V, "N": N, "periods": K_per, "threshold": thr}
    if res["stop_reason"] == "ok":
        details.update(_seeded_check(r, internals, site0, i0, N, T, K_per, w0, t_end, law))
    res["details"].update(details)
    return SimulationResult(**res)


def _seeded_check(r, internals, site0, i0, N, T, K_per, w0, t_end, law) -> dict:
    """Velocity from the passage times of the wave at the sites k = 1…K it crosses (crossings
    of w* for a superkink, of the leading flank's half-height for a solitary wave) and the shape
    error after K whole periods.  For an exact traveling wave t_k = k T (eq. period)."""
    cr_t, cr_s = internals["cr"]
    if r.kind == "superkink":
        want = 1 if r.w_left > r.w_right else -1  # passing front: w goes from w_right to w_left
    else:
        want = 1 if r.kind == "tensile" else -1  # leading flank
    ks, ts = [], []
    for k in range(1, K_per + 1):
        n = site0 + k
        ok = np.nonzero((cr_s[n] == want) & np.isfinite(cr_t[n]))[0]
        if ok.size:
            ks.append(k)
            ts.append(cr_t[n, ok[0]])
    out: dict = {}
    if len(ks) >= 3:
        ks_a, ts_a = np.asarray(ks, float), np.asarray(ts)
        slope, icpt = np.polyfit(ks_a, ts_a, 1)
        Vm = 1.0 / slope
        out.update(
            V_measured=float(Vm),
            velocity_error=float(abs(Vm - r.V)),
            phase_error_max=float(np.max(np.abs(ts_a - (icpt + ks_a * T)))),
            n_sites_timed=len(ks),
        )
    if K_per >= 1 and internals["ext_w"].shape[0]:
        wK = internals["ext_w"][0]
        sl = slice(i0, i0 + N)
        shifted = wK[i0 + K_per : i0 + K_per + N]
        out["shape_error"] = float(np.max(np.abs(shifted - w0[sl])))
        out["shape_error_rel"] = out["shape_error"] / max(1e-300, float(np.ptp(w0[sl])))
    return out
