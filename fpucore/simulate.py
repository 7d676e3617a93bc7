"""Direct numerical simulation of the FPU chain (paper §6: eqs. FPUsystem, Riemann_data, GaussIC,
and the runs seeded with computed traveling waves, Figs. stabSK, Riemann1, stabSW, SWdyn).

Drivers :func:`riemann`, :func:`gaussian`, :func:`seeded` build the initial state, integrate it
with the Numba kernels of :mod:`fpucore.chain_kernels` and return a :class:`SimulationResult`
carrying the space-time field (decimated), probe time series, the conserved energy and its drift,
the integrator's own error estimate, wall time, and the waves found by :mod:`fpucore.tracking`.

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
    stopped (status ``"left_convex"``) — see docs/simulation.md.

Methods: ``"dop853"`` (default) and ``"dopri5"`` — adaptive embedded Dormand–Prince pairs with
tolerance ``rtol`` (atol defaults to rtol); ``"symplectic"`` — 4th-order Yoshida composition of
velocity Verlet with fixed step ``dt`` (bounded energy error on long runs).

Guard (``guard``): after every step all strains are checked.  ``"convex"`` (default) stops the run
(status ``"left_convex"``, with a message) as soon as a strain leaves (α, β); ``"bounded"`` only
stops it outside the zeros of f around 0 (:func:`restoring_interval`), beyond which the cubic
potential has no restoring force and the strain runs away; excursions outside (α, β) are then
reported in ``message`` and ``details["strain_range"]``.  A run never returns infinities.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from . import chain_kernels as ck
from . import tracking
from .errors import ParameterError, require_finite
from .law import HardeningSofteningLaw
from .rk_embedded import get as _get_tableau

BOUNDARIES = ("fixed_particles", "fixed_strain", "free")
GUARDS = ("convex", "bounded")
METHODS = ("dop853", "dopri5", "symplectic")
MAX_L = 10_000_000
_STATUS = {
    ck.ST_OK: "ok",
    ck.ST_BUDGET: "budget",
    ck.ST_LEFT_CONVEX: "left_convex",
    ck.ST_STEP_UNDERFLOW: "step_underflow",
    ck.ST_NONFINITE: "nonfinite",
}


@dataclass(frozen=True)
class SimulationResult:
    """Outcome of one chain simulation.

    t : (n_t,) snapshot times; sites : (n_sites_out,) 1-based site numbers n kept in the output;
    snapshots : (n_t, n_sites_out) strains w_n(t_k); probe_sites : (P,) 1-based sites;
    probe_t : (M,) and probe_series : (P, M) strains at the probe sites on a uniform time grid
    (quintic Hermite interpolation between steps); energy : (n_t,) conserved energy H (see the
    module docstring for which H per boundary) at the snapshot times; energy_drift :
    max_k |H(t_k) − H(0)| / E_scale (relative; E_scale = Σ of the absolute values of the terms of H
    at t = 0), energy_drift_abs the same unscaled; error_estimate : the integrator's own error
    estimate — for adaptive RK the accumulated local error estimates (absolute, RMS over the
    state), for the symplectic method the step-doubling difference of the strains,
    max|w_h − w_2h| / 15, at the snapshot times; waves : tracked waves (:class:`TrackedWave`);
    status : "ok" | "left_convex" | "budget" | "step_underflow" | "nonfinite"; success : status
    == "ok"; message : human-readable summary (reason + suggestion on failure).
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
    status: str
    message: str
    elapsed_s: float
    details: dict = field(default_factory=dict)

    @property
    def success(self) -> bool:
        return self.status == "ok"

    def summary(self) -> dict:
        """JSON-friendly summary (no arrays)."""
        return {
            "scenario": self.scenario,
            "L": self.L,
            "boundary": self.boundary,
            "method": self.method,
            "rtol": self.rtol,
            "dt": self.dt,
            "t_final": self.t_final,
            "status": self.status,
            "message": self.message,
            "waves": [w.as_dict() for w in self.waves],
            "energy_drift": self.energy_drift,
            "energy_drift_abs": self.energy_drift_abs,
            "energy": self.energy_name,
            "error_estimate": self.error_estimate,
            "n_steps": self.n_steps,
            "n_rejected": self.n_rejected,
            "n_rhs": self.n_rhs,
            "elapsed_s": self.elapsed_s,
            "details": self.details,
        }


TrackedWave = tracking.TrackedWave


