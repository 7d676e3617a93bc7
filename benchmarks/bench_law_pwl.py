"""Cost of piecewise-linear laws (event-located period map, tangent and monodromy) against the
cubic, same run.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.bench_law_pwl [--reps 3]

A trilinear superkink at the same place of its velocity range as the cubic's V = 5.2 (a = −1,
b = 10), N = 500, QC guess → Newton, + its Floquet spectrum (structured,
finite_size=False), against the cubic's; process CPU time, best of ``reps``, interleaved so that
load hits both alike.  Different waves: the ratio includes another step count m (from another
c_max/V) and the crossings located (each costs an Illinois search of a few RK sub-steps on the
whole chain).  Target ≤ 3.
"""

from __future__ import annotations

import argparse
import time

from fpucore import CubicLaw, floquet, qc, wave
from fpucore.law import TrilinearLaw

N = 500
CUBIC, V_CUBIC = CubicLaw(-1.0, 10.0), 5.2  # the headline wave of bench_wave / bench_floquet


def velocity(law) -> float:
    """V at the place of the cubic's V = 5.2 in its own superkink range."""
    lo, hi = qc.superkink_velocity_bounds(CUBIC, "lower")
    place = (V_CUBIC - lo) / (hi - lo)
    lo, hi = qc.superkink_velocity_bounds(law, "lower")
    return lo + place * (hi - lo)


def wave_and_spectrum(law, V: float):
    def run():
        r = wave.solve_superkink(law, V, branch="lower", N=N)
        s = floquet.spectrum(r, finite_size=False)
        return r, s

    return run


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args(argv)
    laws = {
        "cubic a=-1 b=10": CUBIC,
        "trilinear E1=1": TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2),
        "trilinear E1=0": TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2),
    }
    calls = {k: wave_and_spectrum(law, V_CUBIC if law is CUBIC else velocity(law))
             for k, law in laws.items()}  # fmt: skip
    out = {k: fn() for k, fn in calls.items()}  # warm (JIT) and keep the results
    t = dict.fromkeys(calls, float("inf"))
    for _ in range(args.reps):
        for k, fn in calls.items():
            c0 = time.process_time()
            fn()
            t[k] = min(t[k], time.process_time() - c0)
    base = t["cubic a=-1 b=10"]
    print(f"superkink N = {N} + Floquet spectrum, CPU s (ratio to the cubic), target <= 3")
    for k, v in t.items():
        r, s = out[k]
        print(f"   {k:16s} V = {r.V:.6g}  {v:7.3f} s  ratio {v / base:5.2f}   wave {r.status} "
              f"residual {r.residual:.1e}, profile error {r.profile_error:.1e}, m = {r.m}; "
              f"spectrum {s.status} ({s.classification}), max|mu|-1 = {s.max_modulus - 1:.1e} "
              f"+- {s.error:.1e}")  # fmt: skip


if __name__ == "__main__":
    main()
