"""fpucore — headless core of fpu-explorer.

Superkinks and solitary waves of the FPU chain with hardening–softening springs
f(w) = a w³ + b w² + w (Vainchtein & Truskinovsky).  Flow of the package:

    law (force law) → qc (quasicontinuum closed forms, phase plane, existence diagram)
    → period_map / wave / continuation (discrete traveling waves)
    → floquet (stability) and simulate / tracking (direct simulation) → cli

Every result object carries its error estimate and ``elapsed_s``.
"""

from ._jit_cache import key_cache_dir

key_cache_dir()  # before any kernel is compiled: see fpucore/_jit_cache.py

from . import qc  # noqa: E402
from .errors import ConvergenceError, ParameterError  # noqa: E402
from .law import CubicLaw, HardeningSofteningLaw  # noqa: E402

__all__ = ["CubicLaw", "HardeningSofteningLaw", "ParameterError", "ConvergenceError", "qc"]
__version__ = "0.1.0"
