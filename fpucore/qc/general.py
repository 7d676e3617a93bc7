"""QC superkinks and solitary waves for ANY hardening–softening law, numerically (paper §3).

The cubic closed forms of :mod:`fpucore.qc` (§4) are replaced by root finding and quadrature on
``law.f / df / ddf`` and the constants ``alpha, beta, w_star`` — so any
:class:`~fpucore.law.HardeningSofteningLaw` works (e.g. :class:`fpucore.law.PolynomialLaw`).

Cancellation-free forms (Taylor with integral remainder; inner integrals over t ∈ [0, 1] by
Gauss–Legendre, exact for polynomial laws)::

    Rayleigh slope   S(a, w) = (f(w) − f(a))/(w − a)       = ∫₀¹ f′(a + t d) dt          (eq. Rline)
    driving force    G = Φ(w₊) − Φ(w₋) − ½(w₊ − w₋)(f₊ + f₋) = ½ Δ³ ∫₀¹ t(1−t) f″(w₊ + tΔ) dt
                                                                                        (eq. zero_G)
    tangency         S(w₊, w) − f′(w) = −d ∫₀¹ t f″(w₊ + t d) dt                   (eq. cminus)
    first integral   G_B(w) = d² J,  J = ∫₀¹ (1−t)(f′(w_B + t d) − V²) dt          (eq. TW_QC_gen3)

with d = w − a (or w − w₊, w − w_B), Δ = w₋ − w₊.  The trivial roots d = 0 are divided out, so
every root below is simple and bracketed (scipy brentq), with an error bar = max(width of the
sign-change bracket actually found around the root, |F(x)|/|F′(x)|).

Profiles come from ξ(w) = ∫ dw / w′(w) (eq. TW_QC_gen3) by QUADRATURE after a substitution that
removes both endpoint singularities:

* superkink: w = w_mid − (Δ/2) tanh s gives dξ/ds = 2/(k|Δ|√Q(w)), k = √24/|V|,
  −G = (w−w₊)²(w₋−w)² Q(w) with Q > 0 smooth (for the cubic Q = |a|/4 and s = pξ exactly);
* solitary wave: w = w_B + (w_M − w_B) sech²u gives dξ/du = 2/(k √|w_M − w_B| √|R̃(w)|),
  −G_B = (w − w_B)²(w_M − w) R̃(w) with R̃ smooth and non-zero (the log singularity at w_B and
  the square-root singularity at the turning point w_M are both absorbed).

ξ(s) is tabulated by composite Gauss–Legendre (24 and 16 nodes per panel: their difference is the
error bar) and inverted by safeguarded Newton; E_ren^QC (eq. Eren_QC) uses the first integral to
reduce the integrand to (V² w_B + f(w_B)) (w − w_B) + V² (w − w_B)² (as in fpucore.qc) and the same
substitution.  Results mirror :class:`fpucore.qc.QCSuperkink` / :class:`fpucore.qc.QCSolitary`.

Caveat: with the tanh substitution the superkink is centred at w(0) = (w₊ + w₋)/2, which equals
w* only for the cubic (eq. cubic_cond1); in general w₊ + w₋ ≠ 2w*.
"""

from __future__ import annotations

import bisect
import functools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np
from scipy.optimize import brentq

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.law import CubicLaw, HardeningSofteningLaw, PolynomialLaw
from fpucore.qc.closed_forms import (
    QC_CHECK,
    QCSolitary,
    QCSuperkink,
    first_integral,
    first_integral_residual,
    require_V,
    require_w_plus,
)
from fpucore.result import Result, status_of

__all__ = [
    "QCSpeeds", "QCSuperkinkGeneral", "QCSolitaryGeneral", "speeds", "sound_speeds",
    "w_minus_from_w_plus", "w_minus_sonic", "rayleigh_roots", "w_S", "solitary_intervals",
    "superkink_w_plus_range", "superkink_velocity_bounds", "superkink_from_w_plus",
    "superkink_from_V", "solitary", "first_integral",
]  # fmt: skip

EPS = float(np.finfo(float).eps)
_GL_HI, _GL_LO = 24, 16  # outer quadrature (ξ tables, energy): value and error-bar orders
_U_MAX = 22.0  # sech²(22) ≈ 3e-19: beyond it the substituted integrands are at their limit
_K_INV = 17  # Chebyshev–Lobatto points per panel for the inverse map s(ξ)
_SQ = math.asinh(1.0)  # sech²u = 1/2 here: switch between the two expansions of R̃


