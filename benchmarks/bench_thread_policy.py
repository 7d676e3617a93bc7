"""The thread policy at every entry point: one dense Floquet spectrum, superkink V = 5.2,
N = 500 (``floquet.spectrum(wave.solve_superkink(CubicLaw(), 5.2, N=500), finite_size=False,
method="dense")``), computed by

* **worker**   — the explorer's way: a job on a 1-thread worker of ``fpucore.parallel.Executor``
  (the reference);
* **cli**      — ``fpu floquet superkink --V 5.2 --N 500 --no-finite-size --method dense --json``;
* **api**      — a script: ``import fpucore`` and the call above;
* **notebook** — a script that first uses NumPy's BLAS itself at the libraries' default threads
  (a matrix product, as a notebook's earlier cells would), then makes the same call;
* **api-all**  — the script with ``FPU_THREADS=all`` (every core: what fpucore did before the
  policy reached the main process), for comparison.

Every entry runs in fresh processes with the user's default environment (OPENBLAS_NUM_THREADS,
OMP_NUM_THREADS, MKL_NUM_THREADS, FPU_THREADS removed: one BLAS thread per core unless fpucore
limits it).  Each figure is the first spectrum of its process (kernels loaded from Numba's cache,
as a user meets it); median of ``--repeat`` processes, entries interleaved.  Two conditions in the
same run: a quiet machine, and with ``--busy`` (default 2) CPU-bound background processes.  The
ratio is each entry's spectrum time over the worker's (target ≤ 1.3).

    python -m benchmarks.bench_thread_policy [--repeat 3] [--busy 2]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

from fpucore import CubicLaw, floquet, wave

THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "FPU_THREADS")
ENTRIES = ("worker", "cli", "api", "notebook", "api-all")
V, N = 5.2, 500

CALL = (
    "import json, fpucore\n"
    f"r = fpucore.wave.solve_superkink(fpucore.CubicLaw(), {V}, N={N})\n"
    "f = fpucore.floquet.spectrum(r, finite_size=False, method='dense')\n"
    "print(json.dumps({'spectrum_s': f.elapsed_s, 'eig_s': f.eig_s}))\n"
)
NOTEBOOK = (
    "import numpy as np\n"
    "a = np.random.default_rng(0).standard_normal((1500, 1500))\n"
    "for _ in range(3):\n"
    "    a = a @ a.T / 1500\n"  # the notebook's own BLAS work, default threads
) + CALL
WORKER = (
    "import json\n"
    "from fpucore.parallel import Executor\n"
    "from benchmarks.bench_thread_policy import spectrum_times\n"
    "with Executor(backend='process', workers=1) as ex:\n"
    "    print(json.dumps(ex.submit(spectrum_times).result()))\n"
)
BUSY = "while True:\n    pass\n"


def spectrum_times() -> dict:
    """The worker's job: the first spectrum of the worker process."""
    r = wave.solve_superkink(CubicLaw(), V, N=N)
    f = floquet.spectrum(r, finite_size=False, method="dense")
    return {"spectrum_s": f.elapsed_s, "eig_s": f.eig_s}


def user_env() -> dict:
    return {k: v for k, v in os.environ.items() if k not in THREAD_VARS}


def run_entry(entry: str) -> dict:
    if entry == "cli":
        cmd = [sys.executable, "-m", "fpucore", "floquet", "superkink", "--V", str(V), "--N",
               str(N), "--no-finite-size", "--method", "dense", "--json"]  # fmt: skip
    else:
        code = {"worker": WORKER, "api": CALL, "notebook": NOTEBOOK, "api-all": CALL}[entry]
        cmd = [sys.executable, "-c", code]
    env = user_env() | ({"FPU_THREADS": "all"} if entry == "api-all" else {})
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    d = json.loads(out.stdout.strip().splitlines()[-1])
    if entry == "cli":
        return {"spectrum_s": d["floquet_elapsed_s"], "eig_s": d["eig_s"]}
    return d


def measure(repeat: int) -> dict[str, dict[str, float]]:
    got: dict[str, list[dict]] = {e: [] for e in ENTRIES}
    for _ in range(repeat):
        for e in ENTRIES:
            got[e].append(run_entry(e))
    return {e: {k: statistics.median(x[k] for x in v) for k in ("spectrum_s", "eig_s")}
            for e, v in got.items()}  # fmt: skip


def report(label: str, res: dict) -> None:
    ref = res["worker"]["spectrum_s"]
    print(f"  {label} (load average {os.getloadavg()[0]:.2f})")
    for e in ENTRIES:
        r = res[e]["spectrum_s"] / ref
        ok = "" if e in ("worker", "api-all") else ("  OK" if r <= 1.3 else "  over 1.3x")
        print(f"    {e:9s} spectrum {res[e]['spectrum_s']:.3f} s  (eig {res[e]['eig_s']:.3f} s)"
              f"  ratio {r:.2f}{ok}")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--busy", type=int, default=2, help="CPU-bound background processes")
    a = ap.parse_args(argv)
    print(f"dense Floquet spectrum, superkink V={V} N={N}, first call of a fresh process, "
          f"median of {a.repeat}; ratio = entry / worker")  # fmt: skip
    report("quiet", measure(a.repeat))
    busy = [subprocess.Popen([sys.executable, "-c", BUSY]) for _ in range(a.busy)]
    try:
        time.sleep(1.0)
        report(f"{a.busy} CPU-bound background processes", measure(a.repeat))
    finally:
        for p in busy:
            p.kill()
            p.wait()


if __name__ == "__main__":
    main()
