"""Force laws f(w) (paper §2, eqs. cubic, cubic_more).

A law is a small Python object (validation, constants α, β, w*, vectorised f, f′, f″, Φ) plus a
handle ``(law_id, params)`` that the Numba kernels in :mod:`.kernels` take.

    kernels (Numba f, f′, f″ by law_id)  →  base (the hardening–softening class)  →  cubic
"""

from .base import HardeningSofteningLaw, require_law
from .cubic import CubicLaw
from .kernels import LAW_CUBIC, ddforce, dforce, force

__all__ = [
    "HardeningSofteningLaw",
    "require_law",
    "CubicLaw",
    "LAW_CUBIC",
    "force",
    "dforce",
    "ddforce",
]
