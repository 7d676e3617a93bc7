"""Trains of solitary waves in a simulated run: each wave's velocity and crest, the spacing, the
count (the degenerate trilinear law's Whitham shocks, arXiv 2406.06437; data
:func:`fpucore.simulate.impact.velocity_jump`).

The measurement uses the probe series of the run (strain w_n(t) at probe sites, on a uniform
time grid from the integrator's degree-7 Hermite interpolation), so the run must have probes
inside the train, in the direction ``side`` from the origin of the data:

* **crests**: at every probe site, the time extrema of w_n(t) beyond the zero-modulus regime's
  breakpoint b (above w₁ for E₁ = 0: tensile crests; below w₂ for E₃ = 0: compressive), each
  refined by the parabola through the grid's three nearest values; its error is the difference
  from the parabola through every second value (a conservative bound: the vertex error falls as
  the step cubed).  For a traveling wave the crest w_n(t) reaches at every site is its true
  extremum, so the crests of one wave agree from site to site.
* **waves**: the leading wave's passage times fix a coarse ray; every crest at the first site is
  followed along that ray (nearest crest within a quarter of the time period at each site).
  A wave's velocity is the least-squares line through its passage times (n, t_n) (as
  :func:`fpucore.simulate.tracking.fit_passage`), its error the fit's standard error plus the
  spread of V between the first and second halves of its sites; its crest the mean over sites,
  the error the spread plus the vertex bound.
* **spacing** P (sites) = V · Δt, Δt the time between consecutive crests at a site (median over
  sites and waves), error its spread plus P·σ_V/V.  **count** n_waves = the waves between the
  data's origin and the leading wave at the final time at spacing P (the leading wave's ray
  extrapolated to t_final), so it says how long the train has grown.

Reference (tests/simulate/test_simulate_trains.py, fpucore.paper.figures_trilinear_riemann):
each wave against the explicit compact wave of the same V on the background ahead
(:func:`fpucore.wave.compact.compact_wave`: crest b + C), and the velocity against the mass
balance: particles behind a right-going train of spacing P move with v̄ = −V M(V)/P
(M = δ/(1 − a) the mass of one compact wave); the symmetric velocity-jump data fix
v̄ = v_left/2, so :func:`train_velocity` solves V M(V) = P |v_left|/2 in closed form.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError
from fpucore.law import HardeningSofteningLaw
from fpucore.result import Result, status_of
from fpucore.simulate.result import SimulationResult
from fpucore.simulate.tracking import fit_passage
from fpucore.wave.compact import zero_modulus_side


@dataclass(frozen=True)
class TrainResult(Result):
    """A tracked train (module docstring).  Arrays are per wave, leading wave first; velocities
    in sites per unit time (signed like ``side``), crests and amplitudes in strain (amplitude =
    crest − background), spacing in sites, time_period in time units."""

    side: int
    n_waves: int
    velocity: float
    velocity_error: float
    velocities: np.ndarray
    velocity_errors: np.ndarray
    crests: np.ndarray
    crest_errors: np.ndarray
    amplitudes: np.ndarray
    spacing: float
    spacing_error: float
    time_period: float
    background: float
    background_error: float
    lead_position: float
    sites: np.ndarray
    message: str
    elapsed_s: float

    ERROR_FIELDS: ClassVar = ("velocity_error", "spacing_error", "background_error")
    DERIVED: ClassVar = ("n_tracked", "converged", "status")

    @property
    def n_tracked(self) -> int:
        return int(self.velocities.size)

    @property
    def converged(self) -> bool:
        return self.n_tracked >= 2 and bool(np.isfinite(self.velocity))

    @property
    def status(self) -> str:
        return status_of(self.converged)


def train_velocity(
    law: HardeningSofteningLaw, w_B: float, v_left: float, spacing: float = 2.0
) -> float:
    """V of a train of explicit compact waves on w_B with the given spacing behind which the
    particles move with v_left/2 (module docstring): V δ/(1 − πV/(2√(2E))) = P |v_left|/2, i.e.
    V = q/(|δ| + q π/(2√(2E))) with q = P |v_left|/2.

    Parameters
    ----------
    law : PiecewiseLinearLaw or TrilinearLaw
        A law with a zero-modulus regime (E₁ = 0 or E₃ = 0); E is the hard regime's modulus.
    w_B : float
        Background strain ahead of the train, inside the zero-modulus regime.
    v_left : float
        Velocity of the pulled particles of the velocity-jump data (strain per unit time).
    spacing : float
        Sites between consecutive waves (2 in the runs).

    Returns
    -------
    float
        The train's velocity V (sites per unit time).
    """
    side, b, E, _ = zero_modulus_side(law)
    q = 0.5 * spacing * abs(v_left)
    return q / (abs(b - w_B) + q * math.pi / (2.0 * math.sqrt(2.0 * E)))


def _crests(s: np.ndarray, t: np.ndarray, b: float, sgn: int):
    """(times, crests, vertex errors) of the time extrema of sgn·s beyond sgn·b."""
    x = sgn * s
    k = np.nonzero((x[2:-2] > b * sgn) & (x[2:-2] >= x[1:-3]) & (x[2:-2] > x[3:-1]))[0] + 2
    dt = t[1] - t[0]

    def vertex(h):
        a, c0, c = x[k - h], x[k], x[k + h]
        den = a - 2 * c0 + c
        d = np.where(den != 0, 0.5 * (a - c) / np.where(den != 0, den, 1.0), 0.0)
        return t[k] + d * h * dt, c0 - 0.25 * (a - c) * d

    tc, wc = vertex(1)
    _, wc2 = vertex(2)
    return tc, sgn * wc, np.abs(wc - wc2)


def track_train(
    result: SimulationResult, law: HardeningSofteningLaw, side: int = 1, origin: float | None = None
) -> TrainResult:
    """The train moving towards ``side`` (+1: larger n) in ``result``, for a law with a
    zero-modulus regime (module docstring).

    Parameters
    ----------
    result : SimulationResult
        A run (e.g. :func:`fpucore.simulate.velocity_jump`) with at least 4 probe sites inside
        the train.
    law : PiecewiseLinearLaw or TrilinearLaw
        The run's law, with a zero-modulus regime (E₁ = 0 or E₃ = 0).
    side : int
        −1 or 1: the train moving towards smaller or larger n.
    origin : float or None
        Site of the data's jump (default L/2 + 1/2).

    Returns
    -------
    TrainResult
        Per wave (leading first): velocities and crests with errors (sites per unit time,
        strain); the train's velocity, spacing (sites), time period, background, count and the
        leading wave's position; ``elapsed_s``.

    Raises
    ------
    ParameterError
        For ``side`` not ±1, a law without a zero-modulus regime, or too few probes in the train.
    """
    t0 = time.perf_counter()
    if side not in (-1, 1):
        raise ParameterError("side", side, "-1 or 1")
    zside, b, _, _ = zero_modulus_side(law)
    sgn = -zside  # E1 = 0: crests above w1; E3 = 0: below w2
    sites = np.asarray(result.probe_sites, dtype=int)
    if sites.size < 4:
        raise ParameterError(
            "result.probe_sites",
            sites.size,
            ">= 4 probe sites",
            "the train is measured from probe time series",
        )
    order = np.argsort(side * sites)
    sites = sites[order]
    t = np.asarray(result.probe_t)
    cr = [_crests(np.asarray(result.probe_series[i]), t, b, sgn) for i in order]
    origin = result.L / 2 + 0.5 if origin is None else float(origin)
    final = np.asarray(result.final_w)
    nan = float("nan")

    def empty(msg):
        e = np.zeros(0)
        return TrainResult(
            side,
            0,
            nan,
            nan,
            e,
            e,
            e,
            e,
            e,
            nan,
            nan,
            nan,
            nan,
            nan,
            nan,
            sites,
            msg,
            time.perf_counter() - t0,
        )

    firsts = [(n, c[0][0]) for n, c in zip(sites, cr) if c[0].size]
    if len(firsts) < 4:
        return empty("fewer than 4 probe sites saw a crest")
    V0, _, _ = fit_passage([f[0] for f in firsts], [f[1] for f in firsts])
    if not (np.isfinite(V0) and V0 * side > 0):
        return empty("the leading crests do not move towards side")
    gaps = np.concatenate([np.diff(c[0]) for c in cr if c[0].size > 1] or [np.zeros(0)])
    if gaps.size == 0:
        return empty("no two crests passed one probe site")
    tper = float(np.median(gaps))
    n0 = sites[0]
    vel, verr, crest, cerr = [], [], [], []
    for tk in cr[0][0]:
        ns, ts, ws, es = [], [], [], []
        for n, (tc, wc, ec) in zip(sites, cr):
            if tc.size == 0:
                continue
            j = int(np.argmin(np.abs(tc - (tk + (n - n0) / V0))))
            if abs(tc[j] - (tk + (n - n0) / V0)) < 0.25 * tper:
                ns.append(n)
                ts.append(tc[j])
                ws.append(wc[j])
                es.append(ec[j])
        if len(ns) < max(4, sites.size // 2):
            continue
        V, dV, _ = fit_passage(ns, ts)
        h = len(ns) // 2
        halves = [fit_passage(ns[a:c], ts[a:c])[0] for a, c in ((0, h + 1), (h - 1, len(ns)))]
        spread = max((abs(x - V) for x in halves if np.isfinite(x)), default=0.0)
        ws_a = np.asarray(ws)
        vel.append(V)
        verr.append(dV + spread)
        crest.append(float(np.mean(ws_a)))
        cerr.append(float(np.max(np.abs(ws_a - ws_a.mean())) + np.max(es)))
    if len(vel) < 2:
        return empty("fewer than 2 waves followed across the probe sites")
    vel_a, verr_a = np.asarray(vel), np.asarray(verr)
    Vt = float(np.median(vel_a))
    Vt_err = float(np.max(verr_a) + np.max(np.abs(vel_a - Vt)))
    P = abs(Vt) * tper
    P_err = abs(Vt) * float(np.max(np.abs(gaps - tper))) + P * Vt_err / abs(Vt)
    # the leading wave at t_final, extrapolated along its passage times
    lead = sites[0] + vel_a[0] * (result.t_final - cr[0][0][0])
    n_waves = int(math.floor(abs(lead - origin) / P)) + 1 if P > 0 else 0
    ahead = (
        final[int(np.clip(round(lead + side * 3), 1, result.L)) - 1 :: 1]
        if side > 0
        else final[: int(np.clip(round(lead - 3), 1, result.L))]
    )
    bg = float(np.median(ahead)) if ahead.size else nan
    bg_err = float(np.max(np.abs(ahead - bg))) if ahead.size else nan
    crest_a = np.asarray(crest)
    msg = (
        f"{n_waves} waves, V = {Vt:.8g} ± {Vt_err:.2g}, spacing {P:.6g} ± {P_err:.2g} sites, "
        f"crest {np.median(crest_a):.8g}"
    )
    return TrainResult(
        side,
        n_waves,
        Vt,
        Vt_err,
        vel_a,
        verr_a,
        crest_a,
        np.asarray(cerr),
        crest_a - bg,
        P,
        P_err,
        tper,
        bg,
        bg_err,
        float(lead),
        sites,
        msg,
        time.perf_counter() - t0,
    )
