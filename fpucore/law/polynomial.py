"""Polynomial hardening–softening laws f(w) = Σ_{k≥1} c_k w^k (paper §2, hypotheses of §3).

:class:`PolynomialLaw` checks the hypotheses the paper places on f (§2, before eq. cubic):

* f(0) = 0 (no constant term — built in) and f′(0) = c_1 > 0;
* (α, β) ∋ 0 is the interval between the nearest zeros of f′ around 0, so f′ > 0 and Φ is
  convex there.  **β must be finite**: without a zero of f′ above 0 there is no softening branch,
  hence no superkink (eq. zero_G has no solution with w₋ in the convex interval), and the law is
  refused.  α may be −∞ (f′ > 0 for every w < 0); code needing a finite lower window must then
  search outward (``fpucore.qc.general`` does).
* exactly one inflection w* in (α, β), where f″ changes sign from + (hardening) to − (softening),
  and 0 < w* (the paper's ``0 < w_* < β``).  Two inflections, an f″ that touches zero without
  changing sign, or the wrong order of signs are refused.

Roots of f′ and f″ come from ``numpy.roots`` (companion-matrix eigenvalues) polished by Newton in
float64; each carries an error bound (last Newton step, or the round-off bound
eps·Σ|k c_k w^(k−1)|/|f″| at the root, whichever is larger).

The Numba kernels of :mod:`fpucore.law` evaluate the law through ``(law_id, params)`` with
``params[k−1] = c_k`` (Horner; one compiled kernel for every degree).

:func:`fpucore.law.law_from_expression` (module :mod:`.expression`) builds one from text.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

import numpy as np

from fpucore.errors import ParameterError, require_finite
from fpucore.law.base import HardeningSofteningLaw
from fpucore.law.kernels import LAW_POLY, POLY_IDS
from fpucore.law.scale import require_coefficient, require_computable

if TYPE_CHECKING:
    from fpucore.law.base import Strain

EPS = float(np.finfo(float).eps)


class CubicCoefficients(Protocol):
    """What :meth:`PolynomialLaw.from_cubic` reads of a cubic law (a CubicLaw; not imported
    here: cubic.py imports this module)."""

    a: float
    b: float


# The largest degree of a law (text or coefficients).  benchmarks/law_degree.py (families with a
# known convex interval, references by mpmath): beta, w*, the QC w- and the discrete wave and its
# Floquet spectrum stay accurate and converged at every degree tried up to 41 — accuracy follows
# the monomial basis' cancellation, not the degree — so the limit bounds the work instead: SymPy's
# exact expansion of the text and the kernels' O(degree) evaluation, far above the paper's laws.
MAX_DEGREE = 16
_FAST_IDS = {k: k for k in POLY_IDS if k != LAW_POLY}  # unrolled kernels: the id is the degree


# =============================================================================== real roots
def _polyval_asc(c: np.ndarray, x: float) -> tuple[float, float, float]:
    """(p(x), p′(x), Σ|c_k||x|^k) for ascending coefficients c (Horner)."""
    p = dp = s = 0.0
    ax = abs(x)
    for ck in c[::-1]:
        dp = dp * x + p
        p = p * x + ck
        s = s * ax + abs(ck)
    return p, dp, s


def real_roots(
    c: Sequence[float] | np.ndarray, lo: float = -math.inf, hi: float = math.inf
) -> list[tuple[float, float]]:
    """Real roots of Σ c[j] x^j in the open interval (lo, hi), sorted, as [(root, error), ...].

    Candidates are the eigenvalue roots with a small imaginary part; each is polished by Newton
    and kept only if |p(x)| is at round-off level there (a complex pair very close to the axis is
    then reported as a (near-)double real root, which is what f′/f″ sign checks need).
    """
    arr: np.ndarray = np.trim_zeros(np.asarray(c, dtype=float), "b")
    if arr.size <= 1:
        return []
    with np.errstate(all="ignore"):  # far roots may overflow p(x): kept unverified, see below
        return _real_roots(arr, lo, hi)


def _real_roots(c: np.ndarray, lo: float, hi: float) -> list[tuple[float, float]]:
    out: list[tuple[float, float]] = []
    for z in np.roots(c[::-1]):
        if abs(z.imag) > 1e-6 * max(1.0, abs(z)):
            continue
        x, step = float(z.real), math.inf
        for _ in range(8):  # Newton polish; quadratic convergence from the eigenvalue estimate
            p, dp, _s = _polyval_asc(c, x)
            if dp == 0.0:
                break
            step = p / dp
            x -= step
            if abs(step) <= 2 * EPS * abs(x):
                break
        p, dp, s = _polyval_asc(c, x)
        if not (math.isfinite(x) and math.isfinite(s)):  # p(x) overflows: no accuracy claimed
            if math.isfinite(z.real) and lo < z.real < hi:
                out.append((float(z.real), math.inf))
            continue
        if abs(p) > 256 * EPS * s:  # not a real root after all (complex pair off the axis)
            continue
        # round-off bound: simple root eps·s/|p′|; near-multiple root the √ form dominates
        dpp = _polyval_asc(np.arange(1, c.size) * c[1:], x)[1] if c.size > 2 else 0.0
        bound = 4 * EPS * s / abs(dp) if dp != 0.0 else math.inf
        if dpp != 0.0:
            bound = min(bound, math.sqrt(8 * EPS * s / abs(dpp)))
        err = max(abs(step) if math.isfinite(step) else 0.0, bound if math.isfinite(bound) else 0.0)
        if lo < x < hi:
            out.append((float(x), float(err)))
    out.sort()
    merged: list[tuple[float, float]] = []  # drop duplicates from a polished double root
    for x, e in out:
        if merged and abs(x - merged[-1][0]) <= max(e, merged[-1][1], 8 * EPS * abs(x)):
            merged[-1] = (0.5 * (x + merged[-1][0]), max(e, merged[-1][1], abs(x - merged[-1][0])))
        else:
            merged.append((x, e))
    return merged


def expression_of(coeffs: Sequence[float]) -> str:
    """Text of f(w) = Σ c_k w^k (coeffs = (c_1, c_2, …)) that
    :func:`fpucore.law.law_from_expression` parses back to the same doubles (coefficients by
    ``repr``) — also for coefficients outside the law class (e.g. a dashboard slider's state),
    for which no :class:`PolynomialLaw` exists; ``"0"`` when every coefficient is zero."""
    out = ""
    for k, c in enumerate(coeffs, start=1):
        c = float(c)
        if c == 0.0:
            continue
        mag = abs(c)
        term = "w" if k == 1 else f"w**{k}"
        term = term if mag == 1.0 else f"{mag!r}*{term}"
        out += (" - " if c < 0 else " + ") + term if out else ("-" if c < 0 else "") + term
    return out or "0"


# =============================================================================== the law
@dataclass(frozen=True)
class PolynomialLaw(HardeningSofteningLaw):
    """f(w) = Σ_{k≥1} c_k w^k with coeffs = (c_1, c_2, …) (trailing zeros dropped).

    Derived on construction (refused with :class:`ParameterError` if the hypotheses of paper §2
    fail, see the module docstring): ``alpha``, ``beta`` (zeros of f′ around 0, α may be −∞),
    ``w_star`` (the inflection), each with an ``*_error`` bound, and ``c_max`` = √f′(w*).
    """

    coeffs: tuple[float, ...] = (1.0, 10.0, -1.0)
    alpha: float = field(init=False, default=math.nan)
    beta: float = field(init=False, default=math.nan)
    w_star: float = field(init=False, default=math.nan)
    alpha_error: float = field(init=False, default=math.nan)
    beta_error: float = field(init=False, default=math.nan)
    w_star_error: float = field(init=False, default=math.nan)
    _c: np.ndarray = field(init=False, repr=False, compare=False, default=None)  # type: ignore[arg-type]  # set in __post_init__

    def __post_init__(self):
        try:
            raw = list(self.coeffs)
        except TypeError:
            raise ParameterError(
                "coeffs", self.coeffs, "a sequence (c_1, c_2, ...) of finite reals"
            ) from None
        c = [require_finite(f"c_{k}", v) for k, v in enumerate(raw, start=1)]
        while c and c[-1] == 0.0:
            c.pop()
        if len(c) > MAX_DEGREE:
            raise ParameterError(
                "coeffs",
                f"degree {len(c)}",
                f"degree <= {MAX_DEGREE}",
                "higher degrees lose accuracy in the monomial basis (benchmarks/law_degree.py)",
            )
        for k, ck in enumerate(c, start=1):
            require_coefficient(f"c_{k}", ck)
        if len(c) < 2:
            raise ParameterError(
                "coeffs",
                tuple(raw),
                "degree >= 2 (at least c_1, c_2)",
                "a linear law has no hardening or softening",
            )
        arr = np.array(c, dtype=float)
        set_ = object.__setattr__
        set_(self, "coeffs", tuple(c))
        set_(self, "_c", arr)
        set_(self, "law_id", _FAST_IDS.get(arr.size, LAW_POLY))
        if not c[0] > 0:
            raise ParameterError(
                "c_1",
                c[0],
                "c_1 = f'(0) > 0",
                "f'(0) must be positive: the unstrained chain "
                "must be stable (0 inside the convex interval (alpha, beta))",
            )
        dc = np.arange(1, arr.size + 1) * arr  # f′ ascending: Σ k c_k w^(k−1)
        ddc = np.arange(1, dc.size) * dc[1:]  # f″ ascending
        pos = real_roots(dc, 0.0, math.inf)
        neg = real_roots(dc, -math.inf, 0.0)
        if not pos:
            raise ParameterError(
                "coeffs",
                self.coeffs,
                "a law whose f' vanishes at some beta > 0",
                "no softening: f'(w) > 0 for every w > 0, so the convex interval has no upper end "
                "beta and no superkink exists (eq. zero_G needs the concave branch)",
            )
        beta, beta_err = pos[0]
        alpha, alpha_err = neg[-1] if neg else (-math.inf, 0.0)
        set_(self, "alpha", alpha)
        set_(self, "beta", beta)
        set_(self, "alpha_error", alpha_err)
        set_(self, "beta_error", beta_err)
        w_star, w_err = self._inflection(ddc, alpha, beta)
        set_(self, "w_star", w_star)
        set_(self, "w_star_error", w_err)
        c2 = float(self._horner(dc, np.asarray(w_star)))
        require_computable("coeffs", self.coeffs, alpha, beta, w_star, c2, "f'(w*)")

    def _inflection(self, ddc: np.ndarray, alpha: float, beta: float) -> tuple[float, float]:
        """The unique zero of f″ in (α, β) with f″ going from + to − (paper §2)."""
        interval = f"(alpha, beta) = ({alpha:.10g}, {beta:.10g})"
        zs = real_roots(ddc, alpha, beta)
        # signs of f″ on the pieces between consecutive zeros (midpoints; α = −∞ → a finite point)
        ends = [alpha if math.isfinite(alpha) else min(-1.0, 2.0 * (zs[0][0] if zs else 0.0) - 1)]
        ends += [z for z, _ in zs] + [beta]
        signs = [np.sign(_polyval_asc(ddc, 0.5 * (a + b))[0]) for a, b in zip(ends[:-1], ends[1:])]
        if len(zs) == 0:
            what = "hardening only (f'' > 0)" if signs[0] > 0 else "softening only (f'' < 0)"
            raise ParameterError(
                "coeffs",
                self.coeffs,
                f"exactly one inflection w* in {interval}",
                f"f'' has no zero in the convex interval: {what}; a hardening-softening law needs "
                "f'' > 0 on (alpha, w*) and f'' < 0 on (w*, beta)",
            )
        if len(zs) >= 2:
            where = ", ".join(f"{z:.10g}" for z, _ in zs)
            raise ParameterError(
                "coeffs",
                self.coeffs,
                f"exactly one inflection w* in {interval}",
                f"f'' has {len(zs)} zeros in the convex interval (at w = {where}): two or more "
                "inflections; the law must change from hardening to softening exactly once",
            )
        (z, zerr), (s0, s1) = zs[0], signs
        if s0 == s1:
            raise ParameterError(
                "coeffs",
                self.coeffs,
                f"exactly one inflection w* in {interval}",
                f"f'' touches zero at w = {z:.10g} without changing sign: no inflection",
            )
        if s0 < 0:
            raise ParameterError(
                "coeffs",
                self.coeffs,
                "f'' > 0 on (alpha, w*) and f'' < 0 on (w*, beta)",
                f"f'' changes from - to + at w = {z:.10g}: softening-hardening, not "
                "hardening-softening",
            )
        if not z > 0:
            raise ParameterError(
                "w_star",
                z,
                f"0 < w* < beta = {beta:.10g}",
                "the inflection must lie at positive strain (hardening at w = 0, paper §2)",
            )
        return z, zerr

    # ----- kernel handle
    @property
    def params(self) -> np.ndarray:
        """(c_1, …, c_n) as float64, the ``p`` of the LAW_POLY kernels."""
        return self._c.copy()

    @property
    def degree(self) -> int:
        return self._c.size

    @classmethod
    def from_cubic(cls, law: CubicCoefficients) -> PolynomialLaw:
        """The cubic a w³ + b w² + w (eq. cubic) as coeffs (1, b, a)."""
        return cls((1.0, law.b, law.a))

    # ----- vectorised evaluation (Horner; derivative/integral coefficients computed once)
    @functools.cached_property
    def _tables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        c = self._c
        k = np.arange(2, c.size + 1)
        return np.arange(1, c.size + 1) * c, k * (k - 1) * c[1:], c / np.arange(2, c.size + 2)

    @staticmethod
    def _horner(c: np.ndarray, w: np.ndarray) -> np.ndarray:
        acc = np.full_like(w, c[-1])
        for ck in c[-2::-1]:
            acc = acc * w + ck
        return acc

    @functools.cached_property
    def scalar_tables(self) -> tuple[tuple[float, ...], ...]:
        """Coefficients of f/w, f′, f″ as tuples of Python floats, highest power first (for
        :meth:`df_scalar` / :meth:`ddf_scalar`: root finders call them thousands of times)."""
        return tuple(tuple(float(x) for x in c[::-1]) for c in (self._c,) + self._tables[:2])

    def df_scalar(self, w: float) -> float:
        """f′(w) for one float, without NumPy overhead (same Horner order as :meth:`df`)."""
        acc = 0.0
        for c in self.scalar_tables[1]:
            acc = acc * w + c
        return acc

    def ddf_scalar(self, w: float) -> float:
        """f″(w) for one float, without NumPy overhead."""
        acc = 0.0
        for c in self.scalar_tables[2]:
            acc = acc * w + c
        return acc

    def f(self, w: Strain) -> Strain:
        """f(w) = w Σ c_k w^(k−1)."""
        w = np.asarray(w, dtype=float)
        return self._horner(self._c, w) * w

    def df(self, w: Strain) -> Strain:
        """f′(w) = Σ k c_k w^(k−1)."""
        return self._horner(self._tables[0], np.asarray(w, dtype=float))

    def ddf(self, w: Strain) -> Strain:
        """f″(w) = Σ k (k−1) c_k w^(k−2)."""
        return self._horner(self._tables[1], np.asarray(w, dtype=float))

    def phi(self, w: Strain) -> Strain:
        """Potential Φ(w) = ∫₀ʷ f = Σ c_k w^(k+1)/(k+1)."""
        w = np.asarray(w, dtype=float)
        return self._horner(self._tables[2], w) * w * w

    @property
    def expression(self) -> str:
        """The law as text that :func:`fpucore.law.law_from_expression` parses back exactly
        (coefficients by ``repr``, so the round trip is lossless), e.g. ``"w + 10*w**2 - w**3"``."""
        return expression_of(self.coeffs)

    def describe(self) -> str:
        terms = [f"{c:+g} w^{k}" if k > 1 else f"{c:+g} w" for k, c in enumerate(self.coeffs, 1)]
        return "f(w) = " + " ".join(t for t, c in zip(terms, self.coeffs) if c != 0.0)
