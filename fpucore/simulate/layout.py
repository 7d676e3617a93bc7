"""State layout, end conditions and status codes shared by the chain kernels
(:mod:`fpucore.simulate.kernels`, :mod:`fpucore.simulate.rkn`, :mod:`fpucore.simulate.observer`).

First-order state ``y`` (length 2L+2) for a chain of L springs (sites n = 1…L of eq. Riemann_data
are indices 0…L−1) joining particles 0…L (paper eq. FPUsystem, strain–velocity form):

    y[0:L]       strains   w_n                 ẇ_n = v_n − v_{n−1}
    y[L:2L+1]    velocities v_j, j = 0…L        v̇_j = f(w_{j+1}) − f(w_j)
    y[2L+1]      displacement u_0 of particle 0 (only enters the dead-load energy)

The ghost forces f(w_0) = ``fL`` and f(w_{L+1}) = ``fR`` close the chain:
  * ``BC_LOAD`` with fL = fR = 0: stress-free ends (literal free ends);
  * ``BC_LOAD`` with fL = f(w_left), fR = f(w_right): fixed boundary strains (eq. fixedBCs) — a
    constant (dead) load on the end particles;
  * ``BC_FIXED_PARTICLES``: end particles held at rest, v_0 = v_L = 0 (in strain form: zero strain
    gradient, w_0 = w_1, w_{L+1} = w_L).

The RKN stepper uses the second-order form instead (see :mod:`fpucore.simulate.rkn`).

The steppers take their arguments grouped by role in the records below: :class:`Chain` (the
equations), :class:`Control` (error control and guard), :class:`Work` (loop state and counters),
:class:`Observer` (event, crossing and probe arrays) and the tableau records :class:`ErkPair`,
:class:`RknPair`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

BC_LOAD = 0
BC_FIXED_PARTICLES = 1

ST_OK = 0
ST_BUDGET = 2
ST_LEFT_CONVEX = 3
ST_STEP_UNDERFLOW = 4
ST_NONFINITE = 5


# --------------------------------------------------------------------------- records
# Small records grouping the steppers' arguments by role (Numba compiles namedtuples of scalars
# and arrays to plain structs: measured no change of in-jit speed, benchmarks/README.md).


class Chain(NamedTuple):
    """The equations: L springs, the force law (``law_id``, parameters ``p``), the end condition
    ``bc`` (BC_LOAD | BC_FIXED_PARTICLES) and the ghost forces fL = f(w_0), fR = f(w_{L+1})."""

    L: int
    law_id: int
    p: np.ndarray
    bc: int
    fL: float
    fR: float


class Control(NamedTuple):
    """Error control (rtol, atol > 0; unused by the fixed-step stepper) and the guard interval
    (lo, hi): a strain outside it, or non-finite, stops the run with ST_LEFT_CONVEX."""

    rtol: float
    atol: float
    lo: float
    hi: float


class Work(NamedTuple):
    """Loop state and work arrays of a stepper (shapes per stepper in its docstring) and the
    counters: stats (6,) = [steps, rejected, force evaluations, Σ local error, max error norm,
    unused], accumulated over calls; bad (2,) = [value, site] of a strain that left (lo, hi);
    g (L+2,) the forces with their ghosts."""

    K: np.ndarray
    W: np.ndarray
    g: np.ndarray
    stats: np.ndarray
    bad: np.ndarray


class Observer(NamedTuple):
    """Arrays filled by :func:`fpucore.simulate.observer.observe` (per site n = 0…L−1).

    thr : prominence of an extremum; level : the strain whose crossings are timed.
    zz (3, L) : [candidate extremum, running min, running max]; zt (L,) candidate time;
    zdir (L,) int8 zigzag direction (+1 looking for a max, −1 for a min, 0 not started).
    ev_t, ev_w (L, K) float, ev_s (L, K) int8 : confirmed extrema (time, value, sign); ev_n (L,)
    counts.  cr_t (L, KC), cr_s (L, KC) int8 : level crossings (time, direction); cr_n counts.
    probe_idx (P,) sites; probe_t (M,) sorted times; probe_out (P, M); pcount (1,) next probe
    time; c (8,) work (Hermite coefficients)."""

    thr: float
    level: float
    zz: np.ndarray
    zt: np.ndarray
    zdir: np.ndarray
    ev_t: np.ndarray
    ev_w: np.ndarray
    ev_s: np.ndarray
    ev_n: np.ndarray
    cr_t: np.ndarray
    cr_s: np.ndarray
    cr_n: np.ndarray
    probe_idx: np.ndarray
    probe_t: np.ndarray
    probe_out: np.ndarray
    pcount: np.ndarray
    c: np.ndarray


class ErkPair(NamedTuple):
    """An embedded explicit RK pair as the stepper reads it (fpucore.tableaux.embedded): A (s, s),
    B (s,), error weights E5, E3 (s+1,), ``dual`` (Hairer's two-estimator norm of DOP853) and
    err_exp = −1/(q + 1) of the controller."""

    A: np.ndarray
    B: np.ndarray
    E5: np.ndarray
    E3: np.ndarray
    dual: bool
    err_exp: float


class RknPair(NamedTuple):
    """An embedded RKN pair (fpucore.tableaux.rkn): C, A, B = b̄, BP = b′, E = b̄ − b̂,
    EP = b′ − b̂′, ``fsal`` (the last stage is F(q₁)) and err_exp = −1/(q + 1)."""

    C: np.ndarray
    A: np.ndarray
    B: np.ndarray
    BP: np.ndarray
    E: np.ndarray
    EP: np.ndarray
    fsal: bool
    err_exp: float
