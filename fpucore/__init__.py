"""fpucore — headless core of fpu-explorer.

Superkinks and solitary waves of the FPU chain with hardening–softening springs
f(w) = a w³ + b w² + w (Vainchtein & Truskinovsky), or any hardening–softening polynomial
(``law_from_expression``).  One subpackage per stage of the science:

    law (force laws)  →  qc (quasicontinuum closed forms, phase plane, diagrams)
    →  tableaux (RK / embedded / RKN coefficients as data)
    →  wave (discrete traveling waves: period map, Newton system, continuation, families)
    →  floquet (stability: monodromy, multipliers, sweeps)
    |  simulate (direct simulation of the chain and wave tracking)
    →  parallel (the execution layer: process pool / Dask, the thread budget)
    →  atlas (sweeps over the existence region, stored in Zarr)
    →  cli (the ``fpu`` command)

``errors`` (ParameterError) and ``result`` (the result protocol) are imported by all and import
nothing back.  Every result object carries its error estimate, ``status`` and ``elapsed_s``.
"""

import importlib
import os
import signal
import sys

# The `fpu` command (console script, or `python -m fpucore`: argv[0] is still "-m" while runpy
# imports the package) cannot catch Ctrl-C before its main() runs: Python would print a
# KeyboardInterrupt traceback.  For the import only, Ctrl-C gives the CLI's own one line and
# exit 130.  The handler stays until fpu's main() has parsed its arguments
# and imported the scientific stack (fpucore/cli/dispatch.py: load_stack puts Python's own
# handler back for the command).  A library import (any other argv[0]) is left alone.
_ORIG_ARGV = getattr(sys, "orig_argv", [])
_RUN_AS_MODULE = "-m" in _ORIG_ARGV and _ORIG_ARGV[_ORIG_ARGV.index("-m") + 1 :][:1] == ["fpucore"]
_CLI_IMPORT = bool(sys.argv) and (
    os.path.basename(sys.argv[0]) == "fpu" or (sys.argv[0] == "-m" and _RUN_AS_MODULE)
)


def _interrupted_during_import(signum, frame):  # pragma: no cover (a subprocess test)
    sys.stderr.write("fpu: interrupted\n")
    sys.stderr.flush()
    os._exit(130)


if _CLI_IMPORT:
    signal.signal(signal.SIGINT, _interrupted_during_import)

from fpucore.jit_cache import key_cache_dir  # noqa: E402

key_cache_dir()  # before any kernel is compiled: see fpucore/jit_cache.py

# Numba's "omp" threading layer (fpucore/parallel/threads.py), chosen before any kernel runs.  Set
# in the environment, read by Numba when it is imported (and inherited by child processes), so
# that importing fpucore does not import Numba; if Numba is in already, its config is set.
THREADING_LAYER = "omp"
os.environ["NUMBA_THREADING_LAYER"] = THREADING_LAYER
if "numba" in sys.modules:
    importlib.import_module("fpucore.parallel.threads").configure_threading_layer(THREADING_LAYER)

# The subpackages and names below load on first use (PEP 562): ``import fpucore`` costs a few
# milliseconds, and the ``fpu`` CLI prints its help without importing NumPy, SciPy or Numba.
_LAZY = {
    "floquet": ("fpucore.floquet", None),
    "qc": ("fpucore.qc", None),
    "simulate": ("fpucore.simulate", None),
    "wave": ("fpucore.wave", None),
    "CubicLaw": ("fpucore.law", "CubicLaw"),
    "HardeningSofteningLaw": ("fpucore.law", "HardeningSofteningLaw"),
    "PolynomialLaw": ("fpucore.law", "PolynomialLaw"),
    "TrilinearLaw": ("fpucore.law", "TrilinearLaw"),
    "PiecewiseLinearLaw": ("fpucore.law", "PiecewiseLinearLaw"),
    "SmoothLaw": ("fpucore.law", "SmoothLaw"),
    "law_from_expression": ("fpucore.law", "law_from_expression"),
    "ParameterError": ("fpucore.errors", "ParameterError"),
    "ConvergenceError": ("fpucore.errors", "ConvergenceError"),
}

__all__ = [
    "CubicLaw",
    "HardeningSofteningLaw",
    "PolynomialLaw",
    "TrilinearLaw",
    "PiecewiseLinearLaw",
    "SmoothLaw",
    "law_from_expression",
    "ParameterError",
    "ConvergenceError",
    "qc",
    "wave",
    "floquet",
    "simulate",
]
__version__ = "0.1.0"


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'fpucore' has no attribute {name!r}")
    module, attr = _LAZY[name]
    value = importlib.import_module(module)
    if attr is not None:
        value = getattr(value, attr)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
