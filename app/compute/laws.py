"""The dashboard's laws: the cubic (a, b) or a typed polynomial expression, and their exact
cache-key form.

fpucore builds the laws; this module adds what the app needs around them: coefficients too
large for the closed forms are refused as a ParameterError (never an overflow on screen), a
typed expression is parsed once (memoised), and :func:`law_key` is the law's part of every
cache key (:mod:`app.compute.cache`).
"""

from __future__ import annotations

import functools

import numpy as np

from fpucore.errors import ParameterError
from fpucore.law import CubicLaw, HardeningSofteningLaw, PolynomialLaw, law_from_expression

from .cache import exact

__all__ = ["law", "expression_law", "make_law", "law_key"]


def law(a: float, b: float) -> CubicLaw:
    """The cubic law f(w) = a w³ + b w² + w (raises ParameterError for a ≥ 0, b ≤ 0, or
    coefficients so large that its closed forms overflow)."""
    try:
        lw = CubicLaw(a=float(a), b=float(b))
        # the closed forms the scenes use first (α, β, w*, c_max) must be finite doubles
        if not all(np.isfinite([lw.alpha, lw.beta, lw.w_star, float(lw.f(lw.beta))])):
            raise OverflowError
        return lw
    except OverflowError:
        raise ParameterError(
            "b", float(b), "|b| small enough for double precision (e.g. b <= 1e100)", "overflow"
        ) from None


@functools.lru_cache(maxsize=64)
def _parsed(expression: str) -> tuple[PolynomialLaw | None, ParameterError | None]:
    try:
        return law_from_expression(expression), None
    except ParameterError as exc:
        return None, exc


def expression_law(expression: str) -> PolynomialLaw:
    """fpucore.law_from_expression, memoised (laws are immutable; the state asks for its law on
    every change and SymPy's parse costs milliseconds).  Raises its ParameterError."""
    lw, exc = _parsed(expression)
    if exc is not None:  # a fresh exception: re-raising the cached one would grow its traceback
        raise ParameterError(exc.name, exc.value, exc.valid, exc.reason)
    return lw


def make_law(a: float, b: float, expression: str = "") -> HardeningSofteningLaw:
    """The explorer's law: the cubic (a, b) when ``expression`` is empty, else the polynomial
    law of the expression (fpucore.law_from_expression).  Raises ParameterError."""
    if expression:
        return expression_law(expression)
    return law(a, b)


def law_key(lw: HardeningSofteningLaw) -> tuple:
    """Exact cache-key form of a law: its kind and coefficients (repr).  The cubic and the same
    cubic as a PolynomialLaw are different keys: different routes (closed forms vs numerical)."""
    if isinstance(lw, CubicLaw):
        return ("cubic", exact(lw.a), exact(lw.b))
    if isinstance(lw, PolynomialLaw):
        return ("poly", *(exact(c) for c in lw.coeffs))
    raise ParameterError("law", lw, "a CubicLaw or PolynomialLaw")
