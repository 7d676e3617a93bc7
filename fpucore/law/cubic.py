"""The cubic law f(w) = a w³ + b w² + w (paper eq. cubic, constants eq. cubic_more)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ParameterError, require_finite
from .base import HardeningSofteningLaw
from .kernels import LAW_CUBIC
from .polynomial import PolynomialLaw
from .scale import require_computable

if TYPE_CHECKING:
    from fpucore.law.base import Strain


def _require_computable(a: float, b: float) -> None:
    """The computable range of :mod:`.scale`, its W, c_max², w* written without overflow."""
    A = -a
    with np.errstate(over="ignore"):
        root = math.sqrt(b * b + 3.0 * A) if b < 1e150 else math.inf
        c2 = 1.0 + (b / A) * (b / 3.0) if b < 1e150 else math.inf
    alpha, beta = -1.0 / (root + b), (b + root) / (3.0 * A)
    require_computable("(a, b)", (a, b), alpha, beta, b / (3.0 * A), c2, "1 + b^2/(3|a|)")


@dataclass(frozen=True)
class CubicLaw(HardeningSofteningLaw):
    """f(w) = a w³ + b w² + w with a < 0 < b (paper eq. cubic).

    Parameters
    ----------
    a : cubic coefficient, must be negative (softening at large strain).
    b : quadratic coefficient, must be positive (hardening at small strain).
    """

    a: float = -1.0
    b: float = 10.0

    def __post_init__(self):
        a = require_finite("a", self.a)
        b = require_finite("b", self.b)
        if not a < 0:
            raise ParameterError("a", a, "a < 0", "the law must soften at large strain")
        if not b > 0:
            raise ParameterError("b", b, "b > 0", "the law must harden at small strain")
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "b", b)
        object.__setattr__(self, "law_id", LAW_CUBIC)
        _require_computable(a, b)

    # ----- kernel handle
    @property
    def params(self) -> np.ndarray:
        return np.array([self.a, self.b], dtype=np.float64)

    # ----- vectorised evaluation
    def f(self, w: Strain) -> Strain:
        w = np.asarray(w, dtype=float)
        return ((self.a * w + self.b) * w + 1.0) * w

    def df(self, w: Strain) -> Strain:
        w = np.asarray(w, dtype=float)
        return (3.0 * self.a * w + 2.0 * self.b) * w + 1.0

    def ddf(self, w: Strain) -> Strain:
        w = np.asarray(w, dtype=float)
        return 6.0 * self.a * w + 2.0 * self.b

    def phi(self, w: Strain) -> Strain:
        """Potential Φ(w) = ∫₀ʷ f = a w⁴/4 + b w³/3 + w²/2."""
        w = np.asarray(w, dtype=float)
        return ((0.25 * self.a * w + self.b / 3.0) * w + 0.5) * w * w

    # ----- constants (eq. cubic_more)
    @property
    def abs_a(self) -> float:
        return -self.a

    @property
    def w_star(self) -> float:
        """Inflection point w* = b / (3|a|): f″(w*) = 0, f′ maximal."""
        return self.b / (3.0 * self.abs_a)

    @property
    def alpha(self) -> float:
        """Lower end of the convex interval, −(√(b²+3|a|) − b)/(3|a|) (written stably)."""
        # (√(b²+3|a|) − b) = 3|a| / (√(b²+3|a|) + b): no cancellation for large b.
        return -1.0 / (math.sqrt(self.b**2 + 3.0 * self.abs_a) + self.b)

    @property
    def beta(self) -> float:
        """Upper end of the convex interval, (b + √(b²+3|a|))/(3|a|)."""
        return (self.b + math.sqrt(self.b**2 + 3.0 * self.abs_a)) / (3.0 * self.abs_a)

    def mirror(self, w: Strain) -> np.ndarray:
        """The symmetry w ↦ 2w* − w, under which f(w) = 4b/3 w*² + 2w* − f(2w* − w)."""
        return 2.0 * self.w_star - np.asarray(w, dtype=float)

    @property
    def symmetry_constant(self) -> float:
        """f(w) + f(2w* − w) = 4b/3 w*² + 2w* for every w (= 2 f(w*))."""
        return 4.0 * self.b / 3.0 * self.w_star**2 + 2.0 * self.w_star

    def describe(self) -> str:
        return f"f(w) = {self.a:g} w^3 + {self.b:g} w^2 + w"

    def as_polynomial(self) -> PolynomialLaw:
        """The same law as a :class:`.PolynomialLaw` with coeffs (1, b, a): the general route."""
        return PolynomialLaw((1.0, self.b, self.a))
