"""The atlas on the execution layer (issue 15, issue 17 "Sweeps in parallel"), ratios in one run.

    python -m benchmarks.bench_atlas            # all parts (~5 min on 2 loaded cores)
    python -m benchmarks.bench_atlas --quick    # A-C only at smaller sizes

A. Throughput: points/s of a superkink atlas at N = 300 with Floquet (8 velocities, chunks of 2)
   on 1 and 2 process workers (pool started and warmed first: the steady state).
B. Per-point overhead of the layer — scheduling, serialization, the Zarr write — as the run's
   wall time minus the points' own compute time (``elapsed_s`` measured in the worker), per
   point, against a point's cost; process pool and Dask LocalCluster, 1 worker each.  Target ≤ 5%.
C. Continuation: one solitary-wave line (w₊ = 1, 16 velocities, N = 300, waves only, inline)
   with continuation against cold starts from the QC guess.
D. ``floquet.sweep`` of 12 superkink velocities at N = 500 on 2 worker processes (pool start
   included, no cache) against 12 sequential spectra in this process, one thread (the
   baseline of the sweep before: a loop in one process).  Target ≤ 0.6×.  Also the CPU seconds of
   both sides (workers' from /proc) and the per-task CPU/wall, to tell load from serialisation.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from fpucore import atlas, floquet, wave
from fpucore.atlas import solve_chunk
from fpucore.law import CubicLaw
from fpucore.parallel import Executor, apply_thread_policy

LAW = CubicLaw(-1.0, 10.0)


def warm(ex: Executor, N: int) -> None:
    """Load the JIT cache in every worker (one small point each), so timings are steady."""
    task = {"law": LAW, "kind": "superkink", "row": "lower", "V": [5.5], "N": N,
            "tol": 1e-12, "floquet": True, "m": None, "continuation": True}  # fmt: skip
    jobs = [ex.submit(solve_chunk, task) for _ in range(max(1, ex.workers))]
    for j in jobs:
        j.result(timeout=600)


def sk_run(ex, V, N, chunk):
    return atlas.run(LAW, "superkink", rows=["lower"], V=V, N=N, floquet=True, chunk=chunk,
                     executor=ex)  # fmt: skip


def part_a(N: int, nV: int) -> None:
    V = np.linspace(5.0, 5.7, nV)
    print(f"A. throughput, superkink atlas N={N} with Floquet, {nV} velocities, chunks of 2")
    rates = {}
    for w in (1, 2):
        with Executor("process", workers=w) as ex:
            warm(ex, N)
            r = sk_run(ex, V, N, 2)
        rates[w] = r.points_per_s
        print(f"   {w} worker(s): {r.elapsed_s:6.2f} s, {r.points_per_s:.3f} points/s "
              f"({r.n_ok} ok)")  # fmt: skip
    print(f"   speed-up 2 vs 1 worker: {rates[2] / rates[1]:.2f}x")


def part_b(N: int, nV: int) -> None:
    V = np.linspace(5.0, 5.7, nV)
    print(f"B. per-point overhead of the layer, N={N} with Floquet, {nV} points, 1 worker")
    for backend in ("process", "dask"):
        with Executor(backend, workers=1) as ex:
            warm(ex, N)
            t0 = time.perf_counter()
            r = atlas.run(LAW, "superkink", rows=["lower"], V=V, N=N, floquet=True, chunk=1,
                          executor=ex, out=None)  # fmt: skip
            wall = time.perf_counter() - t0
        compute = float(np.nansum(r.dataset.elapsed_s.values))
        per_point = compute / nV
        over = (wall - compute) / nV
        print(f"   {backend:7s}: point {per_point:.3f} s, overhead {over * 1e3:.1f} ms/point "
              f"= {100 * over / per_point:.1f}% (target <= 5%)")  # fmt: skip


def part_c(N: int, nV: int) -> None:
    V = np.linspace(4.35, 5.3, nV)
    print(f"C. continuation along a line, solitary w+=1, {nV} velocities, N={N}, waves only")
    out = {}
    for cont in (True, False):
        r = atlas.run(LAW, "solitary", rows=[1.0], V=V, N=N, continuation=cont,
                      backend="inline")  # fmt: skip
        out[cont] = float(np.nansum(r.dataset.wave_elapsed_s.values))
        its = int(np.sum(r.dataset.iterations.values))
        print(f"   {'continued' if cont else 'cold     '}: {out[cont]:.2f} s, {its} Newton "
              f"iterations, {r.n_ok} ok")  # fmt: skip
    print(f"   continuation / cold = {out[True] / out[False]:.2f}")


def cpu_seconds(pids: list[int]) -> float:
    """User + system CPU seconds of live processes (Linux /proc)."""
    tick = os.sysconf("SC_CLK_TCK")
    total = 0.0
    for pid in pids:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        total += (int(fields[11]) + int(fields[12])) / tick
    return total


def part_d(N: int = 500, nV: int = 12) -> None:
    """Wall ratio (pool start included) and, to judge it independently of the machine's load, the
    CPU seconds of each side: if the workers' CPU is about the sequential CPU and their CPU/wall
    is far below 1, they waited for a core (load), not for each other (serialisation)."""
    V = np.linspace(4.9, 5.8, nV)
    print(f"D. {nV}-velocity max|mu| sweep at N={N}: 2 workers vs sequential, same run "
          f"(load average {os.getloadavg()[0]:.1f})")  # fmt: skip
    apply_thread_policy(1)
    c0, t0 = time.process_time(), time.perf_counter()
    seq = [floquet.spectrum(wave.solve_superkink(LAW, v, N=N)).max_modulus for v in V]
    t_seq, c_seq = time.perf_counter() - t0, time.process_time() - c0
    t0 = time.perf_counter()
    ex = Executor(workers=2)
    t_pool = time.perf_counter() - t0
    c1 = time.process_time()
    s = floquet.sweep(LAW, "superkink", V, N=N, use_cache=False, executor=ex)
    t_par = time.perf_counter() - t0
    c_parent = time.process_time() - c1
    c_workers = cpu_seconds(ex.impl.pids())
    t1 = time.perf_counter()  # the same sweep again on the running, warm pool (the dashboard's)
    floquet.sweep(LAW, "superkink", V, N=N, use_cache=False, executor=ex)
    t_warm = time.perf_counter() - t1
    ex.shutdown()
    diff = float(np.max(np.abs(np.array(seq) - s.max_modulus) - s.error))
    task_wall = sum(r["elapsed_s"] for r in s.rows)
    ideal = t_pool + c_workers / 2  # two free cores, perfectly balanced
    print(
        f"   sequential {t_seq:.1f} s (CPU {c_seq:.1f} s, CPU/wall {c_seq / t_seq:.2f}); "
        f"sweep on 2 workers {t_par:.1f} s incl. pool start {t_pool:.1f} s -> wall ratio "
        f"{t_par / t_seq:.2f} (target <= 0.6); max(|d max|mu|| - error bar) = {diff:.1e}"
    )
    print(
        f"   workers' CPU {c_workers:.1f} s (sequential {c_seq:.1f} s), parent CPU "
        f"{c_parent:.2f} s; tasks' wall {task_wall:.1f} s -> per-task CPU/wall "
        f"{c_workers / task_wall:.2f}; load-free estimate (pool start + workers' CPU / 2) / "
        f"sequential CPU = {ideal / c_seq:.2f}; load average {os.getloadavg()[0]:.1f}"
    )
    print(f"   again on the running pool (started, JIT loaded: the dashboard's case) {t_warm:.1f} s"
          f" -> ratio {t_warm / t_seq:.2f}")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args(argv)
    apply_thread_policy(1)
    if a.quick:
        part_a(200, 6), part_b(200, 4), part_c(200, 8)
        return
    part_a(300, 8)
    part_b(300, 6)
    part_c(300, 16)
    part_d()


if __name__ == "__main__":
    main()
