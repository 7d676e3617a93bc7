"""Work–precision of the Floquet monodromy (paper §6, eqs. linear, linear_map).

State: the discrete superkink at V = 5.2 (a = −1, b = 10) on N = 200 sites (N = 120 with
``quick``), where quartets leave the unit circle.  Metric: |max |μ| − max |μ|_ref|, the reference
being fpucore with m = 72 RK steps per period (its quartet-symmetry error is in the note).
Compared in the same run: fpucore's fixed-step DOP853 tangent columns (Numba, local windows,
periodic wrap) over m, and ``scipy.integrate.solve_ivp(method="DOP853")`` on the base orbit plus
the full (2N)² variational matrix over rtol.  Time: building 𝓜 (the eigenvalue call is the same
for both and is the floor).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from fpucore import floquet as fq
from fpucore import wave
from fpucore.law import CubicLaw

from .wp_common import Floor, Row, best_time

ROUTE = "Floquet"


def _scipy_monodromy(r, rtol: float) -> np.ndarray:
    law, N, V = r.law, r.N, r.V

    def rhs(t, y):
        w, wd = y[:N], y[N : 2 * N]
        Y = y[2 * N :].reshape(2 * N, 2 * N)
        f = law.f(np.concatenate(([r.w_left], w, [r.w_right])))
        G = law.df(w)[:, None] * Y[:N]
        dY = np.empty_like(Y)
        dY[:N] = Y[N:]
        dY[N:] = np.roll(G, -1, 0) - 2.0 * G + np.roll(G, 1, 0)  # ring: periodic BC of §6
        return np.concatenate((wd, f[2:] - 2.0 * f[1:-1] + f[:-2], dY.ravel()))

    y0 = np.concatenate((r.w, r.wdot, np.eye(2 * N).ravel()))
    sol = solve_ivp(rhs, (0.0, 1.0 / V), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-2)
    psi = sol.y[2 * N :, -1].reshape(2 * N, 2 * N)
    return np.vstack([np.roll(psi[:N], -1, axis=0), np.roll(psi[N:], -1, axis=0)])


def _max_mod(M: np.ndarray, N: int) -> tuple[float, float]:
    rest, sums, _ = fq.multipliers_of(M, N)
    mu = np.concatenate([sums, rest])
    return float(np.abs(mu).max()), fq.quartet_symmetry_error(mu)[0]


def study(quick: bool = False) -> tuple[list[Row], list[Floor]]:
    law = CubicLaw(-1.0, 10.0)
    N = 120 if quick else 200
    r = wave.solve_superkink(law, 5.2, N=N)
    ref = fq.spectrum(r, m=72, check=False, method="dense")
    rows: list[Row] = []
    for m in (5, 9, 18) if quick else (5, 7, 9, 12, 18, 27):
        M = fq.monodromy(r, m).matrix
        mx, sym = _max_mod(M, N)
        sec = best_time(lambda m=m: fq.monodromy(r, m))
        rows.append(Row(ROUTE, "fpucore DOP853 tangent columns", f"m={m}",
                        abs(mx - ref.max_modulus), sec,
                        f"symmetry {sym:.1e}; ref symmetry {ref.symmetry_error:.1e}"))  # fmt: skip
    for k in (6, 9) if quick else (6, 8, 10, 12):
        rtol = 10.0**-k
        M = _scipy_monodromy(r, rtol)
        mx, sym = _max_mod(M, N)
        sec = best_time(lambda rtol=rtol: _scipy_monodromy(r, rtol), repeat=1)
        rows.append(Row(ROUTE, "scipy solve_ivp DOP853 (dense variational)", f"rtol=1e-{k}",
                        abs(mx - ref.max_modulus), sec, f"symmetry {sym:.1e}"))  # fmt: skip
    M = fq.monodromy(r, 18).matrix
    floor = best_time(lambda: fq.multipliers_of(M, N), repeat=3)
    return rows, [Floor(ROUTE, f"LAPACK eigvals of the {2 * N - 2}² deflated monodromy", floor)]
