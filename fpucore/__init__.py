"""fpucore — headless core of fpu-explorer.

Superkinks and solitary waves of the FPU chain with hardening–softening springs
f(w) = a w³ + b w² + w (Vainchtein & Truskinovsky).  Flow of the package:

    law (force law) → qc (quasicontinuum closed forms, phase plane, existence diagram)
    → period_map / wave / continuation (discrete traveling waves)
    → floquet (stability) and simulate / tracking (direct simulation) → cli

Every result object carries its error estimate and ``elapsed_s``.
"""

from . import qc
from .errors import ConvergenceError, ParameterError
from .law import CubicLaw, HardeningSofteningLaw

__all__ = ["CubicLaw", "HardeningSofteningLaw", "ParameterError", "ConvergenceError", "qc"]
__version__ = "0.1.0"
