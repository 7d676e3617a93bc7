"""Floquet spectrum benchmarks: cost split, error against run time, family sweeps.

    python -m benchmarks.bench_floquet            # parts A, B, D (a few minutes on an idle core)
    python -m benchmarks.bench_floquet --only D   # just the finite-size cost
    python -m benchmarks.bench_floquet --sweep    # + part C: Figs. floquet_SK / floquet_cubicSW
                                                  #   sweeps at several N (cached, minutes)

A. Full spectrum of the N = 500 superkink at V = 5.2 (a = −1, b = 10), warm JIT: the monodromy
   (base re-integration + 2N tangent columns + shift, Numba) against the LAPACK eigenvalue call
   on the same matrix (the floor), measured in the same run.  Target: monodromy ≤ 25 % of eig.
B. Error against run time over the RK step count m: quartet-symmetry violation, step-doubling
   estimate ‖𝓜_m − 𝓜_2m‖, and the change of max |μ| against a reference m = 72.
D. Cost of the stability decision: one structured spectrum with and without the window of six
   shorter rings in [N/2, N], against one dense spectrum, interleaved, single-threaded BLAS.
   Target: structured + decision ≤ 1.5 × dense.
E. Structured half-size route against dense eigvals on the same 𝓜, interleaved,
   threadpool_limits(1), N = 500: ratio t_structured / t_dense (target ≤ 0.33) and the
   agreement of max|μ| (within the error bar) and of the unstable counts.
C. max |μ| against V for superkinks over their velocity range and solitary waves at w₊ = 1, 6,
   at several N (the spurious oscillatory instabilities shrink as N grows).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import scipy.linalg
from threadpoolctl import threadpool_limits

from fpucore import atlas, qc, wave
from fpucore import floquet as fq
from fpucore.floquet.monodromy import deflate
from fpucore.law import CubicLaw, law_from_expression

LAW = CubicLaw(-1.0, 10.0)


def _best(fn, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def part_a(N: int = 500, V: float = 5.2) -> None:
    print(f"A. cost split, superkink V={V} N={N} (2N = {2 * N} multipliers)")
    fq.spectrum(fq.HomogeneousState(LAW, 1.0, 5.0, 16), method="dense")  # warm every kernel
    r = wave.solve_superkink(LAW, V, N=N)
    m = max(r.m, fq.default_steps(LAW, V))
    mono = fq.monodromy(r, m)
    t_mono = _best(lambda: fq.monodromy(r, m), 5)
    t_eig = _best(lambda: fq.multipliers_of(mono.matrix, N), 3)
    t_full = _best(lambda: fq.spectrum(r, method="dense"), 2)
    ratio = t_mono / t_eig
    print(f"   m = {m}, window K = {mono.K}")
    print(f"   monodromy (Numba)           {t_mono * 1e3:8.1f} ms")
    print(f"   LAPACK eigvals (floor)      {t_eig * 1e3:8.1f} ms")
    print(f"   ratio monodromy / eig       {ratio:8.3f}   target <= 0.25: "
          f"{'PASS' if ratio <= 0.25 else 'FAIL'}")  # fmt: skip
    print(f"   full spectrum() incl. 2m check + analysis {t_full * 1e3:8.1f} ms")


def part_a2(N: int = 500, V: float = 5.8) -> None:
    """The paper's O(1e-8): a plain eig of 𝓜 splits the Jordan block at 1 by round-off."""
    import scipy.linalg

    r = wave.solve_superkink(LAW, V, N=N)
    fr = fq.spectrum(r, method="dense")
    raw = scipy.linalg.eigvals(fq.monodromy(r, fr.m).matrix)
    print(
        f"A2. superkink V={V} N={N}: plain eig of M: max|mu|-1 = {np.abs(raw).max() - 1:.2e}, "
        f"|mu-1| of the 2 nearest = {np.sort(np.abs(raw - 1))[1]:.1e};"
    )
    print(
        f"    deflated: max|mu|-1 = {fr.max_modulus - 1:.2e} (error {fr.error:.1e}), "
        f"cluster split {fr.trivial_split:.1e}"
    )


