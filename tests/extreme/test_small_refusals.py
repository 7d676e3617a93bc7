"""Small inputs that escaped as Python errors or were accepted silently (fuzzing report, "smaller"):
each is now a ParameterError naming the argument, its value and the valid range, in the API and
in the CLI (exit 2, one line)."""

from __future__ import annotations

import multiprocessing as mp
import subprocess
import sys

import numpy as np
import pytest

from fpucore import budget, floquet, wave
from fpucore.cli import main
from fpucore.errors import ParameterError
from fpucore.floquet.energy import criterion_from_samples
from fpucore.law import CubicLaw
from fpucore.parallel.threads import apply_thread_policy, thread_policy
from fpucore.simulate.config import restoring_interval
from fpucore.simulate.seeded import whole_periods

LAW = CubicLaw()

CASES = [  # (call, argument named, words of the valid range or reason)
    (lambda: whole_periods(5.0, 0.0), "T", "T > 0"),  # was ZeroDivisionError
    (lambda: whole_periods(5.0, float("nan")), "T", "finite"),
    (lambda: whole_periods(-1.0, 1.0), "t_end", "t_end >= 0"),
    (lambda: restoring_interval(None), "law", "force law"),  # was AttributeError
    (lambda: wave.superkink_family(LAW, ["a"]), "V_values", "finite velocities"),  # ValueError
    (lambda: apply_thread_policy("x"), "n_threads", "an integer in [1, 4096]"),  # ValueError
    (lambda: apply_thread_policy(2.5), "n_threads", "an integer in [1, 4096]"),
    (lambda: thread_policy(0).__enter__(), "n_threads", "an integer in [1, 4096]"),
    # accepted silently before: V of 3 with energies of 2 (zip cut them to 2)
    (
        lambda: criterion_from_samples(
            LAW, 0.5, [5.0, 5.1, 5.2], [1.0, 2.0], [0.0] * 3, [True] * 3, qc_samples=0
        ),
        "energy",
        "length 3",
    ),  # fmt: skip
    (
        lambda: criterion_from_samples(
            LAW, 0.5, [5.0, 5.1], [1.0, 2.0], [0.0] * 2, [True], qc_samples=0
        ),
        "converged",
        "length 2",
    ),  # fmt: skip
    (lambda: floquet.HomogeneousState(LAW, 0.5, 5.0, 8, kind="x"), "kind", "'homogeneous'"),
    (lambda: floquet.HomogeneousState(None, 0.5, 5.0, 8), "law", "force law"),
    (lambda: floquet.structured_multipliers(np.zeros((3, 4)), 2), "mat", "(4, 4)"),
    (lambda: floquet.structured_multipliers(np.full((4, 4), np.nan), 2), "mat", "finite"),
    (lambda: floquet.structured_multipliers(np.eye(4), 2.5), "n", "an integer"),
    (lambda: budget.parse_size("1e308TiB"), "memory_budget", "overflows"),  # OverflowError
    (lambda: budget.parse_size(0.5), "memory_budget", "less than one byte"),
    (lambda: budget.parse_size("0.5"), "memory_budget", "50%"),
]


@pytest.mark.parametrize("call, name, words", CASES)
def test_refused_naming_the_argument(call, name, words):
    with pytest.raises(ParameterError) as e:
        call()
    assert e.value.name == name and words in str(e.value), str(e.value)


def test_valid_calls_still_work():
    assert whole_periods(5.0, 1.0) == (5, 5.0)
    lo, hi = restoring_interval(LAW)
    assert (lo, hi) == pytest.approx((5 - 26**0.5, 5 + 26**0.5), rel=1e-12)
    assert budget.parse_size("2GiB") == 2 * 2**30 and budget.parse_size(1.5) == 1
    assert apply_thread_policy(1)["threads"] == 1


@pytest.mark.parametrize(
    "cmd",
    [
        ["qc", "--w-plus", "1"],
        ["wave", "superkink", "--V", "5.2", "--N", "64"],
        ["atlas", "superkink", "--V", "5:5.2:2", "--out", "{tmp}/a.zarr"],
    ],  # fmt: skip
    ids=["qc", "wave", "atlas"],
)
@pytest.mark.parametrize("env", ["abc", "0.5", "1e308TiB", "-2GiB"])
def test_an_invalid_memory_budget_variable_is_refused_by_every_command(
    capsys, monkeypatch, tmp_path, cmd, env
):
    """qc, wave and atlas never read it before: an invalid value was ignored silently; 0.5 was
    0 bytes and blamed n_snapshots."""
    monkeypatch.setenv("FPU_MEMORY_BUDGET", env)
    assert main([c.replace("{tmp}", str(tmp_path)) for c in cmd]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fpu: error: FPU_MEMORY_BUDGET='{env}'") and err.count("\n") == 1, err
    assert not (tmp_path / "a.zarr").exists()  # refused before the store is made


def test_memory_budget_option_overflow_is_one_line(capsys):
    argv = ["simulate", "riemann", "--w-left", "0.5", "--w-right", "0", "--L", "10",
            "--t-end", "1", "--memory-budget", "1e308TiB"]  # fmt: skip
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error: memory_budget='1e308TiB'") and "overflows" in err, err


def test_law_with_a_or_b_is_refused(capsys):
    """--law used to replace --a/--b silently: the user's cubic was never computed."""
    assert main(["qc", "--w-plus", "1", "--law", "w + 10*w**2 - w**3", "--b", "20"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error: --law=") and "--b 20 given too" in err, err
    assert main(["qc", "--w-plus", "1", "--a", "-2", "--json"]) == 0  # --a alone: the cubic
    assert '"a": -2.0, "b": 10.0' in capsys.readouterr().out


FORK_SCRIPT = r"""
import multiprocessing as mp
import fpucore as F

def job(V):
    r = F.wave.solve_superkink(F.CubicLaw(), V, N=64)
    return bool(r.converged)

if __name__ == "__main__":
    assert mp.get_start_method(allow_none=True) is None  # fpucore leaves the default alone
    job(5.2)  # a solve in the parent first: Numba's OpenMP threads have run
    with mp.get_context("spawn").Pool(2) as pool:  # the README's recommendation
        print(pool.map(job, [5.1, 5.3]))
"""


def test_the_readme_pool_recipe_works_after_a_solve(tmp_path):
    """The documented way to run one's own pool after a solve (fork would hang, README)."""
    script = tmp_path / "pool.py"
    script.write_text(FORK_SCRIPT)
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         timeout=300)  # fmt: skip
    assert out.returncode == 0 and out.stdout.strip() == "[True, True]", out.stderr[-2000:]
    assert mp.get_start_method(allow_none=True) in (None, "fork", "forkserver", "spawn")
