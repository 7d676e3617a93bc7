"""Slow path of tests/extreme/test_extreme_wave.py: the paper's flat-top solitary waves
(Fig. SW_sim, a = −1, b = 10, w₊ = 6) at V = 5.21749194749 (|V − V_SK| ≈ 9.5e-12, compressive) and
V = 5.2174919476 (≈ 1.0e-10 above, tensile), plus |V − V_SK| = 1e-6, 1e-8 for context.  Run:

    .venv/bin/python -m benchmarks.bench_extreme_wave [--budget SECONDS]

Prints, per velocity: converged, N, m, residual, dropped residual, step-doubling error, tail
error, amplitude, route and wall time — or the solver's reason for not converging.

Expected (continuation in plateau mass, fpucore.wave.plateau): all five converge; the two paper
velocities in ~1–2 s each with the front-position error bar in the message (measured ±0.04 and
±0.02 sites); before that route the last three did not converge (≈ 48 s for the five).
"""

from __future__ import annotations

import argparse

from fpucore import qc, wave
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=float, default=120.0, help="time budget per wave [s]")
    args = ap.parse_args(argv)
    v_sk = qc.sound_speeds(LAW, 6.0)[1]
    wave.warm(LAW)
    for V in (v_sk - 1e-6, v_sk + 1e-6, v_sk - 1e-8, 5.21749194749, 5.2174919476):
        r = wave.solve_solitary(LAW, 6.0, V, time_budget_s=args.budget)
        print(
            f"V={V!r} (V-V_SK={V - v_sk:+.2e}) {r.kind}: converged={r.converged} N={r.N} "
            f"m={r.m} residual={r.residual:.1e} dropped={r.dropped_residual:.1e} "
            f"step-doubling={r.integrator_error:.1e} tail={r.tail_error:.1e} "
            f"amplitude={r.amplitude:.6f} time={r.elapsed_s:.1f}s\n    {r.message}",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
