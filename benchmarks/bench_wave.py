"""Benchmarks for discrete traveling waves.  Run:

    .venv/bin/python benchmarks/bench_wave.py            # everything (~1–2 min on 2 cores)
    .venv/bin/python benchmarks/bench_wave.py --quick    # skip the slow scipy baseline
    .venv/bin/python benchmarks/bench_wave.py --bounds   # only 4. (cost of the error bounds)

1. Discrete superkink, V = 5.2, N = 500, QC guess → residual ≤ 1e-11, warm JIT (median of 7).
2. Baseline measured in the same run: the paper's method the straightforward Python way —
   scipy.integrate.solve_ivp(method="DOP853", rtol=atol=1e-12) for the period map, forward
   finite-difference Jacobian (2N extra solves per Newton step), dense numpy solve, same N,
   same equations (eq. nonlin_system), same tolerance.  Also fpucore's own FD-Jacobian option.
3. Work–precision: (a) RK steps m per period vs integrator error (step doubling) and time;
   (b) chain length N vs truncation error (amplitude / E_ren^D against the automatic-N wave)
   and time; (c) Newton tolerance vs achieved residual and time.
4. Cost of the error bounds (profile/amplitude/energy_error) as a share of the solve, same run.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from fpucore import qc, wave
from fpucore.law import CubicLaw
from fpucore.wave import bounds as wb
from fpucore.wave import period_map as pm
from fpucore.wave.attempt import WaveSolve

LAW = CubicLaw(-1.0, 10.0)


def timed(fn, reps=7):
    ts, out = [], None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts), out


def baseline_scipy(V=5.2, N=500, tol=1e-11, max_iter=30):
    """Paper's route with scipy: solve_ivp DOP853 map, forward-FD Jacobian, dense solve."""
    sk = qc.superkink_from_V(LAW, V)
    wl, wr, T = sk.w_minus, sk.w_plus, 1.0 / V
    fl, fr = float(LAW.f(wl)), float(LAW.f(wr))
    n = np.arange(N) - N // 2
    x = np.concatenate([sk.profile(n), -V * sk.dprofile(n)])
    i1 = N // 2 + 1

    def rhs(t, y):
        fw = LAW.f(y[:N])
        ext = np.concatenate([[fl], fw, [fr]])
        return np.concatenate([y[N:], ext[2:] - 2 * ext[1:-1] + ext[:-2]])

    def F(x):
        y = solve_ivp(rhs, (0, T), x, method="DOP853", rtol=1e-12, atol=1e-12).y[:, -1]
        W, WD, w, wd = y[:N], y[N:], x[:N], x[N:]
        return np.concatenate(
            [W[1:] - w[:-1], [wr - w[-1]], WD[1:] - wd[:-1], [W[i1] - LAW.w_star]]
        )

    t0 = time.perf_counter()
    Fx = F(x)
    hist = [np.max(np.abs(Fx))]
    while hist[-1] > tol and len(hist) <= max_iter:
        J = np.empty((2 * N, 2 * N))
        for j in range(2 * N):
            h = 1.49e-8 * max(1.0, abs(x[j]))
            xp = x.copy()
            xp[j] += h
            J[:, j] = (F(xp) - Fx) / h
        x = x + np.linalg.solve(J, -Fx)
        Fx = F(x)
        hist.append(np.max(np.abs(Fx)))
    return time.perf_counter() - t0, hist, x


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip the scipy baseline")
    ap.add_argument("--bounds", action="store_true", help="only section 4 (error-bound cost)")
    args = ap.parse_args(argv)
    print(f"# bench_wave  (python {sys.version.split()[0]}, numpy {np.__version__})")
    t0 = time.perf_counter()
    wave.solve_superkink(LAW, 5.2, N=500)  # JIT load/compile
    print(f"warm-up (JIT load): {time.perf_counter() - t0:.2f} s")

    # 1. headline.  The solver's tol is relative to the strain scale max(1, |w-|, |w+|); the
    # target is an absolute residual <= 1e-11, so ask for 1e-11 / scale.
    sk = qc.superkink_from_V(LAW, 5.2)
    TOL = 1e-11 / max(1.0, abs(sk.w_minus), abs(sk.w_plus))
    t_ours, r = timed(lambda: wave.solve_superkink(LAW, 5.2, N=500, tol=TOL))
    print("\n## 1. discrete superkink V=5.2, N=500, QC guess -> residual <= 1e-11 (median of 7)")
    print(
        f"fpucore exact banded Jacobian : {t_ours * 1e3:8.1f} ms  residual {r.residual:.2e}  "
        f"dropped {r.dropped_residual:.2e}  iterations {r.iterations}  m={r.m} K={r.K}  "
        f"integrator err {r.integrator_error:.1e}"
    )
    t_auto, ra = timed(lambda: wave.solve_superkink(LAW, 5.2, tol=TOL))
    print(
        f"fpucore automatic N={ra.N:<4d}     : {t_auto * 1e3:8.1f} ms  residual {ra.residual:.2e}"
        f"  tail error {ra.tail_error:.1e}"
    )
    t_fd, rf = timed(lambda: wave.solve_superkink(LAW, 5.2, N=500, tol=TOL, jacobian="fd"), 1)
    print(
        f"fpucore FD Jacobian (paper)   : {t_fd * 1e3:8.1f} ms  residual {rf.residual:.2e}  "
        f"iterations {rf.iterations}   -> exact/FD speed-up {t_fd / t_ours:.0f}x"
    )
    print(f"max |w_exact - w_fd| = {np.max(np.abs(r.w - rf.w)):.1e}")

    # 2. baseline
    if not args.quick:
        t_b, hist, xb = baseline_scipy()
        print("\n## 2. baseline: scipy solve_ivp(DOP853) + FD Jacobian + dense solve, N=500")
        print(
            f"scipy baseline: {t_b:8.2f} s  residual history {' '.join(f'{h:.1e}' for h in hist)}"
        )
        print(f"max |w_baseline - w_fpucore| = {np.max(np.abs(xb[:500] - r.w)):.1e}")
        print(f"SPEED-UP fpucore vs scipy baseline: {t_b / t_ours:.0f}x  (target >= 40x)")

    # 3a. work-precision over m
    print("\n## 3a. RK steps per period m vs integrator error (superkink V=5.2, N=500)")
    print("  m   step-doubling err   solve time [ms]   one period map [ms]")
    x = np.empty(1000)
    for m in (4, 6, 8, 10, 12, 16, 24):
        err = pm.step_doubling_error(LAW, r.w, r.wdot, 1 / 5.2, m, r.w_left, r.w_right)
        sp = wave.superkink_spec(LAW, 5.2, "lower")
        S = sp.system(500, m, r.K)
        x0 = sp.qc_guess(500)
        from fpucore.wave.system import newton

        ts, o = timed(lambda S=S, x0=x0: newton(S, x0, 1e-11), 3)
        tp, _ = timed(
            lambda m=m: pm.integrate(LAW, r.w, r.wdot, 1 / 5.2, m, r.w_left, r.w_right), 5
        )
        print(f"{m:3d}   {err:17.2e}   {ts * 1e3:15.1f}   {tp * 1e3:19.3f}")
    _ = x

    # 3b. work-precision over N (near-sonic solitary wave: wide tails)
    print("\n## 3b. chain length N vs truncation error (solitary w+=1, V=4.3; reference: auto N)")
    ref = wave.solve_solitary(LAW, 1.0, 4.3)
    print(
        f"reference automatic N={ref.N}: amplitude {ref.amplitude:.12f}  "
        f"E_ren^D {ref.energy:.10f}  tail error {ref.tail_error:.1e}"
    )
    print("    N   |amp - ref|   |E - ref|    tail error   time [ms]")
    for N in (64, 80, 96, 128, 160, ref.N, 500, 1000):
        try:
            ts, rr = timed(lambda N=N: wave.solve_solitary(LAW, 1.0, 4.3, N=N), 3)
        except Exception as exc:  # N too small for the width: refused
            print(f"{N:5d}   refused: {str(exc)[:70]}")
            continue
        print(
            f"{N:5d}   {abs(rr.amplitude - ref.amplitude):11.2e}   "
            f"{abs(rr.energy - ref.energy):9.2e}   {rr.tail_error:10.2e}   {ts * 1e3:9.1f}"
        )

    # 3c. Newton tolerance
    print("\n## 3c. Newton tolerance vs residual and time (superkink V=5.2, N=500)")
    print("   tol      residual   dropped    iters   time [ms]")
    for tol in (1e-6, 1e-8, 1e-10, 1e-12, 1e-13):
        ts, rr = timed(lambda tol=tol: wave.solve_superkink(LAW, 5.2, N=500, tol=tol), 5)
        print(
            f"{tol:7.0e}   {rr.residual:8.1e}   {rr.dropped_residual:8.1e}   "
            f"{rr.iterations:5d}   {ts * 1e3:9.1f}"
        )

    # 3d. full family sweep (the paper's figures' worth of waves)
    t0 = time.perf_counter()
    from fpucore.wave import solitary_family, superkink_family

    (a, b), (c, d) = qc.solitary_intervals(LAW, 1.0)
    Vs = np.concatenate([np.linspace(a, b, 42)[1:-1], np.linspace(c, d, 42)[1:-1]])
    fam = solitary_family(LAW, 1.0, Vs)
    lo, hi = qc.superkink_velocity_bounds(LAW)
    sk = superkink_family(LAW, np.linspace(lo, hi, 42)[1:-1])
    print(
        f"\n## 3d. families: 80 solitary waves (w+=1) + 40 superkinks, automatic N: "
        f"{time.perf_counter() - t0:.2f} s, all converged: {fam.converged and sk.converged}"
        f", max residual {max(fam.residual.max(), sk.residual.max()):.1e}"
    )

    bounds_cost()


