"""The class of hardening–softening laws (paper §2–3): what every law object provides."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, require_finite

#: a strain or an array of strains.  The laws' functions are vectorised: a float in gives a float
#: out, an array an array of its shape (no overloads spell that out: the result is typed Any).
Strain = Any


@dataclass(frozen=True)
class HardeningSofteningLaw:
    """Base class: a smooth f with f(0)=0, f′>0 on (α, β) ∋ 0, f″>0 on (α, w*), f″<0 on (w*, β).

    Subclasses provide f, df, ddf, phi (vectorised), the constants w_star/alpha/beta and the
    kernel handle ``(law_id, params)``.  Everything in §3 of the paper is written against this.
    """

    law_id: int = field(init=False, repr=False, default=-1)

    if TYPE_CHECKING:  # provided by every subclass (properties or computed fields)

        @property
        def w_star(self) -> float: ...

        @property
        def alpha(self) -> float: ...

        @property
        def beta(self) -> float: ...

    @property
    def params(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def f(self, w: Strain) -> Strain:  # pragma: no cover - abstract
        raise NotImplementedError

    def df(self, w: Strain) -> Strain:  # pragma: no cover - abstract
        raise NotImplementedError

    def ddf(self, w: Strain) -> Strain:  # pragma: no cover - abstract
        raise NotImplementedError

    def phi(self, w: Strain) -> Strain:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def c_max(self) -> float:
        """Largest sound speed, √f′(w*), on the convex interval."""
        return math.sqrt(float(self.df(self.w_star)))

    def require_convex(self, name: str, w: float) -> float:
        """Check α < w < β (f′(w) > 0, Φ convex) for a strain argument."""
        w = require_finite(name, w)
        # f'(w) > 0 checked too: within an ulp of alpha or beta the rounded endpoint can admit a
        # w whose f'(w) is already <= 0 (c+ = sqrt(f') would then be 0 or NaN)
        if not (self.alpha < w < self.beta) or not float(self.df(w)) > 0.0:
            raise ParameterError(
                name,
                w,
                f"(alpha, beta) = ({self.alpha:.10g}, {self.beta:.10g})",
                "strain must lie in the convex interval where f'(w) > 0",
            )
        return w


def interval_note(law: object) -> str:
    """For a law represented on an interval (:class:`~fpucore.law.SmoothLaw`): the clause that
    names it, for messages about non-finite values (its kernels return NaN outside); else ""."""
    iv = getattr(law, "interval", None)
    if not iv:
        return ""
    return (
        f"; a strain may have left the represented interval [{iv[0]:.6g}, {iv[1]:.6g}] of "
        "the smooth law (its kernels return NaN outside)"
    )


def require_law(law: object, name: str = "law") -> HardeningSofteningLaw:
    """The law itself, or ParameterError if it is not a force-law object (None, a string ...)."""
    if not isinstance(law, HardeningSofteningLaw):
        raise ParameterError(
            name, type(law).__name__, "a force law such as fpucore.CubicLaw(a=-1, b=10)"
        )
    return law
