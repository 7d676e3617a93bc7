"""Order of the period map across breakpoints (piecewise-linear laws): the error of one period
of the fixed-step DOP853 map against the EXACT compact wave of a zero-modulus trilinear law
(fpucore.wave.compact: w_{n+1}(T) = w_n(0)), for m = 4 … 256 steps, and the log–log slope.
A smooth law gives slope ≈ 8; without event location at breakpoints the slope drops (the
solution's third derivative jumps where a site crosses a breakpoint).  Run:

    python benchmarks/pwl_period_order.py
"""

import numpy as np

from fpucore.law import TrilinearLaw
from fpucore.wave.compact import compact_wave
from fpucore.wave.period_map import integrate


def errors(V=0.5, wB=0.2, phase=0.3137, ms=(4, 8, 16, 32, 64, 128, 256)):
    law = TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2)
    w = compact_wave(law, V, wB)
    n = np.arange(-8, 8)
    w0, wd0 = w.lattice(n, phase)
    w1, wd1 = w.lattice(n - 1, phase)
    out = []
    for m in ms:
        r = integrate(law, w0, wd0, 1.0 / V, m, w_left=wB, w_right=wB)
        out.append(max(np.max(np.abs(r.w - w1)), np.max(np.abs(r.wd - wd1)) / V))
    return np.array(ms), np.array(out)


if __name__ == "__main__":
    ms, err = errors()
    for m, e in zip(ms, err):
        print(f"m = {m:4d}   error = {e:.3e}")
    ok = err > 1e-14
    slope = np.polyfit(np.log(ms[ok]), np.log(err[ok]), 1)[0]
    print(f"log-log slope = {slope:.2f} (DOP853 on a smooth law: 8)")
