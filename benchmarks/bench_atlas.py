"""The atlas on the execution layer and sweeps in parallel, ratios in one run.

    python -m benchmarks.bench_atlas            # all parts (~5 min on 2 loaded cores)
    python -m benchmarks.bench_atlas --quick    # A-C only at smaller sizes

A. Throughput: points/s of a superkink atlas at N = 300 with Floquet (8 velocities, chunks of 2)
   on 1 and 2 process workers (pool started and warmed first: the steady state).
B. Per-point overhead of the layer — scheduling, serialization, the Zarr write — as the run's
   wall time minus the points' own compute time (``elapsed_s`` measured in the worker), per
   point, against a point's cost; process pool and Dask LocalCluster, 1 worker each.  Target ≤ 5%.
C. Continuation: one solitary-wave line (w₊ = 1, 16 velocities, N = 300, waves only, inline)
   with continuation against cold starts from the QC guess.
D. ``atlas.sweep`` of 12 superkink velocities at N = 500 on 2 cores as ``fpu floquet sweep``
   runs it — a fresh process, the sweep making its own execution (the caller and 1 worker,
   ``caller_runs``), forkserver and worker start-up timed, no cache — against 12 sequential
   spectra in this process, one thread (the sweep before: a loop in one process).  Target ≤ 0.6×.
   Also a 2-worker pool with the caller idle, cold, the same sweep on a running warm pool, and the
   CPU seconds of every side (caller, forkserver, workers), to tell load from serialisation.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

from fpucore import atlas, floquet, wave
from fpucore.atlas import ChunkTask, FloquetOptions, solve_chunk
from fpucore.law import CubicLaw
from fpucore.parallel import Executor, apply_thread_policy

LAW = CubicLaw(-1.0, 10.0)


def warm(ex: Executor, N: int) -> None:
    """Load the JIT cache in every worker (one small point each), so timings are steady."""
    task = ChunkTask(
        LAW,
        "superkink",
        N=N,
        tol=1e-12,
        floquet=FloquetOptions(True, method="structured"),
        row="lower",
        V=(5.5,),
    )
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


def descendants_cpu() -> float:
    """CPU seconds of this process's live children and of every process they waited for: the
    forkserver (our child) and the pool workers it forked, once they exited (Linux /proc:
    utime + stime + cutime + cstime of each child).  Differences over a run count the workers of
    a pool started and shut down inside it, which ``cpu_seconds(pids)`` cannot reach."""
    tick = os.sysconf("SC_CLK_TCK")
    me, total = str(os.getpid()), 0.0
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue  # ended meanwhile
        if fields[1] == me:
            total += sum(int(x) for x in fields[11:15]) / tick
    return total


def cold_sweep(N: int, nV: int, caller_runs: bool, method: str = "structured") -> dict:
    """In a fresh process (``--cold-sweep``), what ``fpu floquet sweep`` meets: no forkserver yet,
    workers to start, the caller's own JIT cache loaded first (one small point, untimed, as the
    sequential side has it).  caller_runs: the sweep makes its own execution (this process + 1
    worker on 2 cores); else a 2-worker pool with the caller idle (pool start timed).
    method: the spectra's eigenvalue route (the sweep's default "structured", or "dense")."""
    V = np.linspace(4.9, 5.8, nV)
    apply_thread_policy(1)
    solve_chunk(
        ChunkTask(
            LAW,
            "superkink",
            N=64,
            tol=1e-12,
            floquet=FloquetOptions(True, method=method),
            row="lower",
            V=(5.5,),
        )
    )
    d0, c0, t0 = descendants_cpu(), time.process_time(), time.perf_counter()
    kw = dict(N=N, use_cache=False, method=method)
    if caller_runs:
        s = atlas.sweep(LAW, "superkink", V, workers=2, **kw)
    else:
        with Executor(workers=2) as ex:
            s = atlas.sweep(LAW, "superkink", V, executor=ex, **kw)
    wall = time.perf_counter() - t0
    return {"wall": wall, "caller_cpu": time.process_time() - c0,
            "pool_cpu": descendants_cpu() - d0, "max_modulus": s.max_modulus.tolist(),
            "error": s.max_modulus_error.tolist(),
            "classification": list(s.classification)}  # fmt: skip


def run_cold_sweep(N: int, nV: int, caller_runs: bool, method: str = "structured") -> dict:
    """:func:`cold_sweep` in a new interpreter (its JSON on the last line of stdout)."""
    cmd = [sys.executable, "-m", "benchmarks.bench_atlas", "--cold-sweep", str(N), str(nV),
           "1" if caller_runs else "0", method]  # fmt: skip
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=900)
    return json.loads(out.stdout.strip().splitlines()[-1])


def sequential_spectra(V, N: int, method: str = "dense") -> tuple[list, float, float, list]:
    """One spectrum per velocity, one after the other in this process, as a user calls
    ``floquet.spectrum`` (route ``method``): (max|μ|, wall s, CPU s, (error, class) pairs)."""
    c0, t0 = time.process_time(), time.perf_counter()
    fr = [floquet.spectrum(wave.solve_superkink(LAW, v, N=N), method=method) for v in V]
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return [f.max_modulus for f in fr], wall, cpu, [(f.error, f.classification) for f in fr]


def part_d(N: int = 500, nV: int = 12) -> None:
    """The sweep as a user meets it (a fresh process: forkserver, worker start-up and pool
    start all timed; the sweep's default structured route) against 12 sequential spectra in this
    process (``spectrum(r, method="dense")``, the reference; before and after the sweeps: their
    mean, as the machine's speed drifts), both with a warm JIT in the calling process.  For the
    parallel efficiency alone, each route also against its own sequential time; then the sweep
    on a running, warm pool (the dashboard's case).  CPU seconds of every side — caller,
    forkserver and workers — tell load from serialisation: with two free cores the wall is about
    (total CPU) / 2."""
    V = np.linspace(4.9, 5.8, nV)
    print(f"D. {nV}-velocity max|mu| sweep at N={N} on 2 cores vs sequential "
          f"(load average {os.getloadavg()[0]:.1f})")  # fmt: skip
    apply_thread_policy(1)
    for method in ("dense", "structured"):  # the caller's JIT, as in cold_sweep
        floquet.spectrum(wave.solve_superkink(LAW, 5.5, N=64), method=method)
    seq = {m: sequential_spectra(V, N, m) for m in ("dense", "structured")}
    for m, (_, t, c, _) in seq.items():
        print(f"   sequential, {m:<10} {t:5.1f} s (CPU {c:.1f} s)")
    runs = {m: run_cold_sweep(N, nV, True, m) for m in ("structured", "dense")}
    t_seq = {}
    for m in ("dense", "structured"):
        _, t2, c2, _ = sequential_spectra(V, N, m)
        t_seq[m] = ((seq[m][1] + t2) / 2, (seq[m][2] + c2) / 2)
        print(f"   sequential, {m:<10} again after the sweeps {t2:.1f} s (CPU {c2:.1f} s); "
              f"mean {t_seq[m][0]:.1f} s")  # fmt: skip
    mu_d, _, _, ec_d = seq["dense"]
    for m, r in runs.items():
        cpu = r["caller_cpu"] + r["pool_cpu"]
        diff = float(np.max(np.abs(np.array(mu_d) - r["max_modulus"])
                            - np.maximum(r["error"], [e for e, _ in ec_d])))  # fmt: skip
        same = r["classification"] == [c for _, c in ec_d]
        print(f"   cold sweep ({m}, caller + 1 worker, as `fpu floquet sweep`"
              f"{' --method dense' if m == 'dense' else ''}): {r['wall']:.1f} s -> ratio to "
              f"12 sequential spectra {r['wall'] / t_seq['dense'][0]:.2f} (target <= 0.6); to "
              f"its own route's sequential time {r['wall'] / t_seq[m][0]:.2f} (parallel "
              f"efficiency); CPU {r['caller_cpu']:.1f} + {r['pool_cpu']:.1f} s = {cpu:.1f} s, "
              f"(CPU / 2) / sequential CPU {cpu / 2 / t_seq[m][1]:.2f}; max(|d max|mu|| - "
              f"error bar) vs dense {diff:.1e}, classifications equal: {same}")  # fmt: skip
    with Executor(workers=2) as ex:  # the dashboard's case: pool started and JIT loaded
        warm(ex, 64)
        t1 = time.perf_counter()
        atlas.sweep(LAW, "superkink", V, N=N, use_cache=False, executor=ex)
        t_warm = time.perf_counter() - t1
    print(f"   again on a running pool (started, JIT loaded: the dashboard's case) {t_warm:.1f} s"
          f" -> ratio {t_warm / t_seq['dense'][0]:.2f}; load average "
          f"{os.getloadavg()[0]:.1f}")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--cold-sweep", nargs=4, metavar=("N", "NV", "CALLER_RUNS", "METHOD"),
                    help="(internal) one cold sweep for part D; prints its JSON")  # fmt: skip
    a = ap.parse_args(argv)
    if a.cold_sweep:
        N, nV, caller_runs, method = a.cold_sweep
        print(json.dumps(cold_sweep(int(N), int(nV), bool(int(caller_runs)), method)))
        return
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