def part_b(N: int = 500, V: float = 5.2, ms=(5, 7, 9, 12, 18, 27, 36), m_ref: int = 72) -> None:
    print(f"B. error against run time, superkink V={V} N={N}; reference m = {m_ref}")
    r = wave.solve_superkink(LAW, V, N=N)
    ref = fq.spectrum(r, m=m_ref, check=False, method="dense")
    print(f"   reference: max|mu|-1 = {ref.max_modulus - 1:.6e}, symmetry {ref.symmetry_error:.1e}")
    print(f"   {'m':>4} {'mono [ms]':>10} {'eig [ms]':>9} {'symmetry':>9} {'||M_m-M_2m||':>13} "
          f"{'|d max|mu||':>12} {'max|mu|-1':>12}")  # fmt: skip
    for m in ms:
        t_mono = _best(lambda m=m: fq.monodromy(r, m), 3)
        fr = fq.spectrum(r, m=m, method="dense")
        dmax = abs(fr.max_modulus - ref.max_modulus)
        ex = fr.max_modulus - 1
        print(f"   {m:>4} {t_mono * 1e3:>10.1f} {fr.eig_s * 1e3:>9.0f} {fr.symmetry_error:>9.1e} "
              f"{fr.integrator_error:>13.1e} {dmax:>12.1e} {ex:>12.6e}")  # fmt: skip


def part_c(Ns=(200, 300, 500), n_sk: int = 22, n_sw: int = 10) -> None:
    lo, hi = qc.superkink_velocity_bounds(LAW)
    V_sk = np.round(np.linspace(lo + 0.016, hi - 0.01, n_sk), 4)
    print(f"C. sweeps (cached in $FPU_CACHE_DIR or ./.fpu_cache); superkink V in [{lo:.5f}, "
          f"{hi:.5f}]")  # fmt: skip
    env = {}
    for N in Ns:
        sw = atlas.sweep(LAW, "superkink", V_sk, N=N, progress=True)
        env[N] = sw
        print(f"   N={N}: max over V of max|mu|-1 = {np.nanmax(sw.max_modulus - 1):.3e}; "
              f"{sw.elapsed_s:.0f} s ({int(sw.cached.sum())} cached)")  # fmt: skip
    print(f"   {'V':>8} " + " ".join(f"{'N=' + str(N):>11}" for N in Ns))
    for i, V in enumerate(V_sk):
        print(f"   {V:>8.4f} " + " ".join(f"{env[N].max_modulus[i] - 1:>11.3e}" for N in Ns))
    print(
        "   N * (max over V of max|mu|-1): "
        + ", ".join(f"N={N}: {N * np.nanmax(env[N].max_modulus - 1):.3f}" for N in Ns)
    )
    for w_plus, bound in ((1.0, 1.0006), (6.0, 1.001)):
        (a, b), (c, d) = qc.solitary_intervals(LAW, w_plus)
        V = np.concatenate([np.linspace(a + 0.05 * (b - a), b - 0.004, n_sw),
                            np.linspace(c + 0.004, d - 0.05 * (d - c), n_sw)])  # fmt: skip
        sw = atlas.sweep(LAW, "solitary", np.round(V, 5), w_plus=w_plus, N=500, progress=True)
        mx = np.nanmax(sw.max_modulus)
        print(f"   solitary w+={w_plus}: max over V of max|mu| = {mx:.6f} (paper bound {bound}): "
              f"{'PASS' if mx < bound else 'FAIL'}; V_SK = {b:.6f}")  # fmt: skip
        rows = zip(
            sw.V, sw.max_modulus, sw.max_modulus_away_from_1, sw.max_modulus_error, strict=True
        )
        for V_, m_, a_, e_ in rows:
            print(f"     V={V_:.5f}  max|mu|-1={m_ - 1:.3e}  away from 1: {a_ - 1:.3e}  "
                  f"error={e_:.1e}")  # fmt: skip


def part_d(N: int = 500, repeat: int = 3) -> None:
    """Cost of the stability decision (the window of six shorter rings in [N/2, N]): one
    structured spectrum with and without it, and the total against one dense spectrum."""
    print(f"D. decision cost at N={N} (threadpool_limits(1), best of {repeat}, interleaved)")
    cases = [
        ("superkink V=5.2", wave.solve_superkink(LAW, 5.2, N=N)),
        ("solitary w+=6 V=5.0", wave.solve_solitary(LAW, 6.0, 5.0, N=N)),
        ("solitary w+=1 V=5.3", wave.solve_solitary(LAW, 1.0, 5.3, N=N)),
    ]
    with threadpool_limits(1):
        for name, r in cases:
            fr = fq.spectrum(r, method="structured")
            t_d, t_s, t_on = float("inf"), float("inf"), float("inf")
            for _ in range(repeat):  # interleaved: all three see the same machine load
                t_d = min(t_d, _best(lambda r=r: fq.spectrum(r, finite_size=False,
                                                             method="dense"), 1))  # fmt: skip
                t_s = min(t_s, _best(lambda r=r: fq.spectrum(r, finite_size=False,
                                                             method="structured"), 1))  # fmt: skip
                t_on = min(t_on, _best(lambda r=r: fq.spectrum(r, method="structured"), 1))
            total = t_on / t_d
            print(f"   {name:<22} {fr.classification:<12} ({fr.decision.reason}) "
                  f"dense {t_d:6.3f} s  structured {t_s:6.3f} s  + decision {t_on:6.3f} s  "
                  f"extra / structured {(t_on - t_s) / t_s:5.2f}  total / dense {total:5.2f}  "
                  f"target <= 1.5: {'PASS' if total <= 1.5 else 'FAIL'}")  # fmt: skip


