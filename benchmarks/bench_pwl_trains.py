"""Work–precision of the degenerate trilinear law's trains of compact solitary waves: the
velocity-jump run (fpucore.simulate.impact.velocity_jump; E1 = 0, w_B = 0.2, v_left = −0.2) at
several tolerances, each train tracked (fpucore.simulate.trains.track_train) and measured against
its closed forms — the velocity V = q/(δ + qπ/(2√(2E₂))), q = |v_left| (mass balance at spacing
2), and every wave's crest w₁ + δ/(ω(1 − a)) at its measured V (fpucore.wave.compact).

    .venv/bin/python -m benchmarks.bench_pwl_trains              # L = 400, t = 120
    .venv/bin/python -m benchmarks.bench_pwl_trains --L 1000 --t-end 400

Printed per rtol: wall time, steps, crossings, waves, |V − closed form| with the tracker's
error bar, the worst |crest − explicit| with its bar, the energy drift.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from fpucore.law import TrilinearLaw
from fpucore.simulate import track_train, train_velocity, velocity_jump
from fpucore.wave.compact import compact_wave

LAW = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
W_B, V_LEFT = 0.2, -0.2
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--L", type=int, default=400)
    ap.add_argument("--t-end", type=float, default=120.0)
    a = ap.parse_args(argv)
    probes = list(range(a.L // 2 + 4, a.L // 2 + 16))
    V_ref = train_velocity(LAW, W_B, V_LEFT)
    print(f"load average {os.getloadavg()[0]:.1f}; L = {a.L}, t = {a.t_end:g}, "
          f"V (closed form) = {V_ref:.12g}")  # fmt: skip
    velocity_jump(LAW, W_B, W_B, V_LEFT, 64, 1.0, guard="bounded", probes=[40])  # warm the JIT
    for rtol in RTOLS:
        t0 = time.perf_counter()
        r = velocity_jump(LAW, W_B, W_B, V_LEFT, a.L, a.t_end, rtol=rtol, guard="bounded",
                          probes=probes, n_probe_t=int(a.t_end * 100) + 1)  # fmt: skip
        wall = time.perf_counter() - t0
        tr = track_train(r, LAW, side=1)
        crest = [abs(compact_wave(LAW, float(V), W_B).b + compact_wave(LAW, float(V), W_B).C - c)
                 for V, c in zip(tr.velocities, tr.crests)]  # fmt: skip
        print(f"rtol {rtol:.0e}: wall {wall:6.2f} s, {r.n_steps} steps, "
              f"{r.details.get('breakpoint_crossings', 0)} crossings, {tr.n_waves} waves, "
              f"|V − V_ref| {abs(tr.velocity - V_ref):.1e} (bar {tr.velocity_error:.1e}), "
              f"crest {max(crest, default=np.nan):.1e} (bar {np.max(tr.crest_errors):.1e}), "
              f"energy drift {r.energy_drift:.1e}")  # fmt: skip


if __name__ == "__main__":
    main()