def bounds_cost(reps: int = 7):
    """4. Cost of the error bounds (target <= 20 %): the solve without them
    (``WaveSolve(...).solve()``) against the bounds at its solution (``bounds.error_bounds``),
    same run, median of ``reps``, over waves of the extreme suite."""
    print("\n## 4. error bounds: share of a wave solve (target <= 20 %)")
    print("  wave                         N    solve [ms]  bounds [ms]   ratio")
    cases = [
        ("superkink V=5.2 N=500", wave.superkink_spec(LAW, 5.2, "lower"), 500),
        ("superkink V=5.2 auto N", wave.superkink_spec(LAW, 5.2, "lower"), None),
        ("solitary w+=1 V=5.0", wave.solitary_spec(LAW, 1.0, 5.0), None),
        ("solitary w+=1 near c-", wave.solitary_spec(LAW, 1.0, 5.5 * (1 - 1e-3)), None),
        ("solitary w+=1 near c+", wave.solitary_spec(LAW, 1.0, 3 * 2**0.5 * (1 + 1e-3)), None),
        ("solitary w+=6 V_SK-1e-3", wave.solitary_spec(LAW, 6.0, 7 * 5**0.5 / 3 - 1e-3), None),
    ]
    ratios = []
    for name, sp, N in cases:
        t_s, done = timed(lambda sp=sp, N=N: WaveSolve(sp, N, 1e-12, "exact", 40, 60).solve(),
                          reps)  # fmt: skip
        sol = sp.kind != "superkink"
        t_b, _ = timed(
            lambda d=done, sol=sol: wb.error_bounds(d.system, d.out.x, d.out.factorization, sol),
            reps,
        )
        ratios.append(t_b / t_s)
        print(f"  {name:26s} {done.N:5d}   {t_s * 1e3:9.1f}   {t_b * 1e3:9.2f}   {t_b / t_s:6.1%}")
    print(f"  largest share: {max(ratios):.1%}  (target <= 20 %)")


if __name__ == "__main__":
    if "--bounds" in sys.argv:
        wave.solve_superkink(LAW, 5.2, N=500)  # JIT load
        bounds_cost()
    else:
        main()
