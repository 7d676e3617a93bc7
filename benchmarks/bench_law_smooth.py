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

D. refusal of a law outside the class (three or five inflections, w* < 0, no softening, a
   domain error, too steep to represent), warm process, SymPy's caches cleared, best of
   ``reps``; target ≤ 50 ms (the class is decided on float64 scans before any 30-digit root or
   representation: tests/law/test_law_smooth.py::test_class_refusals_do_no_extended_precision_work).
E. the build of a stiff law that needs the full 4096 panels (exponential d = 1e-4, tanh m = 0.05,
   s = 0.01).

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
    ap.add_argument("--only-law", action="store_true", help="only A, D and E (no waves)")
    args = ap.parse_args(argv)
    smooth_names = [n for n in PRESETS if n not in ("cubic", "quartic")]
    for n in smooth_names:
        preset_law(n)  # imports SymPy, mpmath: not part of any timing
    print("A. first use of a new law (warm process, caches cleared), target <= 0.3 s")
    for n in smooth_names:
        cpu, wall = min(first_use(n) for _ in range(args.reps))
        print(f"   {n:12s} {cpu:6.3f} s CPU ({wall:6.3f} s wall)")
    refusals_and_stiff(args.reps)
    if args.only_law:
        return
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


REFUSALS = [
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3", {"c": 0.1, "k": 1, "m": 1, "s": 0.01}),
    ("w + w**2/(1 + exp(-(w - 1)/e)) - w**3/100", {"e": 0.05}),
    ("w - w**2*exp(w)", None),
    ("log(1 + w)", None),
    ("w + w**2 - w**3 + log(w + 0.5) - log(0.5)", None),
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3", {"c": 0.1, "k": 1, "m": 0.01, "s": 0.002}),
]
STIFF = [
    ("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 1e-4}),
    ("w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3", {"c": 0.1, "k": 1, "m": 0.05, "s": 0.01}),
]


def timed_law(text, consts, clear: bool) -> tuple[float, float, str]:
    """(CPU s, wall s, outcome) of law_from_expression (SymPy's caches cleared if ``clear``)."""
    from sympy.core.cache import clear_cache

    from fpucore.errors import ParameterError
    from fpucore.law import law_from_expression, smooth, smooth_parse

    if clear:
        clear_cache()
        smooth.symbolic.cache_clear()
        smooth_parse.parse_smooth.cache_clear()
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        law = law_from_expression(text, consts)
        out = f"{law.representation_error.panels} panels"
    except ParameterError as exc:
        out = "refused: ..." + str(exc)[-70:]
    return time.process_time() - c0, time.perf_counter() - t0, out


def refusals_and_stiff(reps: int) -> None:
    print("\nD. refusal by the class check (warm process, caches cleared), target <= 0.05 s")
    for text, consts in REFUSALS:
        cpu, wall, out = min(timed_law(text, consts, True) for _ in range(reps))
        print(f"   {cpu * 1e3:6.1f} ms CPU ({wall * 1e3:6.1f} ms wall)  {text[:44]:44s} {consts}")
        print(f"          {out}")
    print("\nE. build of a stiff law (4096 panels), warm process")
    for text, consts in STIFF:
        cpu, wall, out = min(timed_law(text, consts, False) for _ in range(reps))
        print(f"   {cpu:6.3f} s CPU ({wall:6.3f} s wall)  {text[:44]:44s} {consts}: {out}")


if __name__ == "__main__":
    main()
