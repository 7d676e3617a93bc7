"""fpucore's thread budget in the *main* process (a script, a notebook, the CLI), not only in the
pool's workers: inside a call, BLAS/OpenMP/Numba run on FPU_THREADS threads (default 1), and the
caller's own settings come back afterwards.  Each case runs in a fresh interpreter with the
libraries' defaults (one BLAS thread per core), the situation of a user's script."""

import json
import os
import subprocess
import sys

import pytest

THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "FPU_THREADS")

# spies on the LAPACK call of the dense route: the limits in force while it runs
PROBE = r"""
import importlib, json, sys
import numba, scipy.linalg
from threadpoolctl import threadpool_info
import fpucore
mono = importlib.import_module("fpucore.floquet.monodromy")
seen = []
real = scipy.linalg.eigvals
def spy(*a, **k):
    seen.append({"blas": sorted({d["num_threads"] for d in threadpool_info()
                                 if d["user_api"] == "blas"}),
                 "numba": numba.get_num_threads()})
    return real(*a, **k)
mono.scipy.linalg.eigvals = spy
def blas():
    return sorted({d["num_threads"] for d in threadpool_info() if d["user_api"] == "blas"})
before = blas()
if sys.argv[1] == "api":
    r = fpucore.wave.solve_superkink(fpucore.CubicLaw(), 5.2, N=64)
    fpucore.floquet.spectrum(r, finite_size=False, method="dense")
else:
    from fpucore.cli import main
    main(["floquet", "superkink", "--V", "5.2", "--N", "64", "--no-finite-size", "--json"])
print(json.dumps({"before": before, "inside": seen, "after": blas()}))
"""


def _probe(mode: str, **env_extra) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARS} | env_extra
    out = subprocess.run([sys.executable, "-c", PROBE, mode], env=env, capture_output=True,
                         text=True, timeout=600, check=True)  # fmt: skip
    return json.loads(out.stdout.strip().splitlines()[-1])


needs_two_cores = pytest.mark.skipif(
    len(os.sched_getaffinity(0)) < 2, reason="one core: the default is already one thread"
)


@needs_two_cores
def test_a_script_computes_on_one_thread_and_keeps_its_own_settings():
    d = _probe("api")
    assert d["before"] and max(d["before"]) >= 2  # the libraries' default: a thread per core
    assert d["inside"] and all(x == {"blas": [1], "numba": 1} for x in d["inside"]), d
    assert d["after"] == d["before"], d  # the caller's numpy is left as it was


@needs_two_cores
def test_fpu_threads_overrides_the_budget():
    d = _probe("api", FPU_THREADS="2")
    assert all(x == {"blas": [2], "numba": 2} for x in d["inside"]), d


@needs_two_cores
def test_the_cli_computes_on_the_budget():
    d = _probe("cli")
    assert d["inside"] and all(x == {"blas": [1], "numba": 1} for x in d["inside"]), d


def test_a_malformed_fpu_threads_is_refused_by_name():
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARS} | {"FPU_THREADS": "two"}
    p = subprocess.run([sys.executable, "-m", "fpucore", "wave", "superkink", "--V", "5.2"],
                       env=env, capture_output=True, text=True, timeout=600)  # fmt: skip
    assert p.returncode == 2, p.stderr
    assert p.stderr.strip().splitlines() == [p.stderr.strip()]
    assert "FPU_THREADS" in p.stderr and "'two'" in p.stderr, p.stderr
