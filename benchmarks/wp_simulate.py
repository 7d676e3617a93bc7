"""Work–precision of the chain simulator (paper §6: the traveling-wave-seeded runs).

Case: the discrete superkink at V = 5.2 (a = −1, b = 10, automatic N) run for K = 20 periods.
A traveling wave satisfies w_{n+K}(KT) = w_n(0) exactly (eq. period), so the error is measured
against the wave itself — the reference is exact up to the wave solver's own residual (≤ 1e-12).
Errors: the shape error max_n |w_{n+K}(KT) − w_n(0)|, the velocity error of the fitted passage
times, and the relative energy drift.  Compared in the same run: fpucore's adaptive RKN12(10)
(the default) and RKN8(6) on the second-order strain form, DOP853 and DOPRI5 over rtol, its
symplectic (4th-order Yoshida) method over dt, and
``scipy.integrate.solve_ivp(method="DOP853")`` with a vectorised NumPy right-hand side on the
same wave (strain form with the fixed end strains of eq. fixedBCs).
The runs ask for 2 snapshots: the integrators stop exactly at every output time, so dense
output would cap the step at the snapshot spacing and hide the methods' own step control.
Floor: one right-hand-side evaluation over the simulated chain (Numba), times the number of
evaluations the run made (a method cannot beat its own evaluation count).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from fpucore import CubicLaw, simulate, wave
from fpucore.simulate import kernels as ck

from .wp_common import Floor, Row, best_time

ROUTE_SHAPE = "simulation: seeded superkink, shape error after 20 periods"
ROUTE_ENERGY = "simulation: energy drift (same runs)"
K = 20


def _scipy_shape_error(r, rtol: float) -> tuple[float, float]:
    law, N, T = r.law, r.N, 1.0 / r.V
    wl, wr = r.w_left, r.w_right

    def rhs(t, y):
        f = law.f(np.concatenate(([wl], y[:N], [wr])))
        return np.concatenate((y[N:], f[2:] - 2.0 * f[1:-1] + f[:-2]))

    y0 = np.concatenate([r.w, r.wdot])

    def run():
        return solve_ivp(rhs, (0.0, K * T), y0, method="DOP853", rtol=rtol, atol=rtol)

    sol = run()
    wK = sol.y[:N, -1]
    return float(np.max(np.abs(wK[K:] - r.w[: N - K]))), best_time(run, repeat=1, min_time=0.0)


def study(quick: bool = False) -> tuple[list[Row], list[Floor]]:
    law = CubicLaw(-1.0, 10.0)
    r = wave.solve_superkink(law, 5.2, N=128)
    T = 1.0 / r.V
    rows: list[Row] = []
    settings = [("rkn12", "rtol", 10.0**-k) for k in ((6, 9, 12) if quick else (5, 6, 8, 10, 12))]
    settings += [("rkn8", "rtol", 10.0**-k) for k in ((6, 9) if quick else (5, 6, 8, 10, 12))]
    settings += [("dop853", "rtol", 10.0**-k) for k in ((6, 9, 12) if quick else (5, 6, 8, 10, 12))]
    settings += [("dopri5", "rtol", 10.0**-k) for k in ((6, 9) if quick else (5, 6, 8, 10))]
    settings += [("symplectic", "dt", T / n) for n in ((4, 16) if quick else (4, 8, 16, 32, 64))]
    L_run = None
    for method, key, val in settings:
        kw = {"rtol": val} if key == "rtol" else {"dt": val, "estimate_error": False}

        def run(method=method, kw=kw):
            return simulate.seeded(r, t_end=K * T, method=method, track=False, n_snapshots=2, **kw)

        s = run()
        L_run, n_rhs = s.L, s.n_rhs
        sec = best_time(run, repeat=2, min_time=0.0)
        d = s.details
        label = f"{key}={val:.1e}" if key == "rtol" else f"dt=T/{round(T / val)}"
        note = f"velocity err {d.get('velocity_error', float('nan')):.1e}, n_rhs={n_rhs}"
        rows.append(Row(ROUTE_SHAPE, f"fpucore {method}", label, d.get("shape_error", np.nan),
                        sec, note))  # fmt: skip
        rows.append(Row(ROUTE_ENERGY, f"fpucore {method}", label, s.energy_drift, sec))
    for k in (6, 9, 12) if quick else (6, 8, 10, 12):
        err, sec = _scipy_shape_error(r, 10.0**-k)
        rows.append(Row(ROUTE_SHAPE, "scipy solve_ivp DOP853", f"rtol=1e-{k:02d}", err, sec,
                        f"N={r.N}-site chain"))  # fmt: skip
    y = np.zeros(2 * L_run + 2)
    y[:L_run] = r.w_right
    g, out = np.empty(L_run + 2), np.empty_like(y)
    fL, fR = float(law.f(r.w_left)), float(law.f(r.w_right))
    one = best_time(
        lambda: ck.rhs(y, L_run, law.law_id, law.params, ck.BC_LOAD, fL, fR, g, out), min_time=0.05
    )
    floors = [Floor(ROUTE_SHAPE, f"one right-hand side on L = {L_run} sites (Numba)", one)]
    return rows, floors
