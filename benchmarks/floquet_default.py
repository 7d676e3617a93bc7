"""Which Floquet method is the default: the full ``spectrum`` call (finite-size test included,
as every entry point makes it) by the dense and the structured route on the same waves.

    python -m benchmarks.floquet_default          # ~3 min on an idle core

For each wave: max|μ| and the error bar of both routes, their difference against the larger
bar (agreement), the classification and unstable count of both, and the wall time of each
call (threadpool_limits(1), interleaved, best of ``--repeat``, JIT warm).  The cases: the
paper's cubic superkinks across their velocity range and solitary waves on both sides of
V_SK (reversible: the quarter-size route), a non-reversible wave (the quartic law's superkink:
the half-size Arnoldi route) and a small homogeneous state.
"""

from __future__ import annotations

import argparse
import time

from threadpoolctl import threadpool_limits

from fpucore import floquet as fq
from fpucore import wave
from fpucore.law import CubicLaw, law_from_expression

LAW = CubicLaw(-1.0, 10.0)
QUARTIC = law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")


def cases(N: int) -> list:
    return [
        ("superkink V=4.85", lambda: wave.solve_superkink(LAW, 4.85, N=N)),
        ("superkink V=5.5", lambda: wave.solve_superkink(LAW, 5.5, N=N)),
        ("superkink V=5.8", lambda: wave.solve_superkink(LAW, 5.8, N=N)),
        ("solitary w+=1 V=5.0", lambda: wave.solve_solitary(LAW, 1.0, 5.0, N=N)),
        ("solitary w+=6 V=4.6", lambda: wave.solve_solitary(LAW, 6.0, 4.6, N=N)),
        ("solitary w+=6 V=5.3", lambda: wave.solve_solitary(LAW, 6.0, 5.3, N=N)),
        ("quartic superkink V=5.2", lambda: wave.solve_superkink(QUARTIC, 5.2, N=N)),
        ("homogeneous w=1 V=5 N=16", lambda: fq.HomogeneousState(LAW, 1.0, 5.0, 16)),
    ]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--N", type=int, default=500)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 16), method="dense")  # warm the kernels
    fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 16), method="structured")
    print(f"N = {args.N}, threadpool_limits(1), best of {args.repeat}")
    print(f"{'wave':<26} {'route':<10} {'dense err':>9} {'struct err':>10} {'|diff|':>8} "
          f"{'agree':>5} {'class d/s':<26} {'t dense':>7} {'t struct':>8} "
          f"{'ratio':>5}")  # fmt: skip
    ratios, agree_all = [], True
    with threadpool_limits(1):
        for name, make in cases(args.N):
            r = make()
            best = {"dense": float("inf"), "structured": float("inf")}
            res = {}
            for _ in range(args.repeat):
                for method in best:
                    t0 = time.perf_counter()
                    res[method] = fq.spectrum(r, method=method)
                    best[method] = min(best[method], time.perf_counter() - t0)
            d, s = res["dense"], res["structured"]
            diff = abs(d.max_modulus - s.max_modulus)
            agree = (diff <= max(d.error, s.error) and d.classification == s.classification
                     and d.n_unstable == s.n_unstable)  # fmt: skip
            agree_all &= agree
            ratio = best["structured"] / best["dense"]
            ratios.append(ratio)
            cls = f"{d.classification}/{s.classification}"
            print(f"{name:<26} {s.route:<10} {d.error:9.1e} {s.error:10.1e} {diff:8.1e} "
                  f"{'yes' if agree else 'NO':>5} {cls:<26} {best['dense']:7.3f} "
                  f"{best['structured']:8.3f} {ratio:5.2f}")  # fmt: skip
    print(f"all agree within the larger error bar: {agree_all}; time ratio structured/dense "
          f"{min(ratios):.2f} to {max(ratios):.2f}")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
