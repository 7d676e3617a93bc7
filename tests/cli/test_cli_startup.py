"""Start-up of the ``fpu`` command: help without the scientific stack, Ctrl-C while it loads."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from fpucore import floquet, simulate, warm
from fpucore.cli import choices

HELPS = [[], ["qc"], ["warm"], ["wave"], ["wave", "superkink"], ["floquet"],
         ["floquet", "superkink"], ["floquet", "sweep"], ["simulate"], ["simulate", "riemann"],
         ["simulate", "wave", "solitary"], ["atlas"], ["atlas", "solitary"], ["paper"]]  # fmt: skip

# every help of the parser in one fresh interpreter, then the heavy modules it imported
HELP_PROBE = r"""
import contextlib, io, json, sys
from fpucore.cli import main
for argv in json.loads(sys.argv[1]):
    with contextlib.redirect_stdout(io.StringIO()) as out:
        try:
            main(argv + ["--help"])
        except SystemExit as e:
            assert e.code == 0, (argv, e.code)
    assert "usage: fpu" in out.getvalue(), argv
heavy = ("numpy", "scipy", "numba", "sympy", "tqdm", "threadpoolctl", "llvmlite")
print(json.dumps(sorted(m for m in sys.modules if m.split(".")[0] in heavy)))
"""


def test_help_imports_neither_numpy_nor_scipy_nor_numba():
    out = subprocess.run([sys.executable, "-c", HELP_PROBE, json.dumps(HELPS)],
                         capture_output=True, text=True, timeout=120, check=True)  # fmt: skip
    assert json.loads(out.stdout.strip().splitlines()[-1]) == []


def test_the_parsers_choices_are_the_cores():
    assert choices.FLOQUET_METHODS == floquet.METHODS
    assert choices.SIMULATE_METHODS == simulate.METHODS
    assert choices.BOUNDARIES == simulate.BOUNDARIES
    assert choices.GUARDS == simulate.GUARDS
    assert choices.LAZY_WARM == warm.LAZY


@pytest.mark.parametrize("delay", [0.0, 0.2, 0.5, 1.0])
def test_ctrl_c_while_the_command_loads_gives_one_line(delay):
    """SIGINT at several moments of start-up once fpucore's first module has run (before it,
    only Python's own start-up runs): the package, the parser, the scientific stack, the
    kernels' cache.  Always exit 130 with one line, never a traceback.  ``-X importtime`` tells
    when fpucore's first module was imported (its lines are left out of the comparison)."""
    p = subprocess.Popen([sys.executable, "-X", "importtime", "-m", "fpucore", "floquet",
                          "superkink", "--V", "5.2", "--N", "500"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)  # fmt: skip
    for line in p.stderr:
        if "fpucore.jit_cache" in line:
            break
    time.sleep(delay)
    if p.poll() is not None:
        pytest.skip("finished before the interrupt")
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    lines = [x for x in err.splitlines() if x.strip() and not x.startswith("import time:")]
    # 130, or killed by SIGINT (shown as 130 by a shell) when CPython re-raises the signal at exit
    # after an interrupt that landed inside an extension's own Python evaluation while importing
    assert p.returncode in (130, -signal.SIGINT), (p.returncode, err)
    assert lines == ["fpu: interrupted"], err


def test_fpucore_imports_lazily():
    """``import fpucore`` alone loads no subpackage; its names load on first use."""
    probe = ("import sys, fpucore; a = sorted(m for m in sys.modules if m.startswith('numpy'));"
             "fpucore.CubicLaw; print(a == [], 'fpucore.law' in sys.modules)")  # fmt: skip
    env = dict(os.environ)
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         timeout=120, check=True, env=env)  # fmt: skip
    assert out.stdout.split() == ["True", "True"]
