"""Force laws f(w) (paper §2, eqs. cubic, cubic_more, and any hardening–softening polynomial).

A law is a small Python object (validation, constants α, β, w*, vectorised f, f′, f″, Φ) plus a
handle ``(law_id, params)`` that the Numba kernels in :mod:`.kernels` take.

    kernels (Numba f, f′, f″ by law_id)  →  base (the hardening–softening class)  →  scale (the
    computable range shared by every law)  →  polynomial (Σ c_k w^k, hypotheses of §2 checked)
    →  cubic  ·  expression_bounds (degree, exponents, sizes of a text, before any algebra)
    →  expansion (its coefficients by exact arithmetic)
    →  expression (text → law: a polynomial, else a smooth law)
    ·  smooth_parse (allow-listed AST → SymPy) → smooth_eval (closures: float, longdouble,
    mpmath) → smooth_class (α, β, w*) → chebyshev (the LAW_CHEB data and its measured error)
    → smooth_build (class check, represented interval, representation) → smooth (SmoothLaw)
    → presets (the explorer's laws)
    ·  piecewise (continuous piecewise-linear laws, the soft–hard–soft trilinear family)
"""

from .base import HardeningSofteningLaw, interval_note, require_law
from .cubic import CubicLaw
from .expression import law_from_expression
from .kernels import (
    LAW_CHEB,
    LAW_CUBIC,
    LAW_POLY,
    LAW_PWL,
    POLY_IDS,
    ddforce,
    dforce,
    force,
    forces_into,
)
from .piecewise import PiecewiseLinearLaw, TrilinearLaw
from .piecewise_text import law_from_piecewise_text
from .polynomial import PolynomialLaw, expression_of, real_roots
from .smooth import SmoothLaw

__all__ = [
    "expression_of",
    "HardeningSofteningLaw",
    "require_law",
    "interval_note",
    "CubicLaw",
    "PolynomialLaw",
    "SmoothLaw",
    "LAW_CHEB",
    "law_from_expression",
    "real_roots",
    "LAW_CUBIC",
    "LAW_POLY",
    "LAW_PWL",
    "PiecewiseLinearLaw",
    "TrilinearLaw",
    "law_from_piecewise_text",
    "POLY_IDS",
    "force",
    "forces_into",
    "dforce",
    "ddforce",
]
