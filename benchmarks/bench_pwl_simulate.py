"""Speed of the chain simulator on a piecewise-linear law with event location at its breakpoints
(fpucore.simulate.pwl_rkn): the Riemann run of the degenerate zero-modulus trilinear law at the
paper's size (L = 3600, t = 300, rtol 1e-10, as Fig. Riemann1), against the cubic's Riemann run of
the same size (benchmarks/bench_simulate.py's headline) in the same process.

    .venv/bin/python -m benchmarks.bench_pwl_simulate            # both runs, warm JIT
    .venv/bin/python -m benchmarks.bench_pwl_simulate --t-end 60 # shorter
    .venv/bin/python -m benchmarks.bench_pwl_simulate --cli      # + the PL run from `fpu simulate`

Printed per run: wall and process-CPU time, steps, breakpoint crossings located, steps per
crossing, energy drift and the tracked waves; then the ratio PL / cubic of CPU time and of steps.
Every crossing costs about two whole-chain RKN steps (the trial that saw it and the sub-step up
to it; its Illinois iterations run on a window of 2R + 1 bonds), so the ratio measures how many
more crossings than smooth-dynamics steps the degenerate run has, not a slower kernel.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

from fpucore import simulate
from fpucore.law import CubicLaw, law_from_piecewise_text

PWL_TEXT = "trilinear(w1=0.5, w2=1.5, E1=0, E2=4, E3=0.2)"
PWL_DATA = (1.0, 0.0)  # w_left in the hard regime, w_right in the soundless regime E1 = 0
CUBIC, CUBIC_DATA = CubicLaw(-1.0, 10.0), (4.6, 0.0)
L, RTOL = 3600, 1e-10


def run(law, data, t_end, **kw):
    w0, c0 = time.perf_counter(), time.process_time()
    r = simulate.riemann(law, *data, L, t_end, rtol=RTOL, time_budget_s=3600, **kw)
    return time.perf_counter() - w0, time.process_time() - c0, r


def show(name, wall, cpu, r):
    n_cross = r.details.get("breakpoint_crossings", 0)
    per = f"{r.n_steps / n_cross:.2f} steps/crossing" if n_cross else ""
    print(f"{name}: {r.stop_reason}, wall {wall:.2f} s, CPU {cpu:.2f} s, {r.n_steps} steps, "
          f"{n_cross} crossings {per}, energy drift {r.energy_drift:.2e}")  # fmt: skip
    for w in r.waves:
        print(f"    {w.kind:10s} V = {w.velocity:+.6f} ± {w.velocity_error:.1e}, "
              f"amplitude {w.amplitude:+.4f}, background {w.background:.4f}")  # fmt: skip


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=300.0)
    ap.add_argument("--cli", action="store_true")
    a = ap.parse_args(argv)
    law = law_from_piecewise_text(PWL_TEXT)
    print(f"load average {os.getloadavg()[0]:.1f}; L = {L}, t = {a.t_end:g}, rtol = {RTOL:g}")
    run(CUBIC, CUBIC_DATA, 1.0)  # warm both JITs
    run(law, PWL_DATA, 1.0, guard="bounded")
    cub = run(CUBIC, CUBIC_DATA, a.t_end)
    show("cubic a=-1 b=10, w = 4.6 | 0", *cub)
    pwl = run(law, PWL_DATA, a.t_end, guard="bounded")
    show(f"{PWL_TEXT}, w = 1 | 0", *pwl)
    steps = pwl[2].n_steps / cub[2].n_steps
    print(f"ratio PL / cubic: CPU {pwl[1] / cub[1]:.1f}x, steps {steps:.1f}x")
    if a.cli:
        cmd = [sys.executable, "-m", "fpucore", "simulate", "riemann", "--law", PWL_TEXT,
               "--w-left", str(PWL_DATA[0]), "--w-right", str(PWL_DATA[1]), "--L", str(L),
               "--t-end", str(a.t_end), "--guard", "bounded", "--time-budget", "3600",
               "--progress", "never", "--json"]  # fmt: skip
        w0 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        d = json.loads(out)
        print(f"CLI: wall {time.perf_counter() - w0:.2f} s, elapsed_s {d['elapsed_s']:.2f}, "
              f"{d['stop_reason']}, waves {[w['kind'] for w in d['waves']]}")  # fmt: skip


if __name__ == "__main__":
    main()