@functools.cache
def _gl01(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [0, 1] (cached, read-only: computing them dominated
    the cost of a solitary wave)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    x.flags.writeable = w.flags.writeable = False
    return x, w


def _inner(law: HardeningSofteningLaw) -> tuple[np.ndarray, np.ndarray]:
    """Nodes for the t-integrals: exact for a polynomial law (integrands have degree ≤ n),
    32 nodes otherwise (spectrally accurate for analytic f)."""
    if isinstance(law, PolynomialLaw):
        return _gl01(law.degree // 2 + 2)
    return _gl01(3 if isinstance(law, CubicLaw) else 32)


# =============================================================================== integrals
def _slope(law, a, d):
    """S = ∫₀¹ f′(a + t d) dt = (f(a+d) − f(a))/d (eq. Rline chord slope; f′(a) at d = 0)."""
    t, wt = _inner(law)
    a, d = np.asarray(a, float), np.asarray(d, float)
    return np.sum(law.df(a[..., None] + t * d[..., None]) * wt, axis=-1)


def _J(law, a, d, V2):
    """J = G_a(a + d)/d² = ∫₀¹ (1−t)(f′(a + t d) − V²) dt (eq. TW_QC_gen3 without its double
    zero at w = a; = (f′(a) − V²)/2 at d = 0)."""
    t, wt = _inner(law)
    a, d = np.asarray(a, float), np.asarray(d, float)
    return np.sum((1.0 - t) * (law.df(a[..., None] + t * d[..., None]) - V2) * wt, axis=-1)


@functools.cache
def _inner_py(law: HardeningSofteningLaw) -> tuple[tuple[float, float], ...]:
    """:func:`_inner` as (node, weight) pairs of Python floats (scalar integrands)."""
    t, wt = _inner(law)
    return tuple(zip(t.tolist(), wt.tolist()))


def _scalar_slope(law, a: float, d: float) -> float:
    """:func:`_slope` for one (a, d): pure Python for a polynomial law (root finding)."""
    if not isinstance(law, PolynomialLaw):
        return float(_slope(law, a, d))
    return sum(wk * law.df_scalar(a + tk * d) for tk, wk in _inner_py(law))


def _df1(law, w: float) -> float:
    """f′(w) for one float (pure Python for a polynomial law)."""
    return law.df_scalar(w) if isinstance(law, PolynomialLaw) else float(law.df(w))


def _scalar_J(law, a: float, d: float, V2: float) -> float:
    """:func:`_J` for one (a, d)."""
    if not isinstance(law, PolynomialLaw):
        return float(_J(law, a, d, V2))
    return sum(wk * (1.0 - tk) * (law.df_scalar(a + tk * d) - V2) for tk, wk in _inner_py(law))


def _area(law, a, d):
    """∫₀¹ t(1−t) f″(a + t d) dt: the driving force of eq. zero_G is G = ½ d³ × this."""
    if isinstance(law, PolynomialLaw):  # scalar path: called thousands of times by the roots
        return sum(wk * tk * (1.0 - tk) * law.ddf_scalar(a + tk * d) for tk, wk in _inner_py(law))
    t, wt = _inner(law)
    return float(np.sum(t * (1.0 - t) * law.ddf(a + t * d) * wt))


def _tangency(law, a, d):
    """∫₀¹ t f″(a + t d) dt = (f′(a+d) − S)/d: zero where the line from (a, f(a)) touches f."""
    if isinstance(law, PolynomialLaw):
        return sum(wk * tk * law.ddf_scalar(a + tk * d) for tk, wk in _inner_py(law))
    t, wt = _inner(law)
    return float(np.sum(t * law.ddf(a + t * d) * wt))


# =============================================================================== roots
def _root(F: Callable[[float], float], a: float, b: float) -> tuple[float, float]:
    """Root of F in [a, b] (F(a), F(b) of opposite signs) and its error bar: the larger of the
    half-width of the smallest sign-change bracket found around it and |F(x)|/|F′(x)|."""
    fa, fb = F(a), F(b)
    if fa == 0.0:
        return a, 0.0
    if fb == 0.0:
        return b, 0.0
    scale = max(abs(a), abs(b))
    x = brentq(F, a, b, xtol=EPS * scale, rtol=4 * EPS, maxiter=400)
    lo, hi = min(a, b), max(a, b)
    d = 2 * EPS * max(abs(x), EPS * scale)
    fx = F(x)
    for _ in range(80):
        fl, fr = F(max(lo, x - d)), F(min(hi, x + d))
        if fl == 0 or fr == 0 or (fl < 0) != (fr < 0):
            break
        d *= 2.0
    slope = (fr - fl) / (min(hi, x + d) - max(lo, x - d))
    resid = abs(fx / slope) if slope != 0 else d
    return x, max(d, resid)


def _outward(F, x0: float, direction: float, h0: float, n: int = 120):
    """March x0 + direction·h0·(1.6^k − 1)/0.6 until F changes sign w.r.t. F(x0); the bracket
    or None.  Used beyond (α, β) and when α = −∞ (no finite end to bracket against)."""
    f0, x_prev, h, x = F(x0), x0, h0, x0
    for _ in range(n):
        x = x + direction * h
        fx = F(x)
        if not math.isfinite(fx):
            return None
        if (fx < 0) != (f0 < 0) or fx == 0:
            return (x_prev, x)
        x_prev, h = x, h * 1.6
    return None


def _bracket_to_end(F, x0: float, end: float, direction: float, h0: float):
    """Sign-change bracket of F from x0 toward ``end`` (α or β, possibly infinite), then beyond."""
    f0 = F(x0)
    if math.isfinite(end):
        fe = F(end)
        if (fe < 0) != (f0 < 0) or fe == 0:
            return (x0, end)
        return _outward(F, end, direction, h0)
    return _outward(F, x0, direction, h0)


# =============================================================================== validation
def _dir(law, w_plus: float) -> float:
    """+1 on the lower branch (w₊ < w*, partner w₋ > w*), −1 on the upper branch."""
    return 1.0 if w_plus < law.w_star else -1.0


def _far_end(law, s: float) -> float:
    return law.beta if s > 0 else law.alpha


# =============================================================================== speeds
@dataclass(frozen=True)
class QCSpeeds(Result):
    """c₊ (eq. cplus), V_SK with its partner w₋ (eqs. Rline, zero_G), w₋ˢ and c₋ (eq. cminus),
    each with an error bar (absolute)."""

    w_plus: float
    c_plus: float
    V_SK: float
    c_minus: float
    w_minus: float
    w_minus_sonic: float
    c_plus_error: float
    V_SK_error: float
    c_minus_error: float
    w_minus_error: float
    w_minus_sonic_error: float
    elapsed_s: float

    ERROR_FIELDS: ClassVar = (
        "c_plus_error", "V_SK_error", "c_minus_error", "w_minus_error", "w_minus_sonic_error",
    )  # fmt: skip
    DERIVED: ClassVar = ("converged", "status", "message")

    @property
    def converged(self) -> bool:
        """Roots found with error bars at round-off level (relative 1e-9)."""
        errs = (self.V_SK_error / self.V_SK, self.w_minus_error / max(1.0, abs(self.w_minus)))
        return bool(all(math.isfinite(e) and e <= QC_CHECK for e in errs))

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "root error bars above 1e-9"


def _partner(law, w_plus: float):
    """(w₋, error) on the far side of w* with ∫₀¹ t(1−t) f″(w₊ + tΔ) dt = 0, or None when the
    root would lie beyond α/β (no validation: also used at the ends of the superkink range)."""
    s = _dir(law, w_plus)
    F = lambda w: _area(law, w_plus, w - w_plus)  # noqa: E731
    end = _far_end(law, s)
    br = _bracket_to_end(F, law.w_star, end, s, max(abs(law.w_star - w_plus), 1e-3))
    if br is None or (math.isfinite(end) and s * (max(br, key=lambda x: s * x) - end) > 0):
        return None
    return _root(F, *br)


def w_minus_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float]:
    """(w₋, error): the equal-area partner of w₊ (eq. zero_G with eq. Rline), the zero of
    ∫₀¹ t(1−t) f″(w₊ + tΔ) dt with w₋ on the other side of w*, inside (α, β)."""
    w_plus = require_w_plus(law, w_plus)
    r = _partner(law, w_plus)
    if r is None:
        lo, hi = superkink_w_plus_range(law, "lower" if w_plus < law.w_star else "upper")
        raise ParameterError(
            "w_plus", w_plus, fmt_interval(lo, hi),
            "the equal-area partner w- would leave the convex interval (alpha, beta): no superkink",
        )  # fmt: skip
    return r


def w_minus_sonic(law: HardeningSofteningLaw, w_plus: float, with_error: bool = False):
    """w₋ˢ ≠ w₊ where the line from (w₊, f(w₊)) touches f (eq. cminus; note the paper's typo: the
    slope there is f′(w₋ˢ)).  Zero of ∫₀¹ t f″(w₊ + t d) dt on the far side of w*."""
    w_plus = require_w_plus(law, w_plus)
    s = _dir(law, w_plus)
    F = lambda w: _tangency(law, w_plus, w - w_plus)  # noqa: E731
    br = _bracket_to_end(F, law.w_star, _far_end(law, s), s, abs(law.w_star - w_plus))
    x, err = _root(F, *br)  # always exists: f′(β) = 0 < chord slope (paper §3)
    return (x, err) if with_error else x


def speeds(law: HardeningSofteningLaw, w_plus: float) -> QCSpeeds:
    """All speeds for the state w₊ ahead, with error bars; c₊ < V_SK < c₋ for w₊ ≠ w*."""
    t0 = time.perf_counter()
    w_plus = require_w_plus(law, w_plus)
    wm, wm_err = w_minus_from_w_plus(law, w_plus)
    ws, ws_err = w_minus_sonic(law, w_plus, with_error=True)
    cp = math.sqrt(float(law.df(w_plus)))
    V2 = float(_slope(law, w_plus, wm - w_plus))
    V = math.sqrt(V2)
    dV2 = abs(float(law.df(wm)) - V2) / abs(wm - w_plus) * wm_err  # ∂S/∂w₋ · δw₋
    cm = math.sqrt(float(law.df(ws)))
    return QCSpeeds(
        w_plus, cp, V, cm, wm, ws,
        4 * EPS * cp, dV2 / (2 * V) + 8 * EPS * V,
        abs(float(law.ddf(ws))) * ws_err / (2 * cm) + 8 * EPS * cm, wm_err, ws_err,
        time.perf_counter() - t0,
    )  # fmt: skip


def sound_speeds(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float, float]:
    """(c₊, V_SK, c₋) as in :func:`fpucore.qc.sound_speeds`."""
    sp = speeds(law, w_plus)
    return sp.c_plus, sp.V_SK, sp.c_minus


def solitary_intervals(law: HardeningSofteningLaw, w_plus: float):
    """((c₊, V_SK), (V_SK, c₋)): velocity intervals of the solitary waves for w₊ (eq. wB)."""
    cp, vsk, cm = sound_speeds(law, w_plus)
    return (cp, vsk), (vsk, cm)


# =============================================================================== superkink range
@functools.lru_cache(maxsize=256)  # a property of the law (laws are frozen, hashable)
def superkink_w_plus_range(law: HardeningSofteningLaw, branch: str = "lower"):
    """Open w₊-interval of superkinks on a branch: (w₊_min, w*) ("lower") or (w*, w₊_max)
    ("upper"); its outer end is α (β) or the w₊ whose partner w₋ reaches β (α)."""
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    s = 1.0 if branch == "lower" else -1.0
    near, far = law.w_star, _far_end(law, s)  # far: where w₋ may go
    own = _far_end(law, -s)  # own end: where w₊ may go
    if not math.isfinite(far):
        return (own, near) if s > 0 else (near, own)
    K = lambda wp: _area(law, wp, far - wp)  # noqa: E731
    br = _bracket_to_end(K, near, own, -s, abs(far - near))
    x = _root(K, *br)[0] if br is not None else own
    if math.isfinite(own) and s * (own - x) > 0:  # root beyond α/β: the w₊ end binds
        x = own
    return (x, near) if s > 0 else (near, x)


def _V_SK(law, w_plus: float) -> float:
    """V_SK(w₊) without validation: c_max at w*, the limiting chord at the range ends."""
    if abs(w_plus - law.w_star) <= 4 * EPS * max(1.0, abs(law.w_star)):
        return law.c_max
    r = _partner(law, w_plus)
    wm = r[0] if r is not None else _far_end(law, _dir(law, w_plus))
    return math.sqrt(_scalar_slope(law, w_plus, wm - w_plus))


@functools.lru_cache(maxsize=256)
def superkink_velocity_bounds(law: HardeningSofteningLaw, branch: str = "lower"):
    """(V_lo, V_hi = c_max) of superkinks on a branch (eq. V_bounds_cubic for the cubic, where
    both branches agree; for a general law they differ).  V_lo is V_SK at the outer end of
    :func:`superkink_w_plus_range` (NaN if that end is −∞)."""
    lo, hi = superkink_w_plus_range(law, branch)
    end = lo if branch == "lower" else hi
    return (_V_SK(law, end) if math.isfinite(end) else math.nan), law.c_max


# =============================================================================== ξ(s) tables
@functools.cache
def _cheb_tables(K: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chebyshev–Lobatto points t on [0, 1], their barycentric weights, and the matrix S with
    ∫₀^{t_k} p = Σ_m S[k, m] p(t_m) for the interpolant p of degree K − 1 (spectral integration)."""
    k = np.arange(K)
    t = 0.5 * (1.0 - np.cos(np.pi * k / (K - 1)))
    bw = (-1.0) ** k
    bw[0] *= 0.5
    bw[-1] *= 0.5
    S = np.empty((K, K))
    for m in range(K):  # integrate the m-th Lagrange basis polynomial
        c = np.polynomial.chebyshev.chebfit(2 * t - 1, np.eye(K)[m], K - 1)
        ci = np.polynomial.chebyshev.chebint(c, lbnd=-1)
        S[:, m] = 0.5 * np.polynomial.chebyshev.chebval(2 * t - 1, ci)
    for a in (t, bw, S):
        a.flags.writeable = False
    return t, bw, S


class _Map:
    """ξ(s) = scale ∫₀ˢ g for s on the panel edges ``e`` (0 first, increasing |s|), for a smooth
    g > 0 that is constant beyond the last edge; vectorised inversion s(ξ).

    Edges: composite Gauss–Legendre (``_GL_HI`` nodes; ``_GL_LO`` for the error bar).  Inversion:
    on each panel, g at ``_K_INV`` Chebyshev–Lobatto points is integrated spectrally to ξ at those
    points (the end value checked against the Gauss–Legendre edge: the difference enters ``err``),
    and s(ξ) is interpolated through them (barycentric, in ξ).  The inverse-interpolation error is
    measured halfway between the nodes and also enters ``err``; where either exceeds round-off,
    s_of polishes by Newton on the quadrature.  Built on first use (families need only the edges).
    """

    def __init__(self, g: Callable[[np.ndarray], np.ndarray], scale: float, edges: np.ndarray):
        self.g, self.scale, self.e = g, scale, edges
        xh, wh = _gl01(_GL_HI)
        xl, wl = _gl01(_GL_LO)
        a, b = edges[:-1], edges[1:]
        h = (b - a)[:, None]
        hi = np.sum(g(a[:, None] + h * xh) * wh * h, axis=1)
        lo = np.sum(g(a[:, None] + h * xl) * wl * h, axis=1)
        self.C = np.concatenate([[0.0], np.cumsum(hi)]) * scale
        self.quad_err = float(np.sum(np.abs(hi - lo)) * scale + 8 * EPS * abs(self.C[-1]))
        self.slope_end = scale * float(g(np.array([edges[-1]]))[0])
        self._xh, self._wh = xh, wh
        self._inv = None

    @property
    def err(self) -> float:
        """Error bar of ξ(s) (quadrature, plus the inverse tables' error once they are built)."""
        return self.quad_err + (self._inv[4] if self._inv is not None else 0.0)

    def table_err(self) -> float:
        """:attr:`err` with the inverse tables built (profiles are about to be evaluated)."""
        self._tables()
        return self.err

    def _tables(self):
        """(s nodes (P, K), ξ nodes, barycentric weights in ξ, polish?, table error)."""
        if self._inv is not None:
            return self._inv
        t, bw_s, S = _cheb_tables(_K_INV)
        a, b = self.e[:-1], self.e[1:]
        h = (b - a)[:, None]
        sn = a[:, None] + h * t
        sn[:, -1] = b
        xn = self.C[:-1, None] + self.scale * h * (self.g(sn) @ S.T)
        end_err = float(np.max(np.abs(xn[:, -1] - self.C[1:])))
        xn[:, 0], xn[:, -1] = self.C[:-1], self.C[1:]
        span = xn[:, -1:] - xn[:, :1]
        u = (xn - xn[:, :1]) / span
        d = u[:, :, None] - u[:, None, :]
        k = np.arange(_K_INV)
        d[:, k, k] = 1.0
        bw = 1.0 / np.prod(d, axis=2)
        # halfway points: ξ there from the forward interpolant (Chebyshev in s), s back from the
        # inverse interpolant; |Δs| · slope is the table's error in ξ
        sm = 0.5 * (sn[:, 1:] + sn[:, :-1])
        tm = (sm - a[:, None]) / h
        q = bw_s / (tm[:, :, None] - t)
        xim = np.sum(q * xn[:, None, :], axis=2) / np.sum(q, axis=2)
        self._inv = (sn, xn, bw, False, 0.0)
        jm = np.repeat(np.arange(a.size), _K_INV - 1)
        ds = np.abs(self._interp(jm, xim.ravel()) - sm.ravel())
        slope = (np.diff(xn, axis=1) / np.diff(sn, axis=1)).ravel()
        tab_err = float(np.max(ds * slope)) + end_err
        polish = bool(tab_err > 64 * EPS * max(1.0, abs(self.C[-1])))
        self._inv = (sn, xn, bw, polish, tab_err)
        return self._inv

    @functools.cached_property
    def _py(self):
        """The inverse tables as Python lists, for :meth:`s_of_scalar`."""
        sn, xn, bw, _, _ = self._tables()
        u = (xn - xn[:, :1]) / (xn[:, -1:] - xn[:, :1])
        return self.C.tolist(), sn.tolist(), xn.tolist(), u.tolist(), bw.tolist()

    def s_of_scalar(self, x: float) -> float:
        """:meth:`s_of` for one ξ ≥ 0 in pure Python (tails and bisections call it thousands
        of times; NumPy's per-call overhead was 0.1 ms)."""
        if x >= self.C[-1] or self._tables()[3]:  # tail, or tables needing the Newton polish
            return float(self.s_of(np.array([x]))[0])
        Cl, sn, xn, un, bw = self._py
        j = min(max(bisect.bisect_right(Cl, x) - 1, 0), len(Cl) - 2)
        xj, sj, uj, bj = xn[j], sn[j], un[j], bw[j]
        u = (x - xj[0]) / (xj[-1] - xj[0])
        num = den = 0.0
        for uk, sk, bk in zip(uj, sj, bj):
            d = u - uk
            if d == 0.0:
                return sk
            q = bk / d
            num += q * sk
            den += q
        return min(max(num / den, sj[0]), sj[-1])

    def _xi(self, j: np.ndarray, s: np.ndarray) -> np.ndarray:
        """ξ(s) for s in panel j: C[j] + scale ∫_{e[j]}^{s} g (Gauss–Legendre, ``_GL_HI`` nodes)."""
        a = self.e[j]
        h = (s - a)[:, None]
        return self.C[j] + self.scale * np.sum(self.g(a[:, None] + h * self._xh) * self._wh * h, 1)

    def _interp(self, j: np.ndarray, x: np.ndarray) -> np.ndarray:
        """Barycentric interpolation of s(ξ) on panel j (second form; exact at the nodes)."""
        sn, xn, bw = self._inv[0][j], self._inv[1][j], self._inv[2][j]
        span = xn[:, -1] - xn[:, 0]
        d = ((x - xn[:, 0]) / span)[:, None] - (xn - xn[:, :1]) / span[:, None]
        hit = d == 0.0
        q = bw / np.where(hit, 1.0, d)
        s = np.sum(q * sn, axis=1) / np.sum(q, axis=1)
        exact = hit.any(axis=1)
        if exact.any():
            s[exact] = sn[exact][hit[exact]]
        return s

    def s_of(self, xi: np.ndarray) -> np.ndarray:
        """Invert ξ(s) for ξ ≥ 0 (tail beyond the table: linear, g constant there)."""
        C, e = self.C, self.e
        xi = np.asarray(xi, float)
        shape = xi.shape
        xi = xi.ravel()
        out = np.empty_like(xi)
        tail = xi >= C[-1]
        out[tail] = e[-1] + (xi[tail] - C[-1]) / self.slope_end
        if tail.all():
            return out.reshape(shape)
        polish = self._tables()[3]
        x = xi[~tail]
        j = np.clip(np.searchsorted(C, x, side="right") - 1, 0, len(e) - 2)
        a, b = e[j], e[j + 1]
        s = np.clip(self._interp(j, x), a, b)
        for _ in range(40 if polish else 0):  # Newton on ξ(s) − x inside the panel
            F = self._xi(j, s) - x
            s_new = np.clip(s - F / (self.scale * self.g(s)), a, b)
            done = np.abs(s_new - s) <= 4 * EPS * (1.0 + np.abs(s))
            s = s_new
            if np.all(done):
                break
        out[~tail] = s
        return out.reshape(shape)


def _sech2(x):
    """sech² x = 4e/(1+e)², e = exp(−2|x|) (no overflow)."""
    E = np.exp(-2.0 * np.abs(x))
    return 4.0 * E / (1.0 + E) ** 2


# =============================================================================== superkinks
@dataclass(frozen=True)
class QCSuperkinkGeneral(QCSuperkink):
    """QC superkink of any law: the fields of :class:`fpucore.qc.QCSuperkink` plus error bars;
    the profile comes from the first integral by quadrature (module docstring).

    ``p`` = half the decay rate ahead, √(12(V² − f′(w₊)))/(2V) (the p of eq. SKsoln_cubic);
    ``p_minus`` the same behind (equal to p for the cubic only).  ``xi_error`` bounds the error
    of the tabulated ξ(s); ``rayleigh_residual``/``driving_force`` as in fpucore.qc.
    """

    p_minus: float = math.nan
    V_error: float = math.nan
    w_plus_error: float = math.nan
    w_minus_error: float = math.nan
    xi_error: float = math.nan
    tables: tuple = field(default=(), repr=False, compare=False)  # (ξ ≥ 0, ξ < 0) ξ(s) tables

    ERROR_FIELDS: ClassVar = QCSuperkink.ERROR_FIELDS + (
        "V_error", "w_plus_error", "w_minus_error", "xi_error",
    )  # fmt: skip
    DERIVED: ClassVar = QCSuperkink.DERIVED + ("symmetry_defect", "w_center")
    EXCLUDE: ClassVar = ("law", "tables")

    @property
    def w_center(self) -> float:
        """w(0) = (w₊ + w₋)/2 (= w* only for the cubic, eq. cubic_cond1)."""
        return 0.5 * (self.w_plus + self.w_minus)

    @property
    def amplitude_error(self) -> float:
        return self.w_plus_error + self.w_minus_error

    @property
    def symmetry_defect(self) -> float:
        """w₊ + w₋ − 2w* (zero for the cubic, eq. cubic_cond1; not for a general law)."""
        return self.w_plus + self.w_minus - 2.0 * self.law.w_star

    def _w_of_s(self, s):
        """w = w_mid − (Δ/2) tanh s written from the nearer end (no loss in the tails)."""
        D = self.w_minus - self.w_plus
        if np.ndim(s) == 0:
            E = math.exp(-2.0 * abs(s))
            tail = 2.0 * E / (1.0 + E)
            return np.float64(
                self.w_plus + 0.5 * D * tail if s >= 0 else self.w_minus - 0.5 * D * tail
            )
        E = np.exp(-2.0 * np.abs(s))
        tail = 2.0 * E / (1.0 + E)  # 1 − tanh|s|
        return np.where(s >= 0, self.w_plus + 0.5 * D * tail, self.w_minus - 0.5 * D * tail)

    def _s_of_xi(self, xi):
        xi = np.asarray(xi, float)
        pos, neg = self.tables  # neg tabulates g(−s): s = −s_neg for ξ < 0
        if xi.ndim == 0:
            x = float(xi)
            return np.float64(pos.s_of_scalar(x) if x >= 0 else -neg.s_of_scalar(-x))
        out = np.empty_like(xi)
        right = xi >= 0
        if right.all() or not right.any():  # one side only (scalar calls): one table
            return pos.s_of(xi) if xi.size == 0 or right.flat[0] else -neg.s_of(-xi)
        out[right] = pos.s_of(xi[right])
        out[~right] = -neg.s_of(-xi[~right])
        return out

    def profile(self, xi):
        """w(ξ), w(0) = (w₊ + w₋)/2 (= w* only for the cubic)."""
        return self._w_of_s(self._s_of_xi(xi))

    def dprofile(self, xi):
        """w′(ξ) = −(Δ/2) sech²s · ds/dξ."""
        s = self._s_of_xi(xi)
        D = self.w_minus - self.w_plus
        g = _sk_g(self.law, self.w_plus, self.w_minus, self.V * self.V)
        return -0.5 * D * _sech2(s) / (self.tables[0].scale * g(s))

    @property
    def converged(self) -> bool:
        """Residuals at round-off and the ξ(s) table accurate (relative 1e-9 of the width)."""
        return bool(super().converged and self.xi_error * self.p <= QC_CHECK)


def _sk_g(law, wp: float, wm: float, V2: float):
    """g(s) = Q(w(s))^(−1/2), −G = (w−w₊)²(w₋−w)² Q; Q from the expansion about the nearer end
    (−J about w₊ for s ≥ 0, about w₋ for s < 0) so nothing cancels."""
    D = wm - wp

    def g(s):
        s = np.asarray(s, float)
        E = np.exp(-2.0 * np.abs(s))
        near = 0.5 * D * 2.0 * E / (1.0 + E)  # distance to the nearer end (signed like D)
        far = D - near
        dp = np.where(s >= 0, near, far)  # w − w₊
        dm = np.where(s >= 0, -far, -near)  # w − w₋
        with np.errstate(divide="ignore", invalid="ignore"):  # the branch not taken may be 0/0
            Q = np.where(s >= 0, -_J(law, wp, dp, V2) / (dm * dm), -_J(law, wm, dm, V2) / (dp * dp))
        return 1.0 / np.sqrt(Q)

    return g


def _build_superkink(law, V, wp, wm, branch, t0, wp_err, wm_err, V_err):
    V2 = V * V
    D = wm - wp
    g = _sk_g(law, wp, wm, V2)
    scale = 2.0 * abs(V) / (math.sqrt(24.0) * abs(D))  # 2/(k|Δ|)
    edges = np.arange(0.0, _U_MAX + 0.25, 0.5)
    pos, neg = _Map(g, scale, edges), _Map(lambda s: g(-s), scale, edges)
    fp, fm = float(law.f(wp)), float(law.f(wm))
    rscale = abs(fp) + abs(fm) + V2 * abs(D)
    ray = abs(fp - fm - V2 * (wp - wm)) / rscale
    G = float(law.phi(wp) - law.phi(wm)) - 0.5 * (wp - wm) * (fp + fm)
    G_scale = abs(float(law.phi(wp))) + abs(float(law.phi(wm))) + rscale * abs(wp)
    lam = lambda w: math.sqrt(max(12.0 * (V2 - float(law.df(w))), 0.0)) / V  # noqa: E731
    return QCSuperkinkGeneral(
        law, V, wp, wm, 0.5 * lam(wp), branch, ray, abs(G) / G_scale, time.perf_counter() - t0,
        0.5 * lam(wm), V_err, wp_err, wm_err, max(pos.table_err(), neg.table_err()), (pos, neg),
    )  # fmt: skip


def superkink_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> QCSuperkinkGeneral:
    """Superkink with state w₊ ahead: w₋ from eq. zero_G, V_SK² = S(w₊, w₋) (eq. Rline)."""
    t0 = time.perf_counter()
    sp = speeds(law, w_plus)
    branch = "lower" if sp.w_plus < law.w_star else "upper"
    return _build_superkink(
        law, sp.V_SK, sp.w_plus, sp.w_minus, branch, t0, 4 * EPS * abs(sp.w_plus),
        sp.w_minus_error, sp.V_SK_error,
    )  # fmt: skip


def superkink_from_V(
    law: HardeningSofteningLaw, V: float, branch: str = "lower"
) -> QCSuperkinkGeneral:
    """Superkink with velocity V: w₊ solves V_SK(w₊) = V on the branch ("lower": w₊ < w* < w₋,
    a front with w′ < 0; "upper": w₊ > w* > w₋), w₋ its equal-area partner."""
    t0 = time.perf_counter()
    V = require_V(V)
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    lo, hi = superkink_velocity_bounds(law, branch)
    if not lo < V < hi:
        raise ParameterError(
            "V", V, fmt_interval(lo, hi), f"superkink velocities on the {branch} branch"
        )
    wlo, whi = superkink_w_plus_range(law, branch)
    F = lambda wp: _V_SK(law, wp) ** 2 - V * V  # noqa: E731
    a, b = (wlo, law.w_star) if branch == "lower" else (law.w_star, whi)
    wp, wp_err = _root(F, a, b)
    wm, wm_err = w_minus_from_w_plus(law, wp)
    V2 = float(_slope(law, wp, wm - wp))
    dwm = abs(V2 - float(law.df(wp))) / abs(V2 - float(law.df(wm)))  # |dw₋/dw₊| (implicit fn.)
    return _build_superkink(
        law, math.sqrt(V2), wp, wm, branch, t0, wp_err, wm_err + dwm * wp_err,
        abs(math.sqrt(V2) - V) + 8 * EPS * V,
    )  # fmt: skip


# =============================================================================== Rayleigh roots
def _rayleigh_roots_one(law, w_plus: float, V: float):
    """(w_near, w_far, err_near, err_far) for one V."""
    V2 = V * V
    nan = math.nan
    if not V2 < law.c_max**2:
        return nan, nan, nan, nan
    ws = law.w_star
    fdv = lambda w: _df1(law, w) - V2  # noqa: E731
    h = lambda w: (w - w_plus) * (_scalar_slope(law, w_plus, w - w_plus) - V2)  # noqa: E731
    step = max(abs(ws - w_plus), abs(ws) * 1e-3, 1e-3)
    p1 = _root(fdv, *_bracket_to_end(fdv, ws, law.alpha, -1.0, step))[0]  # f′ = V², left of w*
    p2 = _root(fdv, *_bracket_to_end(fdv, ws, law.beta, 1.0, step))[0]  # … and right of w*
    piece = 0 if w_plus < p1 else (2 if w_plus > p2 else 1)
    roots = [(nan, nan)] * 3  # one per monotone piece of h: (−∞, p1), (p1, p2), (p2, ∞)
    if piece != 1 and (h(p1) < 0) != (h(p2) < 0):
        roots[1] = _root(h, p1, p2)
    if piece != 0:
        br = _bracket_to_end(h, p1, law.alpha, -1.0, step)
        roots[0] = _root(h, *br) if br else (nan, nan)
    if piece != 2:
        br = _bracket_to_end(h, p2, law.beta, 1.0, step)
        roots[2] = _root(h, *br) if br else (nan, nan)
    (r0, e0), (r1, e1) = [r for k, r in enumerate(roots) if k != piece]
    if w_plus <= ws:  # far = the root beyond the partner side, as in fpucore.qc.rayleigh_roots
        return r0, r1, e0, e1
    return r1, r0, e1, e0


def rayleigh_roots(law: HardeningSofteningLaw, w_plus: float, V):
    """(w_near, w_far): the other intersections of f with R(w) = f(w₊) + V²(w − w₊), labelled as
    in :func:`fpucore.qc.rayleigh_roots` (w_far is the saddle w_S for c₊ < V < c₋, w_near the
    center w_C); NaN where they do not exist (V ≥ c₋).  V may be an array.

    h = f − R is monotone on (−∞, p₁), (p₁, p₂), (p₂, ∞) with f′(p_i) = V² (within the hardening–
    softening shape), so each piece not holding w₊ has at most one root: bracketed, then brentq.
    Beyond (α, β) the bracket is searched by outward marching.
    """
    w_plus = require_finite("w_plus", w_plus)
    Va = np.asarray(V, dtype=float)
    out = [_rayleigh_roots_one(law, w_plus, float(v))[:2] for v in Va.ravel()]
    near = np.array([o[0] for o in out]).reshape(Va.shape)
    far = np.array([o[1] for o in out]).reshape(Va.shape)
    if Va.ndim == 0:
        return float(near), float(far)
    return near, far


def w_S(law: HardeningSofteningLaw, w_plus: float, V):
    """Saddle w_S(V) ≠ w₊ of eq. wS (the far Rayleigh root)."""
    return rayleigh_roots(law, w_plus, V)[1]


# =============================================================================== solitary waves
@dataclass(frozen=True)
class QCSolitaryGeneral(QCSolitary):
    """QC solitary wave of any law: the fields of :class:`fpucore.qc.QCSolitary` plus error bars.

    ``w_M`` the turning point (w(0) = w_M), ``w_T`` the next zero of G_B beyond the other saddle
    (the w_T of eq. w_T_M for the cubic; NaN if none), ``gamma`` = √(12(V² − f′(w_B)))/V the
    decay rate (the γ of eq. SWsoln_cubic).  ``energy`` is E_ren^QC (eq. Eren_QC) by quadrature,
    ``energy_error`` its bound (quadrature order difference + tail + propagated root errors +
    round-off amplified near the ends of the velocity interval).
    """

    w_B_error: float = math.nan
    w_M_error: float = math.nan
    V_SK_error: float = math.nan
    xi_error: float = math.nan
    table: object = field(default=None, repr=False, compare=False)  # ξ(u) table

    ERROR_FIELDS: ClassVar = QCSolitary.ERROR_FIELDS + (
        "w_B_error", "w_M_error", "V_SK_error", "xi_error",
    )  # fmt: skip
    EXCLUDE: ClassVar = QCSolitary.EXCLUDE + ("table",)

    @property
    def amplitude_error(self) -> float:
        return self.w_B_error + self.w_M_error

    def profile(self, xi):
        xi = np.asarray(xi, float)
        u = self.table.s_of_scalar(abs(float(xi))) if xi.ndim == 0 else self.table.s_of(np.abs(xi))
        return self.w_B + (self.w_M - self.w_B) * _sech2(u)

    def dprofile(self, xi):
        """w′(ξ) = sign(ξ) (dw/du)/(dξ/du), dw/du = −2 dM sech²u tanh u."""
        xi = np.asarray(xi, float)
        u = self.table.s_of(np.abs(xi))
        dw = -2.0 * (self.w_M - self.w_B) * _sech2(u) * np.tanh(u)
        return np.sign(xi) * dw / (self.table.scale * self.table.g(u))


def _sw_g(law, wB: float, wM: float, V2: float):
    """g(u) = |R̃(w(u))|^(−1/2), w = w_B + dM sech²u, −G_B = (w−w_B)²(w_M−w) R̃:
    near w_B (sech²u < ½) R̃ = −J(w_B, d)/(dM − d); near w_M R̃ = ∫₀¹ h_B(w_M + τ(w − w_M)) dτ/d²
    (G_B(w_M) = 0, h_B = G_B′ = f − f(w_B) − V²(· − w_B))."""
    dM = wM - wB
    fB = float(law.f(wB))
    t, wt = _inner(law)

    def g(u):
        u = np.asarray(u, float)
        sech2 = _sech2(u)
        d = dM * sech2
        gap = dM * np.tanh(u) ** 2  # dM − d
        s = wM - gap[..., None] * t  # w_M + τ (w − w_M)
        hB = law.f(s) - fB - V2 * (s - wB)  # |s − w_B| ≥ |dM|/2 here: mild cancellation
        with np.errstate(invalid="ignore", divide="ignore"):  # each form is used where it is finite
            R_far = -_J(law, wB, d, V2) / gap
            R_near = np.sum(hB * wt, axis=-1) / (d * d)
            R = np.where(np.abs(u) > _SQ, R_far, R_near)
        return 1.0 / np.sqrt(np.abs(R))

    return g


def solitary(
    law: HardeningSofteningLaw, w_plus: float, V: float, check: bool = True
) -> QCSolitaryGeneral:
    """QC solitary wave for the state w₊ ahead of the associated superkink, velocity V (eq. wB):
    V ∈ (c₊, V_SK) → w_B = w₊; V ∈ (V_SK, c₋) → w_B = w_S(V).  ``check=False`` skips the
    first-integral check on the profile (a third of the cost; families need only E and w_M):
    ``first_integral_residual`` is then NaN."""
    t0 = time.perf_counter()
    V = require_V(V)
    sp = speeds(law, w_plus)
    w_plus, cp, vsk, cm = sp.w_plus, sp.c_plus, sp.V_SK, sp.c_minus
    valid = f"{fmt_interval(cp, vsk)} or {fmt_interval(vsk, cm)}"
    if V == vsk:
        raise ParameterError("V", V, valid, "V = V_SK is the superkink itself")
    V2 = V * V
    w_near, w_far, _, far_err = _rayleigh_roots_one(law, w_plus, V)
    if cp < V < vsk:
        interval, wB, other, wB_err = "below", w_plus, w_far, 0.0
    elif vsk < V < cm:
        interval, wB, other, wB_err = "above", w_far, w_plus, far_err
    else:
        raise ParameterError("V", V, valid, f"solitary-wave velocities for w_plus={w_plus:.10g}")
    if not (math.isfinite(w_near) and math.isfinite(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    Jw = lambda w: _scalar_J(law, wB, w - wB, V2)  # noqa: E731
    if not (Jw(w_near) < 0 < Jw(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    wM, wM_err = _root(Jw, w_near, other)
    sgn = 1.0 if other > wB else -1.0
    br = _outward(Jw, other, sgn, 0.125 * abs(other - wB), n=80)
    wT = _root(Jw, *br)[0] if br else math.nan
    dM = wM - wB
    gamma = math.sqrt(12.0 * (V2 - float(law.df(wB)))) / V

    g = _sw_g(law, wB, wM, V2)
    scale = 2.0 * V / (math.sqrt(24.0) * math.sqrt(abs(dM)))
    # grade the panels toward u = 0 when the orbit grazes the other saddle (flat top near V_SK):
    # there R̃ ≈ ε + c u², so panels must resolve u ~ √ε
    eps_rel = max(abs(wM - other) / abs(dM), 1e-300)
    J_lev = int(min(60, max(0, math.ceil(-math.log2(0.05 * math.sqrt(eps_rel))))))
    edges = np.unique(np.concatenate([[0.0], 2.0 ** -np.arange(J_lev, 0, -1.0),
                                      np.arange(0.5, _U_MAX + 0.25, 0.5)]))  # fmt: skip
    m = _Map(g, scale, edges)

    # E_ren^QC = (V² w_B + f_B) ∫d dξ + V² ∫d² dξ over the whole line (even profile)
    fB = float(law.f(wB))
    c1, c2 = V2 * wB + fB, V2
    a, b = edges[:-1], edges[1:]
    hh = (b - a)[:, None]
    vals = []
    for n in (_GL_HI, _GL_LO):
        x, wq = _gl01(n)
        u = a[:, None] + hh * x
        d = dM * _sech2(u)
        jac = scale * g(u) * wq * hh
        vals.append((2.0 * np.sum(d * jac), 2.0 * np.sum(d * d * jac)))
    (I1, I2), (I1l, I2l) = vals
    t1, t2 = c1 * I1, c2 * I2
    tail = 2.0 * abs(c1 * dM) * 4.0 * math.exp(-2.0 * _U_MAX) * m.slope_end
    energy = float(t1 + t2)
    # propagated root errors: near V_SK the plateau length ~ (1/λ_o) log(1/ε), ε = |w_M − other|
    # (R̃ ≈ ε + c u²), so δE ≈ |c1 dM + c2 dM²| (2/λ_o) δε/ε to first order
    lam_o = math.sqrt(max(12.0 * (V2 - float(law.df(other))), EPS)) / V
    d_eps = wM_err + (far_err if interval == "below" else 0.0) + wB_err
    prop = abs(c1 * dM + c2 * dM * dM) * 2.0 / lam_o * d_eps / max(abs(wM - other), EPS)
    # … and the level G_B(other) ≈ ½κ ε² itself is a difference of O(V² d²) terms
    d_o = other - wB
    G_o = abs(d_o * d_o * float(_J(law, wB, d_o, V2)))
    prop += abs(c1 * dM + c2 * dM * dM) / lam_o * 8 * EPS * V2 * d_o * d_o / max(G_o, 1e-300)
    energy_err = float(
        abs(c1 * (I1 - I1l))
        + abs(c2 * (I2 - I2l))
        + tail
        + prop
        + 128 * EPS * (1.0 + V2 / (V2 - float(law.df(wB)))) * (abs(t1) + abs(t2))
    )  # round-off of J ∝ f′ − V² is amplified by κ_B = V²/(V² − f′(w_B)) (near-sonic waves)

    kind = "tensile" if dM > 0 else "compressive"
    sw = QCSolitaryGeneral(
        law, V, w_plus, wB, wT, wM, gamma, kind, interval, vsk, cp, cm, energy, energy_err,
        math.nan, 0.0, wB_err, wM_err, sp.V_SK_error, m.err, m,
    )  # fmt: skip
    xi = np.linspace(0.0, 12.0, 32) / gamma
    fi = first_integral_residual(law, sw.profile(xi), sw.dprofile(xi), wB, V) if check else math.nan
    # xi_error includes the inverse tables' error once a profile has been evaluated (check=True)
    return replace(
        sw, first_integral_residual=fi, xi_error=m.err, elapsed_s=time.perf_counter() - t0
    )