# --------------------------------------------------------------------------- validation
def _require_L(L) -> int:
    try:
        Li = int(L)
    except (TypeError, ValueError):
        raise ParameterError("L", L, f"an integer in [16, {MAX_L}]") from None
    if Li != L or not (16 <= Li <= MAX_L):
        raise ParameterError("L", L, f"an integer in [16, {MAX_L}]")
    return Li


def _require_positive(name: str, x, hi: float = 1e9) -> float:
    x = require_finite(name, x)
    if not (0.0 < x <= hi):
        raise ParameterError(name, x, f"(0, {hi:g}]")
    return x


def _energy_terms(law, y: np.ndarray, L: int, bc: str, fL: float, fR: float):
    """(H, E_scale) for the state y; see the module docstring for H per boundary."""
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


def restoring_interval(law: HardeningSofteningLaw) -> tuple[float, float]:
    """The zeros of f adjacent to 0, (w_lo, w_hi) ⊃ (α, β): inside, f(w) has the sign of w (the
    spring resists); beyond them the potential Φ decreases without bound for the cubic law, so a
    strain that passes them runs away.  Cubic a = −1, b = 10: (5 − √26, 5 + √26)."""
    from scipy.optimize import brentq

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


def _finalize_events(y, L, thr, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n) -> None:
    """Confirm the pending extremum candidate of every site if the strain has since moved away
    from it by more than the prominence threshold (otherwise a wave that passed a site shortly
    before the end, with no later opposite extremum, would be missed)."""
    K = ev_t.shape[1]
    for n in np.nonzero(zdir)[0]:
        if ev_n[n] < K and abs(zz[n, 0] - y[n]) > thr:
            k = ev_n[n]
            ev_t[n, k], ev_w[n, k], ev_s[n, k] = zt[n], zz[n, 0], zdir[n]
            ev_n[n] += 1


