"""The stepper table of the chain simulations: one entry per method (``METHODS``), each knowing
how to start (allocate its work arrays, first step) and advance the chain between two stops by
calling its Numba kernel with the grouped records of :mod:`fpucore.simulate.layout`, and what it
costs (work floats per site, force evaluations per step: the memory and work estimates of
:mod:`fpucore.simulate.config`).  A new method is one class and one row of :data:`STEPPERS`.
"""

from __future__ import annotations

import numpy as np

from fpucore.simulate import kernels as ck
from fpucore.simulate import pwl_rkn
from fpucore.simulate import rkn as crk
from fpucore.simulate.layout import Chain, ErkPair, RknPair, Work
from fpucore.tableaux import rkn as rkn_tableaux
from fpucore.tableaux.embedded import get as get_embedded


def initial_step(y: np.ndarray, dy: np.ndarray, rtol: float, atol: float, t_end: float) -> float:
    """Hairer's starting step h = 0.01 ‖y‖/‖ẏ‖ in the scaled RMS norm, capped at 0.1 and t_end."""
    sc = atol + rtol * np.abs(y)
    d0 = np.sqrt(np.mean((y / sc) ** 2))
    d1 = np.sqrt(np.mean((dy / sc) ** 2))
    h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h, 0.1, t_end)


class ErkStepper:
    """Embedded explicit RK pair on the first-order form (:func:`kernels.erk_chunk`).

    Every stepper has: ``name``, ``stages``, ``order`` (of its error estimator; the fixed-step
    method: its order), ``adaptive``; floats_per_site(), evals_per_step();
    start(law, y, chain, cfg) → (state, work, h0) and
    advance(state, y, t, stop, h, step_limit, ctl, chain, work, obs) → (t, h, status), which
    leaves the first-order state in y."""

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

    def start(self, law, y: np.ndarray, chain: Chain, cfg):
        n = y.size
        tab = self.tab
        K = np.zeros((tab.stages + 1, n))
        W = np.zeros((5, n))
        work = Work(K, W, np.zeros(chain.L + 2), np.zeros(6), np.zeros(2))
        ck.rhs(y, chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, K[0])
        h = initial_step(y, K[0], cfg.rtol, cfg.atol, cfg.t_end)
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

    def start(self, law, y: np.ndarray, chain: Chain, cfg):
        L, rk = chain.L, self.rk
        s = rk.stages
        qv = np.zeros(L + 1)
        K = np.zeros((s + 3, L + 1))  # K[0] = F(q), K[s+1] = q̇ (see rkn.rkn_chunk)
        W = np.zeros((7, L + 1))
        work = Work(K, W, np.zeros(L + 2), np.zeros(6), np.zeros(2))
        crk.y_to_rkn(y, L, qv, K[s + 1])
        crk.accel(qv, L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, K[0])
        h = initial_step(
            np.concatenate([qv, K[s + 1]]),
            np.concatenate([K[s + 1], K[0]]),
            cfg.rtol,
            cfg.atol,
            cfg.t_end,
        )
        pair = RknPair(rk.c, rk.A, rk.b, rk.bp, rk.e, rk.ep, rk.fsal, -1.0 / (rk.err_order + 1))
        return (pair, qv), work, h

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        pair, qv = state
        out = crk.rkn_chunk(qv, t, stop, h, limit, pair, ctl, chain, work, obs)
        crk.rkn_to_y(qv, work.K[self.stages + 1], chain.L, y)
        return out


class PwlRknStepper(RknStepper):
    """The RKN pair with frozen regimes and event location at the breakpoints of a
    piecewise-linear law (:func:`pwl_rkn.pwl_rkn_chunk`).  ``locate = False`` (tests only) takes
    the steps whole with the true law at every stage.  ``event_counts(state)`` →
    (crossings located, largest |w − b| at one before it was set, steps taken unlocated)."""

    locate = True

    def floats_per_site(self) -> float:
        return super().floats_per_site() + 2.0  # frozen pieces, their ends, first stage out

    def start(self, law, y: np.ndarray, chain: Chain, cfg):
        (pair, qv), work, h = super().start(law, y, chain, cfg)
        s = self.stages
        nw = 2 * s + 6  # the window of 2R + 1 bonds, R = s + 2, and u_0
        L = chain.L
        ev = (
            np.zeros(L, np.int64),
            np.zeros((2, L)),
            np.zeros(L),
            np.zeros((s + 3, nw)),
            np.zeros((5, nw)),
            np.zeros(3),
            bool(self.locate),
        )
        return (pair, qv, ev), work, h

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        pair, qv, (pc, pb, cf, KW, WW, evs, locate) = state
        out = pwl_rkn.pwl_rkn_chunk(
            qv, t, stop, h, limit, pair, ctl, chain, work, obs, pc, pb, cf, KW, WW, evs, locate
        )
        crk.rkn_to_y(qv, work.K[self.stages + 1], chain.L, y)
        return out

    @staticmethod
    def event_counts(state) -> tuple[int, float, int]:
        evs = state[2][5]
        return int(evs[0]), float(evs[1]), int(evs[2])


class YoshidaStepper:
    """4th-order Yoshida composition of velocity Verlet, fixed step dt
    (:func:`kernels.yoshida_chunk`)."""

    name, stages, order, adaptive = "symplectic", 3, 4, False

    def floats_per_site(self) -> float:
        """y, K (2 rows) and W (3 rows) over 2L+2; twice with the step-doubling companion run."""
        return 2.0 * (1 + 2 + 3)

    def evals_per_step(self) -> float:
        return 3.0

    def start(self, law, y: np.ndarray, chain: Chain, cfg):
        n = y.size
        work = Work(
            np.zeros((2, n)), np.zeros((3, n)), np.zeros(chain.L + 2), np.zeros(6), np.zeros(2)
        )
        ck.rhs(y, chain.L, chain.law_id, chain.p, chain.bc, chain.fL, chain.fR, work.g, work.K[0])
        return None, work, cfg.dt

    def advance(self, state, y, t, stop, h, limit, ctl, chain, work, obs):
        return ck.yoshida_chunk(y, t, stop, h, limit, ctl, chain, work, obs)


STEPPERS: dict[str, ErkStepper | RknStepper | YoshidaStepper] = {
    "rkn12": RknStepper("rkn12"),
    "dop853": ErkStepper("dop853"),
    "dopri5": ErkStepper("dopri5"),
    "rkn8": RknStepper("rkn8"),
    "symplectic": YoshidaStepper(),
}
METHODS = tuple(STEPPERS)
#: the methods of piecewise-linear laws: event location at the breakpoints (simulate.pwl_rkn)
PWL_STEPPERS = {"rkn12": PwlRknStepper("rkn12"), "rkn8": PwlRknStepper("rkn8")}
RKN_METHODS = tuple(m for m, s in STEPPERS.items() if isinstance(s, RknStepper))
# h·ω_max of each adaptive method at rtol = 1e-10 on the paper's Riemann run (ω_max = 2 c_max,
# the top of the chain's linear spectrum): 3458 / 8881 / 50 821 / 15 265 steps over t = 300
# (benchmarks/README.md); the work estimate scales it as rtol^(1/(q+1)).
H_OMEGA_AT_1E10 = {"rkn12": 1.0, "dop853": 0.40, "dopri5": 0.069, "rkn8": 0.23}
