"""Speed of the chain simulator (issue 5) — the paper's Riemann run, a = −1, b = 10,
w_l = 4.6, w_r = 0, L = 3600, t = 300 (Fig. Riemann1), rtol = 1e-10.

    .venv/bin/python -m benchmarks.bench_simulate            # headline + scipy baseline (~1 min)
    .venv/bin/python -m benchmarks.bench_simulate --quick    # skip the scipy baseline
    .venv/bin/python -m benchmarks.bench_simulate --large    # + L = 100 000 run

1. Headline: ``simulate.riemann`` with its default method (Numba RKN12(10) on the second-order
   strain form, error control, observers, tracking), warm JIT, median of 3; wall and process-CPU
   time (the machine is shared: CPU time is the steadier one).  Target ≤ 1 s.
2. Accuracy of every run below: max_n |w_n(300) − w_ref| against a converged reference, the same
   run at rtol 1e-13 (RKN12; checked against DOP853 at rtol 1e-13).  A faster method that is
   also less accurate would not count.
3. Baseline in the same run: ``scipy.integrate.solve_ivp(method="DOP853")`` with a vectorised
   NumPy right-hand side of the same equations (first-order form), same state, same rtol = atol,
   Hairer's RMS norm and controller.  Ratio = baseline / ours (target ≥ 4×).
4. Other methods on the same run: fpucore's DOP853 (the previous default), DOPRI5 (the paper's
   ode45 pair), RKN8(6) and the symplectic Yoshida-4 (dt = 0.02), with energy drift and tracked
   velocities.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from fpucore import simulate
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
WL, WR, L, T, RTOL = 4.6, 0.0, 3600, 300.0, 1e-10


def timed(fn, reps=3):
    walls, cpus, out = [], [], None
    for _ in range(reps):
        w0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return statistics.median(walls), statistics.median(cpus), out


def numpy_rhs(law, L):
    """Vectorised RHS of eq. FPUsystem (end particles held: the default boundary)."""

    def f(t, y):
        w, v = y[:L], y[L : 2 * L + 1]
        g = np.empty(L + 2)
        g[0] = g[-1] = 0.0
        g[1:-1] = law.f(w)
        dv = g[1:] - g[:-1]
        dv[0] = dv[-1] = 0.0
        out = np.empty_like(y)
        out[:L] = v[1:] - v[:-1]
        out[L : 2 * L + 1] = dv
        out[-1] = v[0]
        return out

    return f


def fmt_waves(s):
    return ", ".join(f"{w.kind} {w.velocity:+.6f}" for w in s.waves)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip the scipy baseline")
    ap.add_argument("--large", action="store_true", help="+ an L = 100 000 run")
    args = ap.parse_args(argv)

    for m in simulate.METHODS:  # JIT warm-up (cached after the first session)
        simulate.riemann(LAW, WL, WR, 64, 1.0, method=m)

    print(f"Riemann w_l={WL}, w_r={WR}, L={L}, t_end={T}, rtol=atol={RTOL}")
    wall, cpu, s = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, rtol=RTOL))
    print(
        f"1. numba {s.method} (default; full: observers + tracking): wall {wall:.3f} s, "
        f"cpu {cpu:.3f} s, {s.n_steps} steps ({s.n_rejected} rejected), {s.n_rhs} force "
        f"evaluations, energy drift {s.energy_drift:.2e}"
    )
    print(f"   waves: {fmt_waves(s)}")
    wall_nt, cpu_nt, _ = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, rtol=RTOL, track=False))
    print(f"   without tracking: wall {wall_nt:.3f} s, cpu {cpu_nt:.3f} s")

    t0 = time.perf_counter()
    ref = simulate.riemann(LAW, WL, WR, L, T, rtol=1e-13, track=False).final_w
    ref2 = simulate.riemann(LAW, WL, WR, L, T, rtol=1e-13, track=False, method="dop853").final_w
    print(
        f"2. reference: rkn12 at rtol 1e-13 ({time.perf_counter() - t0:.1f} s with the check); "
        f"dop853 at 1e-13 agrees to {np.max(np.abs(ref - ref2)):.1e}"
    )

    def err(w):
        return float(np.max(np.abs(w - ref)))

    print(f"   error of the headline run: {err(s.final_w):.2e}")

    if not args.quick:
        from scipy.integrate import solve_ivp

        y0 = np.zeros(2 * L + 2)
        y0[: L // 2] = WL
        y0[L // 2 : L] = WR
        w0, c0 = time.perf_counter(), time.process_time()
        sp = solve_ivp(numpy_rhs(LAW, L), (0, T), y0, method="DOP853", rtol=RTOL, atol=RTOL)
        bw, bc = time.perf_counter() - w0, time.process_time() - c0
        print(
            f"3. scipy solve_ivp DOP853 (numpy RHS): wall {bw:.3f} s, cpu {bc:.3f} s, "
            f"{sp.t.size - 1} steps, {sp.nfev} RHS evaluations, error {err(sp.y[:L, -1]):.2e}"
        )
        print(
            f"   speed-up (baseline / ours, full pipeline): wall {bw / wall:.1f}x, "
            f"cpu {bc / cpu:.1f}x"
        )

    print("4. other methods (full pipeline, one run each):")
    for m, kw in (("dop853", {}), ("dopri5", {}), ("rkn8", {}), ("symplectic", {"dt": 0.02})):
        wm, cm, sm = timed(
            lambda m=m, kw=kw: simulate.riemann(LAW, WL, WR, L, T, method=m, **kw), 1
        )
        extra = f", step-doubling estimate {sm.error_estimate:.1e} (incl. its companion run)"
        print(
            f"   {m:10s} wall {wm:.3f} s, cpu {cm:.3f} s, {sm.n_steps} steps, error "
            f"{err(sm.final_w):.2e}, drift {sm.energy_drift:.2e}"
            f"{extra if m == 'symplectic' else ''}; waves: {fmt_waves(sm)}"
        )

    if args.large:
        wl_, cl_, sl = timed(lambda: simulate.riemann(LAW, WL, WR, 100_000, 20.0), 1)
        print(
            f"5. L=100000, t=20: wall {wl_:.2f} s, cpu {cl_:.2f} s, {sl.n_steps} steps, "
            f"drift {sl.energy_drift:.2e}, status {sl.status}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