# --------------------------------------------------------------------------- core runner
def _run(
    law: HardeningSofteningLaw,
    scenario: str,
    w0: np.ndarray,
    v0: np.ndarray,
    t_end: float,
    boundary: str,
    w_ends: tuple[float, float],
    method: str,
    rtol: float,
    atol: float | None,
    dt: float | None,
    n_snapshots: int,
    max_sites_out: int,
    probes: Sequence[int],
    n_probe_t: int,
    origin: float,
    threshold: float,
    extra_times: Sequence[float] = (),
    late_fraction: float = 1.0 / 3.0,
    n_track: int = 41,
    max_steps: int = 20_000_000,
    progress: Callable[[float], None] | None = None,
    estimate_error: bool = True,
    track: bool = True,
    n_events: int = 16,
    guard: str = "convex",
    level: float | None = None,
):
    t_start = time.perf_counter()
    L = w0.size
    t_end = _require_positive("t_end", t_end, 1e7)
    if boundary not in BOUNDARIES:
        raise ParameterError("boundary", boundary, " | ".join(BOUNDARIES))
    if method not in METHODS:
        raise ParameterError("method", method, " | ".join(METHODS))
    rtol = require_finite("rtol", rtol)
    if not (1e-14 <= rtol <= 1e-2):
        raise ParameterError("rtol", rtol, "[1e-14, 1e-2]")
    atol = rtol if atol is None else _require_positive("atol", atol, 1.0)
    if method == "symplectic":
        dt = 0.02 if dt is None else _require_positive("dt", dt, 0.1)
    n_snapshots = int(n_snapshots)
    if not (2 <= n_snapshots <= 100_000):
        raise ParameterError("n_snapshots", n_snapshots, "[2, 100000]")
    max_sites_out = int(max_sites_out)
    if not (2 <= max_sites_out <= 10_000_000):
        raise ParameterError("max_sites_out", max_sites_out, "[2, 10000000]")
    probe_idx = np.array([int(s) - 1 for s in probes], dtype=np.int64)  # 1-based sites in
    if probe_idx.size and (probe_idx.min() < 0 or probe_idx.max() >= L):
        raise ParameterError("probes", list(probes), f"site numbers in [1, {L}]")
    conv = (float(law.alpha), float(law.beta))
    rest = restoring_interval(law)
    if guard not in GUARDS:
        raise ParameterError("guard", guard, " | ".join(GUARDS))
    lo, hi = conv if guard == "convex" else rest
    for name, x in (("initial strain min", w0.min()), ("initial strain max", w0.max())):
        if not (lo < x < hi):
            raise ParameterError(
                name,
                float(x),
                f"({lo:.10g}, {hi:.10g})",
                "initial strains must lie in the convex interval (alpha, beta); guard='bounded' "
                "allows strains up to the zeros of f"
                if guard == "convex"
                else "initial strains must lie where the force is restoring",
            )

    bc_code = ck.BC_FIXED_PARTICLES if boundary == "fixed_particles" else ck.BC_LOAD
    if boundary == "fixed_strain":
        fL, fR = float(law.f(w_ends[0])), float(law.f(w_ends[1]))
    else:
        fL = fR = 0.0
    if boundary == "fixed_particles" and (v0[0] != 0.0 or v0[-1] != 0.0):
        raise ParameterError(
            "boundary",
            boundary,
            "fixed_strain | free",
            "the initial data move the end particles (v_0 or v_L ≠ 0), they cannot be held",
        )

    # time schedule: output snapshots ∪ tracking snapshots (late window) ∪ extra (full-res)
    t_out = np.linspace(0.0, t_end, n_snapshots)
    t_a = t_end * (1.0 - late_fraction)
    t_trk = np.linspace(t_a, t_end, n_track) if track else np.empty(0)
    t_extra = np.asarray(sorted(float(x) for x in extra_times if 0 < x <= t_end))
    stops = np.unique(np.concatenate([t_out[1:], t_trk, t_extra]))
    stops = stops[stops > 0]
    out_set = {float(x): k for k, x in enumerate(t_out)}
    trk_set = {float(x): k for k, x in enumerate(t_trk)}
    ext_set = {float(x): k for k, x in enumerate(t_extra)}

    if L <= max_sites_out:
        site_idx = np.arange(L)
    else:
        site_idx = np.unique(np.linspace(0, L - 1, max_sites_out).round().astype(np.int64))

    n = 2 * L + 2
    y = np.zeros(n)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    p = law.params
    alpha, beta = lo, hi  # the guard interval checked after every step

    # observer storage
    thr_ev = 0.5 * threshold
    level = float(law.w_star) if level is None else float(level)
    zz = np.empty((L, 3))
    zz[:, 0] = w0
    zz[:, 1] = w0
    zz[:, 2] = w0
    zt = np.zeros(L)
    zdir = np.zeros(L, np.int8)
    ev_t = np.full((L, n_events), np.nan)
    ev_w = np.full((L, n_events), np.nan)
    ev_s = np.zeros((L, n_events), np.int8)
    ev_n = np.zeros(L, np.int64)
    cr_t = np.full((L, 4), np.nan)
    cr_s = np.zeros((L, 4), np.int8)
    cr_n = np.zeros(L, np.int64)
    probe_t = np.linspace(0.0, t_end, int(n_probe_t))
    probe_out = np.full((probe_idx.size, probe_t.size), np.nan)
    probe_out[:, 0] = w0[probe_idx]
    pcount = np.ones(1, np.int64)
    cwork = np.zeros(6)
    stats = np.zeros(6)
    bad = np.array([0.0, 0.0, w0.min(), w0.max()])
    g = np.zeros(L + 2)

    snaps = np.full((t_out.size, site_idx.size), np.nan)
    snaps[0] = w0[site_idx]
    energy = np.full(t_out.size, np.nan)
    H0, E_scale = _energy_terms(law, y, L, boundary, fL, fR)
    energy[0] = H0
    trk_w = np.full((t_trk.size, L), np.nan)
    ext_w = np.full((t_extra.size, L), np.nan)

    if method == "symplectic":
        k0 = np.zeros(n)
        k1 = np.zeros(n)
        ybuf = np.zeros(n)
        ck.rhs(y, L, law.law_id, p, bc_code, fL, fR, g, k0)
        h = dt
    else:
        tab = _get_tableau(method)
        s = tab.stages
        K = np.zeros((s + 1, n))
        W = np.zeros((3, n))
        ck.rhs(y, L, law.law_id, p, bc_code, fL, fR, g, K[0])
        # initial step (Hairer): h = 0.01 ‖y‖/‖f‖ in the scaled RMS norm, capped
        sc = atol + rtol * np.abs(y)
        d0 = np.sqrt(np.mean((y / sc) ** 2))
        d1 = np.sqrt(np.mean((K[0] / sc) ** 2))
        h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
        h = min(h, 0.1, t_end)
        err_exp = -1.0 / (tab.err_order + 1)

    t = 0.0
    status = ck.ST_OK
    for stop in stops:
        if method == "symplectic":
            t, h, status = ck.yoshida_chunk(
                y, t, float(stop), h, max_steps, L, law.law_id, p, bc_code, fL, fR,
                alpha, beta, k0, k1, ybuf, g, stats, bad,
                thr_ev, level, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n, cr_t, cr_s, cr_n,
                probe_idx, probe_t, probe_out, pcount, cwork,
            )  # fmt: skip
        else:
            t, h, status = ck.erk_chunk(
                y, t, float(stop), h, tab.A, tab.B, tab.E5, tab.E3, tab.dual, err_exp,
                rtol, atol, max_steps, L, law.law_id, p, bc_code, fL, fR, alpha, beta,
                K, W, g, stats, bad,
                thr_ev, level, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n, cr_t, cr_s, cr_n,
                probe_idx, probe_t, probe_out, pcount, cwork,
            )  # fmt: skip
        if status != ck.ST_OK:
            break
        key = float(stop)
        if key in out_set:
            k = out_set[key]
            snaps[k] = y[site_idx]
            energy[k] = _energy_terms(law, y, L, boundary, fL, fR)[0]
        if key in trk_set:
            trk_w[trk_set[key]] = y[:L]
        if key in ext_set:
            ext_w[ext_set[key]] = y[:L]
        if progress is not None:
            progress(t / t_end)

    st = _STATUS.get(status, "failed")
    _finalize_events(y, L, thr_ev, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n)
    done = np.isfinite(energy)
    dE = np.abs(energy[done] - H0)
    drift_abs = float(dE.max()) if dE.size else 0.0
    drift = drift_abs / E_scale if E_scale > 0 else drift_abs
    if method == "symplectic":
        err_est = math.nan
        if estimate_error and st == "ok":
            err_est = _step_doubling(
                law, w0, v0, t_out, boundary, bc_code, fL, fR, dt, snaps, site_idx, max_steps
            )
    else:
        err_est = float(stats[3])

    w_min, w_max = float(bad[2]), float(bad[3])
    outside = w_min <= conv[0] or w_max >= conv[1]
    if st == "ok":
        msg = f"reached t = {t:.6g} in {int(stats[0])} steps ({int(stats[1])} rejected)"
        if outside:
            msg += (
                f"; strains went outside the convex interval ({conv[0]:.6g}, {conv[1]:.6g}): "
                f"range [{w_min:.6g}, {w_max:.6g}] (guard 'bounded' allows ({lo:.6g}, {hi:.6g}))"
            )
    elif st == "left_convex":
        if guard == "convex":
            msg = (
                f"stopped at t = {t:.6g}: strain w_{int(bad[1]) + 1} = {bad[0]:.6g} left the "
                f"convex interval (alpha, beta) = ({alpha:.6g}, {beta:.6g}) (guard='convex'). "
                f"Beyond it f' < 0, and beyond the zeros of f ({rest[0]:.6g}, {rest[1]:.6g}) "
                "the cubic potential is unbounded. Suggestion: guard='bounded' to continue "
                "through transient excursions (stops only outside the zeros of f); for a "
                "Riemann run use boundary='fixed_particles' or 'fixed_strain'"
            )
        else:
            msg = (
                f"stopped at t = {t:.6g}: strain w_{int(bad[1]) + 1} = {bad[0]:.6g} left the "
                f"interval between the zeros of f ({alpha:.6g}, {beta:.6g}); beyond it the "
                "cubic potential has no restoring force and the strain runs away. Suggestion: "
                "smaller data, boundary='fixed_particles' or 'fixed_strain', or a longer chain"
            )
    elif st == "budget":
        msg = (
            f"step budget max_steps={max_steps} exhausted at t = {t:.6g}; suggestion: loosen "
            "rtol or raise max_steps"
        )
    else:
        msg = f"integration failed ({st}) at t = {t:.6g}; suggestion: loosen rtol / reduce dt"

    # a run stopped early returns only the times it reached: no NaN rows for times never computed
    keep = np.isfinite(energy) & np.all(np.isfinite(snaps), axis=1)
    t_out, snaps, energy = t_out[keep], snaps[keep], energy[keep]
    if probe_out.size:
        pk = np.all(np.isfinite(probe_out), axis=0)
        probe_t, probe_out = probe_t[pk], probe_out[:, pk]

    waves = []
    if track and st == "ok":
        waves = tracking.track(
            law,
            t_trk,
            trk_w,
            origin=origin,
            threshold=threshold,
            events=(ev_t, ev_w, ev_s),
            crossings=(cr_t, cr_s),
            level=level,
        )

    res = dict(
        scenario=scenario,
        L=L,
        boundary=boundary,
        method=method,
        rtol=rtol,
        dt=dt if method == "symplectic" else None,
        t=t_out,
        sites=site_idx + 1,
        snapshots=snaps,
        probe_sites=probe_idx + 1,
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
        status=st,
        message=msg,
        elapsed_s=time.perf_counter() - t_start,
    )
    res["details"] = {
        "guard": guard,
        "guard_interval": [lo, hi],
        "strain_range": [w_min, w_max],
        "left_convex_interval": bool(outside),
    }
    internals = dict(ext_t=t_extra, ext_w=ext_w, events=(ev_t, ev_w, ev_s), cr=(cr_t, cr_s))
    return res, internals


