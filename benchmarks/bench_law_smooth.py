"""Cost of smooth laws (one compiled Chebyshev kernel, LAW_CHEB) against the cubic, same run.

    .venv/bin/python -m benchmarks.bench_law_smooth [--reps 3]

A. first use of a new law in a warm process (parse, class check, representation): each preset
   with SymPy's and the parser's caches cleared, best of ``reps`` (CPU and wall); target ≤ 0.3 s.
B. the SAME wave through both kernels: the paper's cubic a = −1, b = 10 as ``CubicLaw``
   (LAW_CUBIC) and the same text as a ``SmoothLaw`` (LAW_CHEB, bypassing the polynomial route):
   discrete superkink V = 5.2, N = 500 (QC guess → Newton) + its Floquet spectrum (structured,
   finite_size=False); the ratio is the cost of the representation (and of the numerical QC
   guess).  Target ≤ 2.
C. each non-polynomial preset: its superkink at the velocity at the same place of its range
   (V = V_lo + 0.6 (c_max − V_lo), the cubic's 5.2 is at 0.58), N = 500, + its spectrum, against
   the cubic's time (different waves: the ratio includes the work of another wave, e.g. another
   step count m from another c_max).  Target ≤ 2.

Times are process CPU time (single-threaded: set OPENBLAS_NUM_THREADS=1), best of ``reps``,
interleaved so load hits every law alike.
"""

from __future__ import annotations

import argparse
import time

from fpucore import CubicLaw, floquet, qc, wave
from fpucore.law import SmoothLaw
from fpucore.law.presets import PRESETS, preset_law

N = 500


def first_use(name: str) -> float:
    from sympy.core.cache import clear_cache

    from fpucore.law import smooth, smooth_parse

    clear_cache()
    smooth.symbolic.cache_clear()
    smooth_parse.parse_smooth.cache_clear()
    t0, c0 = time.perf_counter(), time.process_time()
    preset_law(name)
    return time.process_time() - c0, time.perf_counter() - t0


def wave_and_spectrum(law, V: float):
    def run():
        r = wave.solve_superkink(law, V, branch="lower", N=N)
        s = floquet.spectrum(r, finite_size=False)
        return r, s

    return run


def velocity(law) -> float:
    lo, hi = qc.superkink_velocity_bounds(law, "lower")
    return lo + 0.6 * (hi - lo)


def best(calls: dict, reps: int) -> dict:
    out = {k: fn() for k, fn in calls.items()}  # warm; keep the results for the report
    t = dict.fromkeys(calls, float("inf"))
    for _ in range(reps):
        for k, fn in calls.items():
            t0 = time.process_time()
            fn()
            t[k] = min(t[k], time.process_time() - t0)
    return t, out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args(argv)
    smooth_names = [n for n in PRESETS if n not in ("cubic", "quartic")]
    for n in smooth_names:
        preset_law(n)  # imports SymPy, mpmath: not part of any timing
    print("A. first use of a new law (warm process, caches cleared), target <= 0.3 s")
    for n in smooth_names:
        cpu, wall = min(first_use(n) for _ in range(args.reps))
        print(f"   {n:12s} {cpu:6.3f} s CPU ({wall:6.3f} s wall)")
    cubic = CubicLaw(-1.0, 10.0)
    same = SmoothLaw("a*w**3 + b*w**2 + w", {"a": -1.0, "b": 10.0})
    calls = {"cubic (LAW_CUBIC)": wave_and_spectrum(cubic, 5.2),
             "cubic as SmoothLaw": wave_and_spectrum(same, 5.2)}  # fmt: skip
    for n in smooth_names:
        law = preset_law(n)
        calls[n] = wave_and_spectrum(law, velocity(law))
    t, out = best(calls, args.reps)
    base = t["cubic (LAW_CUBIC)"]
    print(f"\nB/C. superkink N = {N} + Floquet spectrum, CPU s (ratio to the cubic), target <= 2")
    for k, v in t.items():
        r, s = out[k]
        print(f"   {k:20s} V = {r.V:.6g}  {v:7.3f} s  ratio {v / base:5.2f}   wave {r.status} "
              f"residual {r.residual:.1e}, m = {r.m}; spectrum {s.status}, "
              f"max|mu|-1 = {s.max_modulus - 1:.1e}")  # fmt: skip


if __name__ == "__main__":
    main()
