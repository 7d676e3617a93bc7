"""Hardening–softening force laws f(w) (paper §2, eqs. cubic, cubic_more).

A law is a small Python object (validation, closed forms, vectorised evaluation) plus a pair
``(law_id, params)`` that the Numba kernels take, so every jitted integrator evaluates f, f′ through
:func:`force` / :func:`dforce` below.  Adding a second law means adding a subclass here and a
branch in the three kernels — QC/discrete/Floquet/simulation code is untouched.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from .errors import ParameterError, require_finite

LAW_CUBIC = 0


# --------------------------------------------------------------------------- Numba kernels
@njit(cache=True, nogil=True)
def force(law_id: int, p: np.ndarray, w: float) -> float:
    """f(w) for the law (law_id, p).  Cubic: p = [a, b], f = a w³ + b w² + w."""
    if law_id == LAW_CUBIC:
        return ((p[0] * w + p[1]) * w + 1.0) * w
    return math.nan


@njit(cache=True, nogil=True)
def dforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f′(w)."""
    if law_id == LAW_CUBIC:
        return (3.0 * p[0] * w + 2.0 * p[1]) * w + 1.0
    return math.nan


@njit(cache=True, nogil=True)
def ddforce(law_id: int, p: np.ndarray, w: float) -> float:
    """f″(w)."""
    if law_id == LAW_CUBIC:
        return 6.0 * p[0] * w + 2.0 * p[1]
    return math.nan


# --------------------------------------------------------------------------- Python objects
@dataclass(frozen=True)
class HardeningSofteningLaw:
    """Base class: a smooth f with f(0)=0, f′>0 on (α, β) ∋ 0, f″>0 on (α, w*), f″<0 on (w*, β).

    Subclasses provide f, df, ddf, phi (vectorised), the constants w_star/alpha/beta and the
    kernel handle ``(law_id, params)``.  Everything in §3 of the paper is written against this.
    """

    law_id: int = field(init=False, repr=False, default=-1)

    @property
    def params(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def f(self, w):  # pragma: no cover - abstract
        raise NotImplementedError

    def df(self, w):  # pragma: no cover - abstract
        raise NotImplementedError

    def ddf(self, w):  # pragma: no cover - abstract
        raise NotImplementedError

    def phi(self, w):  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def c_max(self) -> float:
        """Largest sound speed, √f′(w*), on the convex interval."""
        return math.sqrt(float(self.df(self.w_star)))

    def require_convex(self, name: str, w: float) -> float:
        """Check α < w < β (f′(w) > 0, Φ convex) for a strain argument."""
        w = require_finite(name, w)
        if not (self.alpha < w < self.beta):
            raise ParameterError(
                name,
                w,
                f"(alpha, beta) = ({self.alpha:.10g}, {self.beta:.10g})",
                "strain must lie in the convex interval where f'(w) > 0",
            )
        return w


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

    # ----- kernel handle
    @property
    def params(self) -> np.ndarray:
        return np.array([self.a, self.b], dtype=np.float64)

    # ----- vectorised evaluation
    def f(self, w):
        w = np.asarray(w, dtype=float)
        return ((self.a * w + self.b) * w + 1.0) * w

    def df(self, w):
        w = np.asarray(w, dtype=float)
        return (3.0 * self.a * w + 2.0 * self.b) * w + 1.0

    def ddf(self, w):
        w = np.asarray(w, dtype=float)
        return 6.0 * self.a * w + 2.0 * self.b

    def phi(self, w):
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

    def mirror(self, w):
        """The symmetry w ↦ 2w* − w, under which f(w) = 4b/3 w*² + 2w* − f(2w* − w)."""
        return 2.0 * self.w_star - np.asarray(w, dtype=float)

    @property
    def symmetry_constant(self) -> float:
        """f(w) + f(2w* − w) = 4b/3 w*² + 2w* for every w (= 2 f(w*))."""
        return 4.0 * self.b / 3.0 * self.w_star**2 + 2.0 * self.w_star

    def describe(self) -> str:
        return f"f(w) = {self.a:g} w^3 + {self.b:g} w^2 + w"
