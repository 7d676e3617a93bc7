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

import os
import signal
import sys

# The `fpu` command (console script, or `python -m fpucore`: argv[0] is still "-m" while runpy
# imports the package) cannot catch Ctrl-C before its main() runs, and importing this package
# takes ~1 s: Python would print a KeyboardInterrupt traceback.  For the import only, Ctrl-C
# gives the CLI's own one line and exit 130 (issue 14 item 7); the previous handler comes back
# at the end of this file.  A library import (any other argv[0]) is left alone.
_CLI_IMPORT = bool(sys.argv) and (os.path.basename(sys.argv[0]) == "fpu" or sys.argv[0] == "-m")


def _interrupted_during_import(signum, frame):  # pragma: no cover (a subprocess test)
    sys.stderr.write("fpu: interrupted\n")
    sys.stderr.flush()
    os._exit(130)


if _CLI_IMPORT:
    _PREVIOUS_SIGINT = signal.signal(signal.SIGINT, _interrupted_during_import)

from fpucore.jit_cache import key_cache_dir  # noqa: E402

key_cache_dir()  # before any kernel is compiled: see fpucore/jit_cache.py

from fpucore.parallel.threads import configure_threading_layer  # noqa: E402

configure_threading_layer()  # Numba's "omp" layer, chosen before any kernel runs

from fpucore import floquet, qc, simulate, wave  # noqa: E402
from fpucore.errors import ConvergenceError, ParameterError  # noqa: E402
from fpucore.law import (  # noqa: E402
    CubicLaw,
    HardeningSofteningLaw,
    PolynomialLaw,
    law_from_expression,
)

__all__ = [
    "CubicLaw",
    "HardeningSofteningLaw",
    "PolynomialLaw",
    "law_from_expression",
    "ParameterError",
    "ConvergenceError",
    "qc",
    "wave",
    "floquet",
    "simulate",
]
__version__ = "0.1.0"

if _CLI_IMPORT:
    signal.signal(signal.SIGINT, _PREVIOUS_SIGINT)