_ENERGY_NAME = {
    "fixed_particles": "H = sum_{j=1}^{L-1} v_j^2/2 + sum_n Phi(w_n) (end particles at rest)",
    "free": "H = sum_{j=0}^{L} v_j^2/2 + sum_n Phi(w_n)",
    "fixed_strain": (
        "H = sum_{j=0}^{L} v_j^2/2 + sum_n [Phi(w_n) - f(w_right) w_n] "
        "+ (f(w_left) - f(w_right)) u_0 (dead-load potential included)"
    ),
}


def _step_doubling(law, w0, v0, t_out, boundary, bc_code, fL, fR, dt, snaps, site_idx, max_steps):
    """max |w_h − w_2h| / (2⁴ − 1) over the output snapshots (Yoshida is 4th order)."""
    L = w0.size
    n = 2 * L + 2
    y = np.zeros(n)
    y[:L] = w0
    y[L : 2 * L + 1] = v0
    p = law.params
    k0, k1, ybuf, g = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(L + 2)
    ck.rhs(y, L, law.law_id, p, bc_code, fL, fR, g, k0)
    stats, bad = np.zeros(6), np.array([0.0, 0.0, np.inf, -np.inf])
    e = np.zeros((L, 1))
    ei = np.zeros((L, 1), np.int8)
    en = np.zeros(L, np.int64)
    zz = np.zeros((L, 3))
    zz[:, 1] = -np.inf
    zz[:, 2] = np.inf
    zt, zdir = np.zeros(L), np.zeros(L, np.int8)
    pidx, pt, pout, pc = np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 0)), np.zeros(1, np.int64)
    worst = 0.0
    t = 0.0
    for k in range(1, t_out.size):
        t, _, status = ck.yoshida_chunk(
            y, t, float(t_out[k]), 2.0 * dt, max_steps, L, law.law_id, p, bc_code, fL, fR,
            law.alpha, law.beta, k0, k1, ybuf, g, stats, bad,
            np.inf, np.nan, zz, zt, zdir, e, e, ei, en, e, ei, en,
            pidx, pt, pout, pc, np.zeros(6),
        )  # fmt: skip
        if status != ck.ST_OK:
            return math.nan
        worst = max(worst, float(np.max(np.abs(y[site_idx] - snaps[k]))))
    return worst / 15.0


