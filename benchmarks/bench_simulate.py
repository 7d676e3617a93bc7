"""Speed of the chain simulator — the paper's Riemann run, a = −1, b = 10,
w_l = 4.6, w_r = 0, L = 3600, t = 300 (Fig. Riemann1), rtol = 1e-10.

    .venv/bin/python -m benchmarks.bench_simulate            # headline + scipy baseline (~1 min)
    .venv/bin/python -m benchmarks.bench_simulate --quick    # skip the scipy baseline
    .venv/bin/python -m benchmarks.bench_simulate --large    # + L = 100 000 run
    .venv/bin/python -m benchmarks.bench_simulate --against /tmp/old   # + speed against a tree
    .venv/bin/python -m benchmarks.bench_simulate --cli      # + the run from the `fpu` command

1. Headline: ``simulate.riemann`` with its default method (Numba RKN12(10) on the second-order
   strain form, error control, observers, tracking), warm JIT, median of 3; wall and process-CPU
   time (the machine is shared: CPU time is the steadier one).  Target ≤ 1 s.
2. Accuracy of every run below: max_n |w_n(300) − w_ref| against a converged reference, the same
   run at rtol 1e-13 (RKN12; checked against DOP853 at rtol 1e-13).  A faster method that is
   also less accurate would not count.
3. Baseline in the same run: ``scipy.integrate.solve_ivp(method="DOP853")`` with a vectorised
   NumPy right-hand side of the same equations (first-order form), same state, same rtol = atol,
   Hairer's RMS norm and controller.  Ratio = baseline / ours (target ≥ 4×).
4. Other methods on the same run: fpucore's DOP853, DOPRI5 (the paper's
   ode45 pair), RKN8(6) and the symplectic Yoshida-4 (dt = 0.02), with energy drift and tracked
   velocities.
6. ``--against DIR``: the headline run of every method timed in fresh processes importing
   fpucore from this tree and from DIR, interleaved (A B A B …, so that the machine's load
   falls on both alike); ratio of the median CPU times (this tree / DIR) and a check that the
   final strains are bitwise identical.  Used to show that a refactor of the kernels kept their
   in-jit speed.
7. ``--cli``: ``fpu simulate riemann`` (the headline run) in fresh processes: its reported
   ``elapsed_s`` (the first simulation of a process) and the ratio of the scipy baseline to it
   (target ≥ 4×).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

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


ROOT = Path(__file__).resolve().parents[1]
# run in a fresh process with PYTHONPATH=<tree>: one method, warm JIT, median CPU time of `reps`
_CHILD = """
import hashlib, json, statistics, sys, time
from fpucore import simulate
from fpucore.law import CubicLaw
law = CubicLaw(-1.0, 10.0)
method, reps, L, T = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
kw = {"dt": 0.02, "estimate_error": False} if method == "symplectic" else {"rtol": 1e-10}
simulate.riemann(law, 4.6, 0.0, 64, 1.0, method=method, **kw)
cpu = []
for _ in range(reps):
    c0 = time.process_time()
    s = simulate.riemann(law, 4.6, 0.0, L, T, method=method, **kw)
    cpu.append(time.process_time() - c0)
digest = hashlib.sha1(s.final_w.tobytes()).hexdigest()
print(json.dumps({"cpu": statistics.median(cpu), "steps": s.n_steps, "digest": digest}))
"""


def child_run(tree: Path, method: str, reps: int, L_: int, T_: float) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree))
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, method, str(reps), str(L_), str(T_)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def against(other: Path, rounds: int = 3) -> None:
    """Section 6: this tree against ``other``, interleaved fresh processes."""
    print(f"6. this tree ({ROOT}) against {other}: CPU s, median of {rounds} interleaved processes")
    for m in simulate.METHODS:
        T_ = T if m != "dopri5" else 60.0  # dopri5's 50 821 steps over t = 300 take ~5 s
        mine, theirs, digests = [], [], set()
        for _ in range(rounds):
            for tree, acc in ((ROOT, mine), (other, theirs)):
                r = child_run(tree, m, 1, L, T_)
                acc.append(r["cpu"])
                digests.add(r["digest"])
        a, b = statistics.median(mine), statistics.median(theirs)
        same = "bitwise identical" if len(digests) == 1 else "DIFFERENT final strains"
        print(f"   {m:10s} t={T_:g}: this {a:.3f} s, other {b:.3f} s, ratio {a / b:.3f}; {same}")


def fmt_waves(s):
    return ", ".join(f"{w.kind} {w.velocity:+.6f}" for w in s.waves)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip the scipy baseline")
    ap.add_argument("--large", action="store_true", help="+ an L = 100 000 run")
    ap.add_argument("--against", type=Path, default=None, help="another source tree to compare")
    ap.add_argument("--only-against", action="store_true", help="run section 6 only")
    ap.add_argument("--cli", action="store_true", help="+ section 7: the run from the CLI")
    args = ap.parse_args(argv)
    if args.against is not None and args.only_against:
        against(args.against)
        return 0

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
    if args.against is not None:
        against(args.against)
    if args.cli:
        cli_runs(None if args.quick else bw)
    return 0


def cli_runs(baseline_s: float | None, rounds: int = 3) -> None:
    """Section 7: ``fpu simulate riemann`` in fresh processes: the ``elapsed_s`` it reports (the
    first simulation of a process, kernels loaded from Numba's cache) and the process's wall
    time, medians; ratio of the scipy baseline (section 3) to ``elapsed_s``."""
    cmd = [sys.executable, "-m", "fpucore", "simulate", "riemann", "--w-left", str(WL),
           "--w-right", str(WR), "--L", str(L), "--t-end", str(T), "--json"]  # fmt: skip
    elapsed, walls = [], []
    for _ in range(rounds):
        w0 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, check=True)
        walls.append(time.perf_counter() - w0)
        elapsed.append(json.loads(out.stdout.strip().splitlines()[-1])["elapsed_s"])
    e, w = statistics.median(elapsed), statistics.median(walls)
    ratio = f"; scipy DOP853 / CLI elapsed_s = {baseline_s / e:.1f}x" if baseline_s else ""
    print(f"7. CLI (fresh process, median of {rounds}): elapsed_s {e:.3f} s, process wall "
          f"{w:.3f} s{ratio}")  # fmt: skip


if __name__ == "__main__":
    raise SystemExit(main())
