"""Continuous piecewise-linear (PL) hardening–softening laws: the soft–hard–soft trilinear family.

A PL law has breakpoints b₁ < … < b_m and slopes (moduli) s₀, …, s_m: f′ = s_j on piece
j = (b_j, b_{j+1}) (b₀ = −∞, b_{m+1} = +∞), f continuous with f(0) = 0.  The paper's class (§2:
f′ > 0 around 0, f″ > 0 then f″ < 0) is read *in the sense of Φ′ = f*: f is convex then concave,
i.e. the slopes **strictly increase to one maximum regime, then strictly decrease**:

* f″ is the measure Σ_k J_k δ(w − b_k), J_k = s_k − s_{k−1}: J_k > 0 before the hard regime
  (hardening), J_k < 0 after it (softening).  The maximum-slope ("hard") regime H = [w₁, w₂]
  = [b_h, b_{h+1}] is bounded (both hardening and softening present) and plays the role of the
  cubic's inflection w*: f is convex on (−∞, w₂] and concave on [w₁, ∞), f″ = 0 inside H.
  ``w_star`` is the midpoint (w₁ + w₂)/2 — the centre (w₊ + w₋)/2 of the superkinks in their
  bifurcation limit (w₊, w₋) → (w₁, w₂) (fpucore.qc.piecewise), as w* is for the cubic (eq.
  cubic_cond1) — and c_max = √f′(w*) = √s_h.  ``hard_regime`` = (w₁, w₂).
* **the origin lies strictly inside a soft regime before H** (0 < w₁, the analogue of the paper's
  0 < w*, and 0 not at a breakpoint, so f′(0) is defined): for the trilinear law, inside the
  first regime, f(w) = E₁ w for w ≤ w₁.  f′(0) = s(0) > 0 is the paper's class; f′(0) = 0 (a
  zero-modulus first regime, E₁ = 0) is accepted as the degenerate case of the companion study
  (arXiv 2406.06437): the unstrained chain is then a soundless state (c₊ = 0, any V > 0 is
  supersonic) on which compact discrete solitary waves travel (fpucore.wave.compact).
* moduli are ≥ 0 (a negative modulus makes Φ non-convex: phase transitions, outside the class);
  a zero modulus can only be the first or the last (unimodality).
* (α, β) is where f′ > 0 (Φ strictly convex): α = −∞ unless s₀ = 0 (then α = b₁), β = +∞ unless
  s_m = 0 (then β = b_m).  Unlike a polynomial, a PL law needs no finite β to soften: superkinks
  exist because s_m < s_h (equal-area condition, fpucore.qc.piecewise).

Numba handle (law id ``LAW_PWL`` of :mod:`.kernels`): p = [m, b₁…b_m, s₀…s_m, f(b₁)…f(b_m)];
piece j ≥ 1 is evaluated from its left breakpoint, f = f(b_j) + s_j (w − b_j), piece 0 from b₁
(anchored values instead of intercepts: f is then continuous at every breakpoint to rounding
of one product, and exactly 0 on a zero-modulus piece).  A point on a breakpoint belongs to the
piece on its right.  f″ is 0 away from the breakpoints (the Dirac masses are what integrators
must locate: event location at breakpoints).

Text form (parse-only, no eval; :func:`fpucore.law.piecewise_text.law_from_piecewise_text`)::

    trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)
    piecewise(breakpoints=[0.5, 1.5, 3], slopes=[1, 4, 0.5, 0.1])
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from fpucore.errors import ParameterError, require_finite
from fpucore.law.base import HardeningSofteningLaw
from fpucore.law.kernels import LAW_PWL
from fpucore.law.scale import COEFF_RANGE, require_computable

MAX_PIECES = 64  # the kernels scan the breakpoints linearly: a few are the use case


def _fmt(x: float) -> str:
    return repr(float(x))


class _PiecewiseTables(HardeningSofteningLaw):
    """Evaluation shared by the PL laws from the tables ``_b`` (breakpoints), ``_s`` (slopes),
    ``_fb`` (f at breakpoints), ``_phib`` (Φ at breakpoints), set by ``_build``."""

    # set by ``_build`` (declared as fields by the dataclass subclasses)
    _b: np.ndarray
    _s: np.ndarray
    _fb: np.ndarray
    _phib: np.ndarray
    _h: int

    @property
    def expression(self) -> str:  # pragma: no cover - abstract
        raise NotImplementedError

    def _build(self, b: np.ndarray, s: np.ndarray) -> None:
        set_ = object.__setattr__
        m = b.size
        fb = np.empty(m)
        # f(b_k) from the piece containing 0 outward (f(0) = 0): sums of slope × length
        j0 = int(np.searchsorted(b, 0.0, side="right"))
        k0 = max(j0, 1) - 1  # anchor breakpoint of the piece containing 0
        fb[k0] = s[j0] * b[k0]
        for k in range(k0 + 1, m):
            fb[k] = fb[k - 1] + s[k] * (b[k] - b[k - 1])
        for k in range(k0 - 1, -1, -1):
            fb[k] = fb[k + 1] - s[k + 1] * (b[k + 1] - b[k])
        phib = np.empty(m)
        phib[k0] = 0.5 * fb[k0] * b[k0]  # ∫₀^{b_k0} f, f linear on [0, b_k0] with f(0) = 0
        for k in range(k0 + 1, m):
            phib[k] = phib[k - 1] + 0.5 * (fb[k - 1] + fb[k]) * (b[k] - b[k - 1])
        for k in range(k0 - 1, -1, -1):
            phib[k] = phib[k + 1] - 0.5 * (fb[k + 1] + fb[k]) * (b[k + 1] - b[k])
        h = int(np.argmax(s))
        for name, val in (("_b", b), ("_s", s), ("_fb", fb), ("_phib", phib)):
            val.flags.writeable = False
            set_(self, name, val)
        set_(self, "law_id", LAW_PWL)
        set_(self, "_h", h)

    # ----- kernel handle
    @property
    def params(self) -> np.ndarray:
        """[m, b₁…b_m, s₀…s_m, f(b₁)…f(b_m)] (float64), the ``p`` of the LAW_PWL kernels."""
        return np.concatenate(([float(self._b.size)], self._b, self._s, self._fb))

    # ----- structure
    @property
    def breakpoints(self) -> tuple[float, ...]:
        return tuple(float(x) for x in self._b)

    @property
    def slopes(self) -> tuple[float, ...]:
        return tuple(float(x) for x in self._s)

    @property
    def hard_regime(self) -> tuple[float, float]:
        """(w₁, w₂): the maximum-slope regime, the PL analogue of the inflection w*."""
        return float(self._b[self._h - 1]), float(self._b[self._h])

    @property
    def w_star(self) -> float:
        """Midpoint of the hard regime (module docstring): f′(w*) = max slope."""
        w1, w2 = self.hard_regime
        return 0.5 * (w1 + w2)

    @property
    def c_max(self) -> float:
        return math.sqrt(float(self._s[self._h]))

    @property
    def alpha(self) -> float:
        return -math.inf if self._s[0] > 0 else float(self._b[0])

    @property
    def beta(self) -> float:
        return math.inf if self._s[-1] > 0 else float(self._b[-1])

    @property
    def degenerate(self) -> bool:
        """A zero-modulus first or last regime (the companion study's degenerate case)."""
        return bool(self._s[0] == 0.0 or self._s[-1] == 0.0)

    def piece(self, w):
        """Index j of the piece containing w (a breakpoint belongs to the piece on its right)."""
        return np.searchsorted(self._b, np.asarray(w, dtype=float), side="right")

    # ----- vectorised evaluation
    def _anchor(self, w):
        w = np.asarray(w, dtype=float)
        j = self.piece(w)
        k = np.maximum(j, 1) - 1
        return w, j, k

    def f(self, w):
        w, j, k = self._anchor(w)
        return self._fb[k] + self._s[j] * (w - self._b[k])

    def df(self, w):
        """f′(w); on a breakpoint the slope on its right."""
        return self._s[self.piece(w)] + 0.0 * np.asarray(w, dtype=float)

    def ddf(self, w):
        """f″ away from the breakpoints: 0 (its Dirac masses J_k δ(w − b_k) are not a function)."""
        return np.zeros_like(np.asarray(w, dtype=float))

    def phi(self, w):
        """Φ(w) = ∫₀ʷ f, exact: Φ(b_k) + f(b_k)(w − b_k) + s_j (w − b_k)²/2."""
        w, j, k = self._anchor(w)
        d = w - self._b[k]
        return self._phib[k] + self._fb[k] * d + 0.5 * self._s[j] * d * d

    def require_convex(self, name: str, w: float) -> float:
        w = require_finite(name, w)
        if not (self.alpha < w < self.beta):
            raise ParameterError(
                name,
                w,
                f"(alpha, beta) = ({self.alpha:.10g}, {self.beta:.10g})",
                "strain must lie where f'(w) > 0 (outside the zero-modulus regime)",
            )
        return w

    def describe(self) -> str:
        return "f piecewise linear: " + self.expression

    def _validate_common(self, b: np.ndarray, s: np.ndarray, bname: str, sname) -> None:
        """Class checks shared by both constructors; ``sname(k)`` names slope k."""
        m = b.size
        for k in range(1, m):
            if not b[k] > b[k - 1]:
                raise ParameterError(
                    bname,
                    tuple(float(x) for x in b),
                    "strictly increasing breakpoints",
                    f"breakpoint {k + 1} ({b[k]:.10g}) is not above breakpoint {k} "
                    f"({b[k - 1]:.10g})",
                )
        for k, sk in enumerate(s):
            if sk < 0:
                raise ParameterError(
                    sname(k),
                    float(sk),
                    "a modulus >= 0",
                    "a negative modulus makes the potential non-convex (phase transitions are "
                    "outside the hardening-softening class)",
                )
            if sk != 0 and not COEFF_RANGE[0] <= sk <= COEFF_RANGE[1]:
                raise ParameterError(
                    sname(k),
                    float(sk),
                    f"0 or [{COEFF_RANGE[0]:g}, {COEFF_RANGE[1]:g}]",
                    "outside this range the closed forms overflow or underflow",
                )
        h = int(np.argmax(s))
        for k in range(1, m + 1):
            up = k <= h
            if (s[k] > s[k - 1]) != up or s[k] == s[k - 1]:
                raise ParameterError(
                    sname(k),
                    float(s[k]),
                    f"{'>' if up else '<'} {sname(k - 1)} = {s[k - 1]:.10g}",
                    "the slopes must strictly increase to one maximum (hard) regime and then "
                    "strictly decrease: f convex then concave (hardening then softening)",
                )
        if h == 0 or h == m:
            raise ParameterError(
                sname(h),
                float(s[h]),
                "a maximum slope on a bounded (middle) regime",
                "the stiffest regime is unbounded: "
                + ("no hardening" if h == 0 else "no softening")
                + ", so no superkink exists",
            )
        if not b[h - 1] > 0:
            raise ParameterError(
                bname,
                tuple(float(x) for x in b),
                f"the hard regime starting above 0 (it starts at {b[h - 1]:.10g})",
                "the origin must lie in a soft regime before the "
                "hard one (the paper's 0 < w*: hardening at w = 0)",
            )
        if np.any(b == 0.0):
            raise ParameterError(
                bname,
                tuple(float(x) for x in b),
                "breakpoints != 0",
                "the origin must lie inside a regime, where f'(0) is defined",
            )
        W = float(np.max(np.abs(b)))
        w_star = 0.5 * (b[h - 1] + b[h])
        require_computable(
            bname, tuple(float(x) for x in b), -W, W, w_star, float(s[h]), "the largest slope"
        )


@dataclass(frozen=True)
class PiecewiseLinearLaw(_PiecewiseTables):
    """Any continuous PL law f with f(0) = 0, breakpoints b₁ < … < b_m (m ≥ 2) and slopes
    s₀ … s_m ≥ 0 that strictly increase to one bounded maximum regime, then strictly decrease
    (module docstring).  Refused with :class:`ParameterError` otherwise."""

    breakpoints: tuple = (0.5, 1.5)
    slopes: tuple = (1.0, 4.0, 0.2)
    _b: np.ndarray = field(init=False, repr=False, compare=False)
    _s: np.ndarray = field(init=False, repr=False, compare=False)
    _fb: np.ndarray = field(init=False, repr=False, compare=False)
    _phib: np.ndarray = field(init=False, repr=False, compare=False)
    _h: int = field(init=False, repr=False, compare=False, default=-1)

    def __post_init__(self):
        b = _seq("breakpoints", self.breakpoints, 2, MAX_PIECES)
        s = _seq("slopes", self.slopes, 1, MAX_PIECES + 1)
        if s.size != b.size + 1:
            raise ParameterError(
                "slopes",
                tuple(s.tolist()),
                f"{b.size + 1} slopes (one more than the {b.size} breakpoints)",
                "one modulus per regime",
            )
        self._validate_common(b, s, "breakpoints", lambda k: f"slopes[{k}]")
        object.__setattr__(self, "breakpoints", tuple(b.tolist()))
        object.__setattr__(self, "slopes", tuple(s.tolist()))
        self._build(b, s)

    def __hash__(self):
        return hash((type(self).__name__, self.breakpoints, self.slopes))

    def __eq__(self, other):
        return (
            isinstance(other, _PiecewiseTables)
            and self.breakpoints == other.breakpoints
            and self.slopes == other.slopes
        )

    @property
    def expression(self) -> str:
        bs = ", ".join(_fmt(x) for x in self.breakpoints)
        ss = ", ".join(_fmt(x) for x in self.slopes)
        return f"piecewise(breakpoints=[{bs}], slopes=[{ss}])"


@dataclass(frozen=True)
class TrilinearLaw(_PiecewiseTables):
    """Soft–hard–soft trilinear law: f = E₁w (w ≤ w₁), E₁w₁ + E₂(w − w₁) (w₁ ≤ w ≤ w₂),
    f(w₂) + E₃(w − w₂) (w ≥ w₂), with 0 < w₁ < w₂, E₂ > E₁ ≥ 0, E₂ > E₃ ≥ 0 (asymmetric
    allowed; E₁ = 0 or E₃ = 0 the degenerate zero-modulus cases)."""

    w1: float = 0.5
    w2: float = 1.5
    E1: float = 1.0
    E2: float = 4.0
    E3: float = 0.2
    _b: np.ndarray = field(init=False, repr=False, compare=False)
    _s: np.ndarray = field(init=False, repr=False, compare=False)
    _fb: np.ndarray = field(init=False, repr=False, compare=False)
    _phib: np.ndarray = field(init=False, repr=False, compare=False)
    _h: int = field(init=False, repr=False, compare=False, default=-1)

    def __post_init__(self):
        vals = {n: require_finite(n, getattr(self, n)) for n in ("w1", "w2", "E1", "E2", "E3")}
        for n, v in vals.items():
            object.__setattr__(self, n, v)
        w1, w2, E1, E2, E3 = (vals[n] for n in ("w1", "w2", "E1", "E2", "E3"))
        if not w1 > 0:
            raise ParameterError(
                "w1",
                w1,
                "w1 > 0",
                "the origin lies inside the first (soft) regime: f(w) = E1 w "
                "for w <= w1, f'(0) = E1 (the paper's 0 < w*)",
            )
        if not w2 > w1:
            raise ParameterError("w2", w2, f"w2 > w1 = {w1:.10g}", "breakpoints must increase")
        for n, v in (("E1", E1), ("E3", E3)):
            if v < 0:
                raise ParameterError(
                    n,
                    v,
                    "E >= 0",
                    "a negative modulus makes the potential non-convex (phase "
                    "transitions are outside the hardening-softening class)",
                )
        if not E2 > max(E1, E3):
            which, v = ("E1", E1) if E1 >= E3 else ("E3", E3)
            raise ParameterError(
                "E2",
                E2,
                f"E2 > max(E1, E3) = {v:.10g}",
                f"the middle regime must be the hard one (stiffer than {which}): soft-hard-soft",
            )
        names = ("E1", "E2", "E3")
        self._validate_common(
            np.array([w1, w2]), np.array([E1, E2, E3]), "(w1, w2)", lambda k: names[k]
        )
        self._build(np.array([w1, w2]), np.array([E1, E2, E3]))

    @property
    def expression(self) -> str:
        return (
            f"trilinear(w1={_fmt(self.w1)}, w2={_fmt(self.w2)}, E1={_fmt(self.E1)}, "
            f"E2={_fmt(self.E2)}, E3={_fmt(self.E3)})"
        )

    def as_piecewise(self) -> PiecewiseLinearLaw:
        return PiecewiseLinearLaw((self.w1, self.w2), (self.E1, self.E2, self.E3))


def _seq(name: str, value, lo: int, hi: int) -> np.ndarray:
    try:
        raw = list(value)
    except TypeError:
        raise ParameterError(name, value, f"a sequence of {lo} to {hi} finite reals") from None
    if not lo <= len(raw) <= hi:
        raise ParameterError(name, tuple(raw), f"a sequence of {lo} to {hi} finite reals")
    return np.array([require_finite(f"{name}[{k}]", v) for k, v in enumerate(raw)], dtype=float)
