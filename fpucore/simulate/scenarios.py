"""Direct numerical simulation of the FPU chain (paper §6: eqs. FPUsystem, Riemann_data, GaussIC,
and the runs seeded with computed traveling waves, Figs. stabSK, Riemann1, stabSW, SWdyn).

Drivers :func:`riemann`, :func:`gaussian` (here) and :func:`fpucore.simulate.seeded.seeded`
build the initial state, integrate it (:func:`fpucore.simulate.engine.run_chain` over the Numba
kernels of :mod:`fpucore.simulate.kernels`) and return a
:class:`~fpucore.simulate.result.SimulationResult` carrying the space-time field (decimated),
probe time series, the conserved energy and its drift, the integrator's own error estimate, wall
time, and the waves found by :mod:`fpucore.simulate.tracking`.  The end conditions, methods,
guards and budgets below hold for every driver.

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

from collections.abc import Sequence
from typing import Any

import numpy as np

from fpucore.errors import ParameterError, require_finite
from fpucore.law import HardeningSofteningLaw, require_law
from fpucore.law.scale import require_discrete
from fpucore.parallel.threads import on_budget
from fpucore.simulate.config import (
    configure,
    detection_threshold,
    require_L,
    restoring_interval,
    split_options,
)
from fpucore.simulate.engine import run_chain
from fpucore.simulate.result import SimulationResult

__all__ = ["riemann", "gaussian", "jump_strains", "run_jump"]


def require_simulable(law) -> HardeningSofteningLaw:
    """The law, refused if its f′ has no digits left (:func:`require_discrete`).  A PL law is
    evaluated piece by piece from anchored values (one slope, no cancelling sum), so its
    stiffness contrast — infinite for a zero-modulus regime — costs no digits."""
    law = require_law(law)
    return law if getattr(law, "breakpoints", ()) else require_discrete(law)


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
    **kw: Any,
) -> SimulationResult:
    """Riemann initial data (eq. Riemann_data): w_n(0) = w_left for n ≤ L/2, w_right for
    n > L/2, ẇ_n(0) = 0 (all particles at rest).  L even.  ``threshold`` (strain units) is the
    detection threshold of the wave tracker, default 2 % of |w_left − w_right|.

    Further keywords (all drivers): atol, dt, late_fraction, max_steps, estimate_error, track,
    guard, ``time_budget_s`` (wall seconds; None = no limit: past it the run stops with
    stop_reason "time_budget" and the times it reached), ``memory_budget`` (bytes or "2GiB";
    default FPU_MEMORY_BUDGET or 25 % of RAM, see :mod:`fpucore.budget`) and ``progress``
    (a callable receiving the fraction of t_end done).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_left, w_right : float
        Strains left (n ≤ L/2) and right (n > L/2) of the jump, in the convex interval (α, β)
        (a piecewise-linear law with ``guard="bounded"``: any finite strain).
    L : int
        Number of sites (springs) n = 1 … L, even, in [16, MAX_L].
    t_end : float
        Final time (time units), in (0, 1e7].
    method : str
        Integrator, one of :data:`fpucore.simulate.METHODS` (a piecewise-linear law: the RKN
        pairs only).
    rtol : float
        Relative tolerance, in [1e-14, 1e-2].
    boundary : str
        End condition, one of :data:`fpucore.simulate.BOUNDARIES`.
    n_snapshots : int
        Stored field times, in [2, 100000].
    max_sites_out : int
        Sites kept per stored snapshot, in [2, 10⁷] (every k-th site beyond).
    probes : sequence of int
        Site numbers in [1, L] whose strain is recorded as a time series.
    n_probe_t : int
        Times of each probe series, in [2, 10⁷].
    threshold : float or None
        Detection threshold of the wave tracker, strain units.
    ``**kw``
        The further keywords listed above.

    Returns
    -------
    SimulationResult
        Snapshots of shape (n_snapshots, sites kept), probe series, tracked waves (speeds in
        sites per unit time), conservation and error estimates, stop_reason, run time and
        ``details``.

    Raises
    ------
    ParameterError
        When the law, a strain, ``L``, ``t_end`` or an option is out of range, or the run would
        exceed its memory budget.
    TypeError
        For an unknown keyword.
    """
    law = require_simulable(law)  # before any option is looked at
    opts, run = split_options(kw)
    L = require_L(L)
    if L % 2:
        raise ParameterError("L", L, "an even integer", "the Riemann jump sits at n = L/2")
    wl, wr = jump_strains(law, w_left, w_right, opts)
    thr = detection_threshold(threshold, abs(wl - wr))
    out = {
        "n_snapshots": n_snapshots,
        "max_sites_out": max_sites_out,
        "probes": probes,
        "n_probe_t": n_probe_t,
    }
    return run_jump(
        law, "riemann", (wl, wr), 0.0, L, t_end, boundary, method, rtol, thr, out, opts, run
    )


def jump_strains(law: HardeningSofteningLaw, w_left, w_right, opts: dict) -> tuple[float, float]:
    """The two strains of jump data (:func:`riemann`, :func:`~.impact.velocity_jump`): any
    finite strain for a piecewise-linear law with guard="bounded" (it restores everywhere, e.g.
    in the soundless zero-modulus regime), else inside the convex interval (α, β)."""
    if getattr(law, "breakpoints", ()) and opts.get("guard") == "bounded":
        return require_finite("w_left", w_left), require_finite("w_right", w_right)
    return law.require_convex("w_left", w_left), law.require_convex("w_right", w_right)


def run_jump(
    law: HardeningSofteningLaw,
    kind: str,
    sides: tuple[float, float],
    v_left: float,
    L: int,
    t_end: float,
    boundary: str,
    method: str,
    rtol: float,
    threshold: float,
    out: dict,
    opts: dict,
    run: dict,
) -> SimulationResult:
    """The chain run of jump data: strains ``sides`` = (w_left, w_right) for n ≤ L/2 and
    n > L/2, the particles j < L/2 moving with ``v_left``, the rest at rest; ``out`` the
    stored-output options (n_snapshots, max_sites_out, probes, n_probe_t), ``opts``/``run``
    those of :func:`~.config.split_options`."""
    cfg = configure(law, L, t_end, boundary, method, rtol, **out, **opts)
    wl, wr = sides
    w0 = np.full(L, wr)
    w0[: L // 2] = wl
    v0 = np.zeros(L + 1)
    v0[: L // 2] = v_left
    res, _ = run_chain(
        law, kind, w0, v0, cfg, (wl, wr), origin=L / 2 - 0.5, threshold=threshold, **run
    )
    res["details"].update({"w_left": wl, "w_right": wr, "threshold": threshold})
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
    **kw: Any,
) -> SimulationResult:
    """Gaussian initial data (eq. GaussIC): w_n(0) = w_B + A exp(−(n − L/2)²/2), ẇ_n(0) = 0,
    n = 1…L.  w_B must lie in the convex interval (α, β); w_B + A in it too unless
    ``guard="bounded"`` (the paper's w_B = 1, A = 6 starts at w = 7 > β, and w_B = 6, A = −6
    reaches w ≈ 6.94 > β: both need guard="bounded", see docs/simulation.md).  ``threshold``
    (tracker detection threshold) default 2 % of |A|.  Further keywords as for :func:`riemann`.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_B : float
        Background strain, in the convex interval (α, β).
    A : float
        Amplitude (strain); w_B + A must lie in :func:`restoring_interval`.
    L : int
        Number of sites (springs) n = 1 … L, in [16, MAX_L].
    t_end : float
        Final time (time units), in (0, 1e7].
    method : str
        Integrator, one of :data:`fpucore.simulate.METHODS` (a piecewise-linear law: the RKN
        pairs only).
    rtol : float
        Relative tolerance, in [1e-14, 1e-2].
    boundary : str
        End condition, one of :data:`fpucore.simulate.BOUNDARIES`.
    n_snapshots : int
        Stored field times, in [2, 100000].
    max_sites_out : int
        Sites kept per stored snapshot, in [2, 10⁷] (every k-th site beyond).
    probes : sequence of int
        Site numbers in [1, L] whose strain is recorded as a time series.
    n_probe_t : int
        Times of each probe series, in [2, 10⁷].
    threshold : float or None
        Detection threshold of the wave tracker, strain units.
    ``**kw``
        The further keywords of :func:`riemann`.

    Returns
    -------
    SimulationResult
        Snapshots of shape (n_snapshots, sites kept), probe series, tracked waves (speeds in
        sites per unit time), conservation and error estimates, stop_reason, run time and
        ``details``.

    Raises
    ------
    ParameterError
        When the law, a strain, ``L``, ``t_end`` or an option is out of range, or the run would
        exceed its memory budget.
    TypeError
        For an unknown keyword.
    """
    law = require_simulable(law)  # before any option is looked at
    opts, run = split_options(kw)
    L = require_L(L)
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
    thr = detection_threshold(threshold, abs(A))
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
    res, _ = run_chain(
        law, "gaussian", w0, v0, cfg, (wB, wB), origin=L / 2 - 1.0, threshold=thr, **run
    )
    res["details"].update({"w_B": wB, "A": A, "threshold": thr})
    return SimulationResult(**res)
