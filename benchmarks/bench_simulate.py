"""Speed of the chain simulator (issue 5) — the paper's Riemann run, a = −1, b = 10,
w_l = 4.6, w_r = 0, L = 3600, t = 300 (Fig. Riemann1), rtol = 1e-10.

    .venv/bin/python -m benchmarks.bench_simulate            # headline + scipy baseline (~1 min)
    .venv/bin/python -m benchmarks.bench_simulate --quick    # skip the scipy baseline
    .venv/bin/python -m benchmarks.bench_simulate --large    # + L = 100 000 run

1. Headline: ``simulate.riemann`` (Numba DOP853, error control, observers, tracking), warm JIT,
   median of 3; wall and process-CPU time (the machine is shared: CPU time is the steadier one).
2. Baseline in the same run: ``scipy.integrate.solve_ivp(method="DOP853")`` with a vectorised
   NumPy right-hand side of the same equations, same state, same rtol = atol, same norm (both use
   Hairer's RMS norm and controller).  Ratio = baseline / ours (target ≥ 4×); the final strains
   of the two runs are compared as a correctness check.
3. Other methods on the same run: DOPRI5 (the paper's ode45 pair) and the symplectic Yoshida-4
   (dt = 0.02), with energy drift and tracked velocities.
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
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--large", action="store_true")
    args = ap.parse_args(argv)

    simulate.riemann(LAW, WL, WR, 64, 1.0)  # JIT warm-up (cached after the first session)
    simulate.riemann(LAW, WL, WR, 64, 1.0, method="symplectic")

    print(f"Riemann w_l={WL}, w_r={WR}, L={L}, t_end={T}, rtol=atol={RTOL}")
    wall, cpu, s = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, rtol=RTOL))
    print(
        f"1. numba dop853 (full: observers + tracking): wall {wall:.3f} s, cpu {cpu:.3f} s, "
        f"{s.n_steps} steps ({s.n_rejected} rejected), energy drift {s.energy_drift:.2e}"
    )
    print(f"   waves: {fmt_waves(s)}")
    wall_nt, cpu_nt, _ = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, rtol=RTOL, track=False))
    print(f"   without tracking: wall {wall_nt:.3f} s, cpu {cpu_nt:.3f} s")

    if not args.quick:
        from scipy.integrate import solve_ivp

        y0 = np.zeros(2 * L + 2)
        y0[: L // 2] = WL
        y0[L // 2 : L] = WR
        w0, c0 = time.perf_counter(), time.process_time()
        ref = solve_ivp(numpy_rhs(LAW, L), (0, T), y0, method="DOP853", rtol=RTOL, atol=RTOL)
        bw, bc = time.perf_counter() - w0, time.process_time() - c0
        nsteps = ref.t.size - 1
        diff = float(np.max(np.abs(ref.y[:L, -1] - s.final_w)))
        print(
            f"2. scipy solve_ivp DOP853 (numpy RHS): wall {bw:.3f} s, cpu {bc:.3f} s, "
            f"{nsteps} steps, {ref.nfev} RHS evaluations; max |w_scipy - w_ours| = {diff:.1e}"
        )
        print(
            f"   speed-up (baseline / ours, full pipeline): wall {bw / wall:.1f}x, "
            f"cpu {bc / cpu:.1f}x"
        )

    wall5, cpu5, s5 = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, method="dopri5"), 1)
    print(
        f"3. dopri5: wall {wall5:.3f} s, cpu {cpu5:.3f} s, {s5.n_steps} steps, "
        f"drift {s5.energy_drift:.2e}; waves: {fmt_waves(s5)}"
    )
    ws, cs, sy = timed(lambda: simulate.riemann(LAW, WL, WR, L, T, method="symplectic", dt=0.02), 1)
    print(
        f"   symplectic dt=0.02: wall {ws:.3f} s, cpu {cs:.3f} s (incl. step-doubling "
        f"estimate run), drift {sy.energy_drift:.2e}, error estimate {sy.error_estimate:.2e}; "
        f"waves: {fmt_waves(sy)}"
    )

    if args.large:
        wl_, cl_, sl = timed(lambda: simulate.riemann(LAW, WL, WR, 100_000, 20.0), 1)
        print(
            f"4. L=100000, t=20: wall {wl_:.2f} s, cpu {cl_:.2f} s, {sl.n_steps} steps, "
            f"drift {sl.energy_drift:.2e}, status {sl.status}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
