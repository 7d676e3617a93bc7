"""Integration engine of the chain simulations (paper §6): state layout, guards, the
conserved energies per end condition, the stepping loop with snapshots/probes/events, and the
symplectic step-doubling error estimate.  The scenario drivers (:func:`fpucore.simulate.riemann`,
``gaussian``, ``seeded``) build initial data and call :func:`run_chain`; see
:mod:`fpucore.simulate` for the end conditions, guards and energies."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np
from scipy.optimize import brentq

from fpucore.errors import ParameterError, require_finite
from fpucore.law import HardeningSofteningLaw
from fpucore.simulate import kernels as ck
from fpucore.simulate import rkn as crk
from fpucore.simulate import tracking
from fpucore.tableaux import rkn as rkn_tableaux
from fpucore.tableaux.embedded import get as get_embedded

BOUNDARIES = ("fixed_particles", "fixed_strain", "free")
GUARDS = ("convex", "bounded")
METHODS = ("rkn12", "dop853", "dopri5", "rkn8", "symplectic")
RKN_METHODS = ("rkn12", "rkn8")
MAX_L = 10_000_000
_STATUS = {
    ck.ST_OK: "ok",
    ck.ST_BUDGET: "budget",
    ck.ST_LEFT_CONVEX: "left_convex",
    ck.ST_STEP_UNDERFLOW: "step_underflow",
    ck.ST_NONFINITE: "nonfinite",
}


def require_positive(name: str, x, hi: float = 1e9) -> float:
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
        if ev_n[n] < K and abs(zz[0, n] - y[n]) > thr:
            k = ev_n[n]
            ev_t[n, k], ev_w[n, k], ev_s[n, k] = zt[n], zz[0, n], zdir[n]
            ev_n[n] += 1


def _initial_step(y: np.ndarray, dy: np.ndarray, rtol: float, atol: float, t_end: float) -> float:
    """Hairer's starting step h = 0.01 ‖y‖/‖ẏ‖ in the scaled RMS norm, capped at 0.1 and t_end."""
    sc = atol + rtol * np.abs(y)
    d0 = np.sqrt(np.mean((y / sc) ** 2))
    d1 = np.sqrt(np.mean((dy / sc) ** 2))
    h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h, 0.1, t_end)


# --------------------------------------------------------------------------- core runner
def run_chain(
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
    t_end = require_positive("t_end", t_end, 1e7)
    if boundary not in BOUNDARIES:
        raise ParameterError("boundary", boundary, " | ".join(BOUNDARIES))
    if method not in METHODS:
        raise ParameterError("method", method, " | ".join(METHODS))
    rtol = require_finite("rtol", rtol)
    if not (1e-14 <= rtol <= 1e-2):
        raise ParameterError("rtol", rtol, "[1e-14, 1e-2]")
    atol = rtol if atol is None else require_positive("atol", atol, 1.0)
    if method == "symplectic":
        dt = 0.02 if dt is None else require_positive("dt", dt, 0.1)
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
    zz = np.empty((3, L))  # per site: extremum candidate, running min, running max
    zz[:] = w0
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
    cwork = np.zeros(8)  # Hermite coefficients
    stats = np.zeros(6)
    bad = np.zeros(2)  # value and site of a strain that left the guard interval
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
        acc = np.zeros((2, L))
        ck.rhs(y, L, law.law_id, p, bc_code, fL, fR, g, k0)
        h = dt
    elif method in RKN_METHODS:
        rk = rkn_tableaux.get(method)
        s = rk.stages
        qv = np.zeros(L + 1)
        K = np.zeros((s + 3, L + 1))  # K[0] = F(q), K[s+1] = q̇ (see chain_rkn.rkn_chunk)
        W = np.zeros((7, L + 1))
        crk.y_to_rkn(y, L, qv, K[s + 1])
        crk.accel(qv, L, law.law_id, p, bc_code, fL, fR, g, K[0])
        h = _initial_step(np.concatenate([qv, K[s + 1]]), np.concatenate([K[s + 1], K[0]]),
                          rtol, atol, t_end)  # fmt: skip
        err_exp = -1.0 / (rk.err_order + 1)
        rk_args = (rk.c, rk.A, rk.b, rk.bp, rk.e, rk.ep, rk.fsal, err_exp)
    else:
        tab = get_embedded(method)
        s = tab.stages
        K = np.zeros((s + 1, n))
        W = np.zeros((5, n))
        ck.rhs(y, L, law.law_id, p, bc_code, fL, fR, g, K[0])
        h = _initial_step(y, K[0], rtol, atol, t_end)
        err_exp = -1.0 / (tab.err_order + 1)

    t = 0.0
    status = ck.ST_OK
    for stop in stops:
        if method == "symplectic":
            t, h, status = ck.yoshida_chunk(
                y, t, float(stop), h, max_steps, L, law.law_id, p, bc_code, fL, fR,
                alpha, beta, k0, k1, ybuf, acc, g, stats, bad,
                thr_ev, level, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n, cr_t, cr_s, cr_n,
                probe_idx, probe_t, probe_out, pcount, cwork,
            )  # fmt: skip
        elif method in RKN_METHODS:
            t, h, status = crk.rkn_chunk(
                qv, t, float(stop), h, *rk_args, rtol, atol, max_steps,
                L, law.law_id, p, bc_code, fL, fR, alpha, beta, K, W, g, stats, bad,
                thr_ev, level, zz, zt, zdir, ev_t, ev_w, ev_s, ev_n, cr_t, cr_s, cr_n,
                probe_idx, probe_t, probe_out, pcount, cwork,
            )  # fmt: skip
            crk.rkn_to_y(qv, K[s + 1], L, y)  # snapshots, energy and events read y
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

    w_min, w_max = float(zz[1].min()), float(zz[2].max())  # the strain range over all steps
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
        stop_reason=st,
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
    stats, bad = np.zeros(6), np.zeros(2)
    e = np.zeros((L, 1))
    ei = np.zeros((L, 1), np.int8)
    en = np.zeros(L, np.int64)
    zz = np.zeros((3, L))
    zz[1] = -np.inf
    zz[2] = np.inf
    zt, zdir = np.zeros(L), np.zeros(L, np.int8)
    pidx, pt, pout, pc = np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 0)), np.zeros(1, np.int64)
    worst = 0.0
    t = 0.0
    for k in range(1, t_out.size):
        t, _, status = ck.yoshida_chunk(
            y, t, float(t_out[k]), 2.0 * dt, max_steps, L, law.law_id, p, bc_code, fL, fR,
            law.alpha, law.beta, k0, k1, ybuf, np.zeros((2, L)), g, stats, bad,
            np.inf, np.nan, zz, zt, zdir, e, e, ei, en, e, ei, en,
            pidx, pt, pout, pc, np.zeros(8),
        )  # fmt: skip
        if status != ck.ST_OK:
            return math.nan
        worst = max(worst, float(np.max(np.abs(y[site_idx] - snaps[k]))))
    return worst / 15.0
