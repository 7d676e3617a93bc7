"""A run seeded with a computed discrete traveling wave (paper §6, Figs. stabSK, stabSW): the
wave placed on a longer chain, integrated, and checked against itself — its velocity from the
passage times at the sites it crosses and its shape after whole periods.  End conditions,
methods, guards and budgets as for every driver (:mod:`fpucore.simulate.scenarios`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.parallel.threads import on_budget
from fpucore.simulate.config import (
    MAX_L,
    configure,
    detection_threshold,
    require_L,
    require_positive,
    split_options,
)
from fpucore.simulate.engine import run_chain
from fpucore.simulate.result import SimulationResult

if TYPE_CHECKING:
    from fpucore.wave.driver import WaveResult

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
    t_end by the output schedule (:func:`fpucore.simulate.schedule.output_schedule`).

    Parameters
    ----------
    t_end : float
        Final time (time units), >= 0 and at most 1e15 periods.
    T : float
        Period (time units), > 0.

    Returns
    -------
    tuple of (int, float)
        K whole periods and t_K = K·T (time units).

    Raises
    ------
    ParameterError
        When ``T`` is not a finite positive number, or ``t_end`` is negative, non-finite or
        more than 1e15 periods.
    """
    t_end, T = require_finite("t_end", t_end), require_finite("T", T)
    if not T > 0.0:
        raise ParameterError("T", T, "a period T > 0", "there are no whole periods of length 0")
    if not t_end >= 0.0:
        raise ParameterError("t_end", t_end, "t_end >= 0")
    if not t_end / T <= 1e15:  # K must be a count, not an overflow
        raise ParameterError("t_end", t_end, f"at most 1e15 periods T = {T:.10g}")
    K = int(math.floor(t_end / T + 1e-9))
    if K >= 1 and K * T > t_end * (1.0 + 1e-12):
        K -= 1  # t_end more than rounding short of K periods: the last whole one is K − 1
    return K, K * T


@on_budget
def seeded(
    r: WaveResult,
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
    **kw: Any,
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
    :func:`whole_periods`).  Further keywords as for :func:`fpucore.simulate.scenarios.riemann`.

    Parameters
    ----------
    r : WaveResult
        A converged traveling wave: N sites in [8, MAX_L], ``w`` and ``wdot`` of shape (N,),
        V > 0 in sites per unit time.
    L : int or None
        Number of sites of the chain, in [16, MAX_L] and at least N + ⌈V t_end⌉ + 2·margin;
        None: that minimum.
    t_end : float or None
        Final time (time units), in (0, 1e7]; None: 50 periods T = 1/V.
    method : str
        Integrator, one of :data:`fpucore.simulate.METHODS`.
    rtol : float
        Relative tolerance, in [1e-14, 1e-2].
    boundary : str
        End condition, one of :data:`fpucore.simulate.BOUNDARIES`.
    n_snapshots : int
        Stored field times, in [2, 100000].
    max_sites_out : int
        Sites kept per stored snapshot, in [2, 10⁷].
    probes : sequence of int
        Site numbers in [1, L] whose strain is recorded as a time series.
    n_probe_t : int
        Times of each probe series, in [2, 10⁷].
    threshold : float or None
        Detection threshold of the wave tracker, strain units.
    margin : int
        Sites between the chain's left end and the wave's first site, in [10, MAX_L].
    ``**kw``
        Further keywords of :func:`fpucore.simulate.scenarios.riemann`.

    Returns
    -------
    SimulationResult
        The run, with the check against the wave in ``details`` (velocities in sites per unit
        time, phase errors in time units, shape_error in strain units).

    Raises
    ------
    ParameterError
        When ``r`` is not a converged finite wave with V > 0, or ``L``, ``t_end``, ``margin``
        or an option is out of range.
    TypeError
        For an unknown keyword.
    """
    opts, run = split_options(kw)
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
            "t_end",
            t_end,
            f"(0, {(MAX_L - N - 2 * margin) / V:.6g}]",
            f"the wave's path V·t_end needs a chain longer than L = {MAX_L}",
        )
    L = L_min if L is None else require_L(L)
    if L < L_min:
        raise ParameterError(
            "L", L, f">= {L_min}", "the chain must hold the wave and its path plus margins"
        )
    L = require_L(L)
    K_per, t_K = whole_periods(t_end, T)
    extra = (t_K,) if K_per >= 1 else ()
    thr_scale = abs(float(getattr(r, "amplitude", 0.0)) or abs(r.w_left - r.w_right) or 1.0)
    if r.kind == "superkink":
        thr_scale = abs(r.w_left - r.w_right)
    thr = detection_threshold(threshold, thr_scale)
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
        n_extra=len(extra),
        **opts,
    )
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
        law,
        "seeded",
        w0,
        v0,
        cfg,
        (wl, wr),
        origin=float(i0 - 1),
        threshold=thr,
        extra_times=extra,
        level=level,
        **run,
    )
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
