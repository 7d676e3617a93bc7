"""Work–precision of the one-period map Φ_T (paper eq. nonlin_map without the shift).

State: the QC superkink at V = 5.2 (a = −1, b = 10) sampled on N = 1000 sites.  Reference: DOP853
with m = 256 fixed steps (error of that reference, by step doubling, is printed in the note).
Compared in the same run: fpucore's fixed-step DOP853 and RK4 (Numba) over m, and
``scipy.integrate.solve_ivp(method="DOP853")`` with a vectorised NumPy right-hand side over rtol.
Floor: one DOP853 step (12 right-hand-side evaluations) of the Numba kernel.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from fpucore import CubicLaw, qc
from fpucore.tableaux.rk import DOP853, RK4
from fpucore.wave import period_map as pm

from .wp_common import Floor, Row, best_time

ROUTE = "period map"


def _state(N=1000, V=5.2):
    law = CubicLaw(-1.0, 10.0)
    sk = qc.superkink_from_V(law, V)
    n = np.arange(-N // 2, N // 2, dtype=float)
    return law, sk, sk.profile(n), -V * sk.dprofile(n)


def scipy_rhs_factory(law, wl, wr):
    def rhs(t, y):
        N = y.size // 2
        w, wd = y[:N], y[N:]
        f = law.f(np.concatenate(([wl], w, [wr])))
        return np.concatenate((wd, f[2:] - 2.0 * f[1:-1] + f[:-2]))

    return rhs


def study(quick: bool = False) -> tuple[list[Row], list[Floor]]:
    law, sk, w0, wd0 = _state()
    T = 1.0 / sk.V
    wl, wr = sk.w_minus, sk.w_plus
    ref = pm.integrate(law, w0, wd0, T, 256, wl, wr)
    ref_err = pm.step_doubling_error(law, w0, wd0, T, 256, wl, wr)
    xref = np.concatenate([ref.w, ref.wd])
    rows: list[Row] = []
    for tab, ms in ((DOP853, (2, 3, 4, 6, 8, 12, 16, 24)), (RK4, (4, 8, 16, 32, 64, 128))):
        for m in ms[:4] if quick else ms:
            r = pm.integrate(law, w0, wd0, T, m, wl, wr, tableau=tab)
            err = float(np.max(np.abs(np.concatenate([r.w, r.wd]) - xref)))
            sec = best_time(
                lambda m=m, tab=tab: pm.integrate(law, w0, wd0, T, m, wl, wr, tableau=tab)
            )
            rows.append(Row(ROUTE, f"fpucore {tab.name} fixed m", f"m={m}", err, sec,
                            f"ref err {ref_err:.1e}"))  # fmt: skip
    rhs = scipy_rhs_factory(law, wl, wr)
    y0 = np.concatenate([w0, wd0])
    for k in (4, 6, 8, 10, 12) if not quick else (6, 10):
        rtol = 10.0**-k

        def run(rtol=rtol):
            return solve_ivp(rhs, (0, T), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-2)

        sol = run()
        err = float(np.max(np.abs(sol.y[:, -1] - xref)))
        rows.append(Row(ROUTE, "scipy solve_ivp DOP853", f"rtol=1e-{k}", err, best_time(run),
                        f"nfev={sol.nfev}"))  # fmt: skip
    floor = best_time(lambda: pm.integrate(law, w0, wd0, T / 16, 1, wl, wr), min_time=0.1)
    return rows, [Floor(ROUTE, "one DOP853 step on N = 1000 sites (Numba)", floor)]
