"""Riemann data with a velocity jump (an impact): the generalized Riemann problem of eq.
FPUsystem in the variables (w, v) — a jump in the particle velocity as well as in the strain.

    w_n(0) = w_left (n ≤ L/2),  w_right (n > L/2);    v_j(0) = v_left (j < L/2),  0 (j ≥ L/2).

With v_left < 0 the left part pulls away from the right one (a piston pulling the chain; v_left > 0
pushes).  In the degenerate trilinear law E₁ = 0 with both strains in the zero-modulus regime
(the "sonic vacuum": no force below w₁, like a granular chain with gaps) the particles at rest
with different strains never move — only a velocity jump sets the chain in motion.  Then, by the
reflection n → −n, v → −v and a Galilean shift, the run is symmetric about v_left/2 when
w_left = w_right, and each half carries away a periodic train of the explicit compact discrete
solitary waves (:mod:`fpucore.wave.compact`) on the background w_B = w_right: a Whitham shock
whose trains :func:`fpucore.simulate.trains.track_train` measures (docs/guide/trilinear.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from fpucore.errors import ParameterError, require_finite
from fpucore.law import HardeningSofteningLaw
from fpucore.parallel.threads import on_budget
from fpucore.simulate.config import detection_threshold, require_L, split_options
from fpucore.simulate.result import SimulationResult
from fpucore.simulate.scenarios import jump_strains, require_simulable, run_jump

__all__ = ["velocity_jump", "MAX_V_JUMP"]

#: |v_left| bound (strain per unit time; the hard regime's sound speed of the examples is 2)
MAX_V_JUMP = 100.0


@on_budget
def velocity_jump(
    law: HardeningSofteningLaw,
    w_left: float,
    w_right: float,
    v_left: float,
    L: int,
    t_end: float,
    method: str = "rkn12",
    rtol: float = 1e-10,
    boundary: str = "fixed_strain",
    n_snapshots: int = 200,
    max_sites_out: int = 1000,
    probes: Sequence[int] = (),
    n_probe_t: int = 4001,
    threshold: float | None = None,
    **kw: Any,
) -> SimulationResult:
    """Riemann data with a velocity jump (module docstring): strains w_left | w_right as
    :func:`fpucore.simulate.riemann`, the particles j < L/2 moving with velocity ``v_left``, the
    others at rest.  L even.  The end particle 0 moves, so ``boundary`` is "fixed_strain"
    (default: the dead loads f(w_left), f(w_right) hold a prestressed background) or "free".
    Further keywords as for :func:`fpucore.simulate.riemann`.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w); a piecewise-linear law with a zero-modulus regime gives trains of
        compact waves (:func:`fpucore.simulate.track_train`).
    w_left, w_right : float
        Strains left (n ≤ L/2) and right (n > L/2) of the jump (a piecewise-linear law with
        ``guard="bounded"``: any finite strain; else in the convex interval (α, β)).
    v_left : float
        Velocity of the particles 0 … L/2 − 1 (strain per unit time), in [−100, 100], nonzero
        unless w_left ≠ w_right.
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
        End condition: "fixed_strain" or "free" (the end particle moves).
    n_snapshots : int
        Stored field times, in [2, 100000].
    max_sites_out : int
        Sites kept per stored snapshot, in [2, 10⁷].
    probes : sequence of int
        Site numbers in [1, L] whose strain is recorded as a time series (a train is measured
        from at least 4 of them inside it).
    n_probe_t : int
        Times of each probe series, in [2, 10⁷].
    threshold : float or None
        Detection threshold of the wave tracker (strain units), default 2 % of
        max(|w_left − w_right|, |v_left|).
    ``**kw``
        The further keywords of :func:`fpucore.simulate.riemann`.

    Returns
    -------
    SimulationResult
        As :func:`fpucore.simulate.riemann`, with ``details["v_left"]``.

    Raises
    ------
    ParameterError
        As :func:`fpucore.simulate.riemann`; for v_left out of range; for data without any jump.
    """
    law = require_simulable(law)
    opts, run = split_options(kw)
    L = require_L(L)
    if L % 2:
        raise ParameterError("L", L, "an even integer", "the jump sits at n = L/2")
    v = require_finite("v_left", v_left)
    if not -MAX_V_JUMP <= v <= MAX_V_JUMP:
        raise ParameterError("v_left", v, f"[{-MAX_V_JUMP:g}, {MAX_V_JUMP:g}]")
    wl, wr = jump_strains(law, w_left, w_right, opts)
    if v == 0.0 and wl == wr:
        raise ParameterError("v_left", v, "nonzero when w_left == w_right", "the data have no jump")
    if boundary == "fixed_particles" and v != 0.0:
        raise ParameterError(
            "boundary", boundary, "free | fixed_strain", "the end particle 0 moves with v_left"
        )
    thr = detection_threshold(threshold, max(abs(wl - wr), abs(v)))
    out = {
        "n_snapshots": n_snapshots,
        "max_sites_out": max_sites_out,
        "probes": probes,
        "n_probe_t": n_probe_t,
    }
    s = run_jump(
        law, "velocity_jump", (wl, wr), v, L, t_end, boundary, method, rtol, thr, out, opts, run
    )
    s.details["v_left"] = v
    return s