def part_e(N: int = 500, repeat: int = 3) -> None:
    """Structured route vs dense eigvals on the same monodromy, single-threaded, interleaved:
    the reversible (quarter-size) route these waves take, and the isotropic Arnoldi route that
    every non-reversible wave takes (forced with reversor=None)."""
    print(f"E. structured vs dense multipliers at N={N} (threadpool_limits(1), best of {repeat})")
    quartic = law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")
    cases = [
        ("superkink V=5.2", wave.solve_superkink(LAW, 5.2, N=N)),
        ("superkink V=5.8", wave.solve_superkink(LAW, 5.8, N=N)),
        ("solitary w+=6 V=5.0", wave.solve_solitary(LAW, 6.0, 5.0, N=N)),
        ("quartic superkink V=5.2", wave.solve_superkink(quartic, 5.2, N=N)),  # not reversible
    ]
    with threadpool_limits(1):
        for name, r in cases:
            mono = fq.monodromy(r, max(r.m, fq.default_steps(r.law, r.V)))
            c = fq.reversor_of(r.law, r.w, r.wdot)
            # the route the wave takes, and the Arnoldi route forced (that of non-reversible waves)
            routes = {"reversible": c, "arnoldi": None} if c is not None else {"arnoldi": None}
            for rv in routes.values():
                fq.structured_multipliers(mono.matrix, N, mono.K, reversor=rv)  # compile
            _, deflated, _ = deflate(mono.matrix, N)  # the reference matrix
            t_d, t_e = float("inf"), float("inf")
            t_s = dict.fromkeys(routes, float("inf"))
            for _ in range(repeat):
                t_d = min(t_d, _best(lambda m=mono: fq.multipliers_of(m.matrix, N), 1))
                for k, rv in routes.items():
                    t_s[k] = min(t_s[k], _best(lambda m=mono, rv=rv: fq.structured_multipliers(
                        m.matrix, N, m.K, reversor=rv), 1))  # fmt: skip
                t_e = min(t_e, _best(lambda b=deflated: scipy.linalg.eigvals(b.copy(order="F"),
                          overwrite_a=True, check_finite=False), 1))  # fmt: skip
            a = fq.spectrum(r, finite_size=False, method="dense")
            b = fq.spectrum(r, finite_size=False, method="structured")
            print(f"   {name:<20} dense {t_d:6.3f} s (eigvals alone {t_e:.3f});  structured route "
                  f"taken: {b.route} (reversor c = {c});  max|mu|-1 {a.max_modulus - 1:.3e} / "
                  f"{b.max_modulus - 1:.3e} (diff {b.max_modulus - a.max_modulus:.1e}, error "
                  f"{max(a.error, b.error):.1e}), unstable {a.n_unstable}/"
                  f"{b.n_unstable}")  # fmt: skip
            for k, rv in routes.items():
                _, _, _, info = fq.structured_multipliers(mono.matrix, N, mono.K, reversor=rv)
                ratio = t_s[k] / t_d
                verdict = "PASS" if ratio <= 0.33 else "FAIL"
                taken = k == b.route
                tail = f"  target <= 0.33: {verdict}" if taken else ""
                print(f"      {info['route'] + ('' if taken else ' (forced)'):<19} {t_s[k]:6.3f} s "
                      f"(reduce {info['reduce_s']:.3f}, Arnoldi {info['arnoldi_s']:.3f}, eig "
                      f"{info['eig_s']:.3f})  ratio {ratio:5.2f} (to eigvals alone "
                      f"{t_s[k] / t_e:.2f}){tail}")  # fmt: skip


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sweep", action="store_true", help="also run the family sweeps (part C)")
    ap.add_argument("--N", type=int, nargs="+", default=[200, 300, 500], help="sweep chain sizes")
    ap.add_argument("--quick", action="store_true", help="smaller N for a smoke run")
    ap.add_argument("--only", choices=("A", "B", "D", "E"), default=None, help="one part only")
    args = ap.parse_args(argv)
    N = 200 if args.quick else 500
    if args.only in ("D", "E"):
        (part_d if args.only == "D" else part_e)(N)
        return 0
    part_a(N)
    part_a2(N)
    part_b(N, ms=(6, 12, 24) if args.quick else (5, 7, 9, 12, 18, 27, 36))
    part_d(N)
    part_e(N)
    if args.sweep:
        part_c(tuple(args.N), n_sk=8 if args.quick else 22, n_sw=4 if args.quick else 10)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
