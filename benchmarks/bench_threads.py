"""The thread budget: two Floquet spectra at once.

    python -m benchmarks.bench_threads [--repeat 3] [--N 500]

Each spectrum is ``floquet.spectrum(wave.solve_superkink(CubicLaw(), 5.2, N=500),
method="dense")`` (its cost is the LAPACK ``dgeev`` of the deflated ~1000 × 1000 matrix), run
in a separate process, warm (one spectrum first, timed afterwards).  Two settings in the same run:

* **policy**  — every process calls ``fpucore.parallel.apply_thread_policy(1)`` (what the
  Executor's workers, the atlas and the server do): one BLAS/OpenMP/Numba thread each;
* **default** — the libraries' defaults (OPENBLAS_NUM_THREADS / OMP_NUM_THREADS removed from the
  environment): one thread per core in each process.

For each: one process alone, then two processes started together (they wait for a common start
signal).  Target: with the policy, each of the two concurrent spectra within 1.3× of one alone
(the alone baseline of the policy is one thread, of the default all cores).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

from fpucore import floquet, wave
from fpucore.law import CubicLaw
from fpucore.parallel import apply_thread_policy, cores

THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")


def child(mode: str, N: int, repeat: int) -> None:
    """Run in a subprocess: warm up, print READY, wait for GO on stdin, time ``repeat`` spectra."""
    if mode == "policy":
        apply_thread_policy(1)
    r = wave.solve_superkink(CubicLaw(), 5.2, N=N)
    floquet.spectrum(r, method="dense")  # warm (JIT, LAPACK workspace)
    print("READY", flush=True)
    sys.stdin.readline()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        floquet.spectrum(r, method="dense")
        times.append(time.perf_counter() - t0)
    print(" ".join(f"{t:.4f}" for t in times), flush=True)


def run(mode: str, n_proc: int, N: int, repeat: int) -> list[float]:
    """Median spectrum time of each of ``n_proc`` processes started together."""
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARS}
    cmd = [sys.executable, "-m", "benchmarks.bench_threads", "--child", mode, "--N", str(N),
           "--repeat", str(repeat)]  # fmt: skip
    procs = [subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                              env=env) for _ in range(n_proc)]  # fmt: skip
    for p in procs:
        assert p.stdout.readline().strip() == "READY"
    for p in procs:
        p.stdin.write("GO\n")
        p.stdin.flush()
    out = []
    for p in procs:
        ts = sorted(float(x) for x in p.stdout.readline().split())
        p.wait()
        out.append(ts[len(ts) // 2])
    return out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--child", choices=("policy", "default"))
    ap.add_argument("--N", type=int, default=500)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    if a.child:
        child(a.child, a.N, a.repeat)
        return
    print(f"two concurrent Floquet spectra, superkink V=5.2 N={a.N}, {cores()} cores, "
          f"median of {a.repeat} per process")  # fmt: skip
    pairs = {}
    for mode in ("policy", "default"):
        alone = run(mode, 1, a.N, a.repeat)[0]
        pair = pairs[mode] = run(mode, 2, a.N, a.repeat)
        ratios = [t / alone for t in pair]
        ok = "OK" if max(ratios) <= 1.3 else "over 1.3x"
        print(f"  {mode:8s} alone {alone:.3f} s   two at once {pair[0]:.3f} / {pair[1]:.3f} s   "
              f"ratio {ratios[0]:.2f} / {ratios[1]:.2f}  ({ok})")  # fmt: skip
    gain = max(pairs["default"]) / max(pairs["policy"])
    print(f"  two at once: default threads / policy = {gain:.1f}x (the oversubscription loss)")


if __name__ == "__main__":
    main()