# --------------------------------------------------------------------------- scenarios
def _common_kwargs(kw: dict) -> dict:
    allowed = {
        "method", "rtol", "atol", "dt", "n_snapshots", "max_sites_out", "probes", "n_probe_t",
        "threshold", "late_fraction", "max_steps", "progress", "estimate_error", "track", "guard",
    }  # fmt: skip
    bad = set(kw) - allowed
    if bad:
        raise TypeError(f"unexpected keyword arguments {sorted(bad)}")
    return kw


def riemann(
    law: HardeningSofteningLaw,
    w_left: float,
    w_right: float,
    L: int,
    t_end: float,
    method: str = "dop853",
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
    detection threshold of the wave tracker, default 2 % of |w_left − w_right|."""
    kw = _common_kwargs(kw)
    L = _require_L(L)
    if L % 2:
        raise ParameterError("L", L, "an even integer", "the Riemann jump sits at n = L/2")
    wl = law.require_convex("w_left", w_left)
    wr = law.require_convex("w_right", w_right)
    w0 = np.full(L, wr)
    w0[: L // 2] = wl
    v0 = np.zeros(L + 1)
    thr = 0.02 * abs(wl - wr) if threshold is None else _require_positive("threshold", threshold)
    if thr == 0.0:
        thr = 1e-3
    res, _ = _run(
        law, "riemann", w0, v0, t_end, boundary, (wl, wr), method,
        rtol, kw.pop("atol", None), kw.pop("dt", None), n_snapshots,
        max_sites_out, probes, n_probe_t, origin=L / 2 - 0.5, threshold=thr, **kw,
    )  # fmt: skip
    res["details"].update({"w_left": wl, "w_right": wr, "threshold": thr})
    return SimulationResult(**res)


def gaussian(
    law: HardeningSofteningLaw,
    w_B: float,
    A: float,
    L: int,
    t_end: float,
    method: str = "dop853",
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
    (tracker detection threshold) default 2 % of |A|."""
    kw = _common_kwargs(kw)
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
    nn = np.arange(1, L + 1, dtype=float)
    w0 = wB + A * np.exp(-0.5 * (nn - L / 2) ** 2)
    v0 = np.zeros(L + 1)
    thr = 0.02 * abs(A) if threshold is None else _require_positive("threshold", threshold)
    if thr == 0.0:
        thr = 1e-3
    res, _ = _run(
        law, "gaussian", w0, v0, t_end, boundary, (wB, wB), method,
        rtol, kw.pop("atol", None), kw.pop("dt", None), n_snapshots,
        max_sites_out, probes, n_probe_t, origin=L / 2 - 1.0, threshold=thr, **kw,
    )  # fmt: skip
    res["details"].update({"w_B": wB, "A": A, "threshold": thr})
    return SimulationResult(**res)


def seeded(
    r,
    L: int | None = None,
    t_end: float | None = None,
    method: str = "dop853",
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
    (max_k |t_k − t_0 − k/V|), periods, shape_error (max_n |w_{n+K}(KT) − w_n(0)|, K whole periods).
    """
    kw = _common_kwargs(kw)
    V = require_finite("r.V", r.V)
    if V <= 0:
        raise ParameterError("r.V", V, "V > 0")
    law = r.law
    N = int(r.N)
    T = 1.0 / V
    t_end = 50.0 * T if t_end is None else _require_positive("t_end", t_end, 1e7)
    margin = int(margin)
    if margin < 10:
        raise ParameterError("margin", margin, "an integer >= 10")
    L_min = N + int(math.ceil(V * t_end)) + 2 * margin
    L = L_min if L is None else _require_L(L)
    if L < L_min:
        raise ParameterError(
            "L", L, f">= {L_min}", "the chain must hold the wave and its path plus margins"
        )
    L = _require_L(L)
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
    K_per = int(math.floor(t_end / T + 1e-9))
    amp = abs(float(getattr(r, "amplitude", 0.0)) or abs(wl - wr) or 1.0)
    if r.kind == "superkink":
        amp = abs(wl - wr)
    thr = 0.02 * amp if threshold is None else _require_positive("threshold", threshold)
    # passage level timed at every site: w* for a superkink (w(0) = w*), the half-height of the
    # leading flank for a solitary wave (a crossing time is sharper than an extremum time)
    if r.kind == "superkink":
        level = float(law.w_star)
    else:
        wM = float(np.asarray(r.w)[N // 2])
        level = 0.5 * (wM + wr)
    res, internals = _run(
        law, "seeded", w0, v0, t_end, boundary, (wl, wr), method,
        rtol, kw.pop("atol", None), kw.pop("dt", None), n_snapshots,
        max_sites_out, probes, n_probe_t, origin=float(i0 - 1), threshold=thr,
        extra_times=(K_per * T,) if K_per >= 1 else (), level=level, **kw,
    )  # fmt: skip
    details = {"kind": r.kind, "V_prescribed": V, "N": N, "periods": K_per, "threshold": thr}
    if res["status"] == "ok":
        details.update(_seeded_check(r, internals, site0, i0, N, T, K_per, w0, t_end, law))
    res["details"].update(details)
    return SimulationResult(**res)


def _seeded_check(r, internals, site0, i0, N, T, K_per, w0, t_end, law) -> dict:
    """Velocity from the passage times of the wave at the sites k = 1…K it crosses (level w*
    crossing for a superkink, time-extremum for a solitary wave) and the shape error after K
    whole periods.  For an exact traveling wave t_k = k T (eq. period)."""
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
