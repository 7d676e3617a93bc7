"""The QC orbit of a piecewise-linear law, arc by arc (the closed forms of
:mod:`fpucore.qc.piecewise_orbit`'s module docstring): the potential P(w) between the
breakpoints, one regime's :class:`Arc` (exponential, trigonometric or parabolic), a half orbit
from a level to a double zero of Q as a list of arcs, its two moments ∫(w − w_B), ∫(w − w_B)²
in closed form, and the profile evaluated on the arcs."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def orbit_potential(law, wB: float, V2: float, w: float) -> float:
    """P(w) = −∫_{w_B}^w (f − R): trapezoids between the breakpoints (exact for a PL law)."""
    fB = float(law.f(wB))
    g = lambda x: float(law.f(x)) - fB - V2 * (x - wB)  # noqa: E731
    lo, hi = min(wB, w), max(wB, w)
    pts = [lo, *[x for x in law._b if lo < x < hi], hi]
    tot = sum(0.5 * (g(a) + g(c)) * (c - a) for a, c in zip(pts[:-1], pts[1:]))
    return -tot if w >= wB else tot


@dataclass(frozen=True)
class Arc:
    """One regime's arc: entry at ξ_a (level w_a, slope dw_a), exit at ξ_b (∞ for a tail)."""

    j: int
    lam: float
    e: float
    K: float
    xi_a: float
    xi_b: float
    w_a: float
    dw_a: float
    w_b: float
    dw_b: float
    c: float = 0.0  # w″ on a λ = 0 arc

    def w(self, s):
        """w at ξ = ξ_a + s (s ≥ 0 within the arc)."""
        u_a = self.w_a - self.e
        if self.lam > 0:
            r = math.sqrt(self.lam)
            if math.isinf(self.xi_b):  # tail: pure decay
                return self.e + u_a * np.exp(-r * s)
            p, q = _pq(u_a, self.dw_a, r, self.K)
            return self.e + (p * np.exp(r * s) - q * np.exp(-r * s)) / (2.0 * r)
        if self.lam < 0:
            nu = math.sqrt(-self.lam)
            return self.e + u_a * np.cos(nu * s) + self.dw_a / nu * np.sin(nu * s)
        return self.w_a + self.dw_a * s + 0.5 * self.c * s * s

    def dw(self, s):
        """w′ at ξ = ξ_a + s."""
        u_a = self.w_a - self.e
        if self.lam > 0:
            r = math.sqrt(self.lam)
            if math.isinf(self.xi_b):
                return -r * u_a * np.exp(-r * s)
            p, q = _pq(u_a, self.dw_a, r, self.K)
            return 0.5 * (p * np.exp(r * s) + q * np.exp(-r * s))
        if self.lam < 0:
            nu = math.sqrt(-self.lam)
            return -u_a * nu * np.sin(nu * s) + self.dw_a * np.cos(nu * s)
        return self.dw_a + self.c * s


def _pq(u: float, du: float, r: float, K: float) -> tuple[float, float]:
    """(u′ + r u, u′ − r u), the one with equal signs evaluated, the other as K/it."""
    if (du >= 0) == (u >= 0):
        p = du + r * u
        return p, (K / p if p != 0 else du - r * u)
    q = du - r * u
    return (K / q if q != 0 else du + r * u), q


def half_orbit(law, wB: float, V2: float, w0: float, target: float, turning=False) -> list[Arc]:
    """Arcs from ξ = 0 at level w0 (w′ from Q, sign toward the target; exactly 0 at a turning
    point, where Q(w0) is zero only to rounding and √Q would start the arc with a spurious
    slope ~1e-8) to the limit ``target`` (a double zero of Q, approached exponentially)."""
    d = 1.0 if target > w0 else -1.0
    b = law._b
    arcs: list[Arc] = []
    xi, w_a = 0.0, w0
    dw_a = 0.0 if turning else d * math.sqrt(max(24.0 * orbit_potential(law, wB, V2, w0) / V2, 0.0))
    j = int(law.piece(w0)) - int(d < 0 and bool(np.any(b == w0)))  # a corner: the piece ahead
    jt = int(law.piece(target))
    fB = float(law.f(wB))
    while True:
        s = float(law._s[j])
        lam = 12.0 * (V2 - s) / V2
        if j == jt:  # the tail: e = target, K = 0 exactly
            arcs.append(Arc(j, lam, target, 0.0, xi, math.inf, w_a, dw_a, target, 0.0))
            return arcs
        w_b = float(b[j] if d > 0 else b[j - 1])
        Qb = 24.0 * orbit_potential(law, wB, V2, w_b) / V2
        dw_b = d * math.sqrt(max(Qb, 0.0))
        if s != V2:
            g_b = float(law.f(w_b)) - fB - V2 * (w_b - wB)
            e = w_b - g_b / (s - V2)
            K = Qb - lam * (w_b - e) ** 2
            if lam > 0:
                r = math.sqrt(lam)
                pa, qa = _pq(w_a - e, dw_a, r, K)
                pb, qb = _pq(w_b - e, dw_b, r, K)
                # u′ + r u ∝ e^{rξ}, u′ − r u ∝ e^{−rξ}: the larger pair decides
                if min(abs(pa), abs(pb)) >= min(abs(qa), abs(qb)):
                    dxi = math.log(pb / pa) / r
                else:
                    dxi = -math.log(qb / qa) / r
            else:
                nu = math.sqrt(-lam)
                th_a = math.atan2(nu * (w_a - e), dw_a)
                th_b = math.atan2(nu * (w_b - e), dw_b)
                dxi = ((th_b - th_a) % (2 * math.pi)) / nu  # u′ + iνu ∝ e^{iνξ}
            arcs.append(Arc(j, lam, e, K, xi, xi + dxi, w_a, dw_a, w_b, dw_b))
        else:
            dxi = 2.0 * (w_b - w_a) / (dw_a + dw_b)
            c = (dw_b - dw_a) / dxi
            arcs.append(Arc(j, 0.0, math.nan, 0.0, xi, xi + dxi, w_a, dw_a, w_b, dw_b, c))
        xi, w_a, dw_a = xi + dxi, w_b, dw_b
        j += 1 if d > 0 else -1


def orbit_moments(arcs: list[Arc], wB: float) -> tuple[float, float]:
    """(∫(w − w_B) dξ, ∫(w − w_B)² dξ) over a half orbit, in closed form (module docstring)."""
    m1 = m2 = 0.0
    for a in arcs:
        if math.isinf(a.xi_b):
            r = math.sqrt(a.lam)
            u = a.w_a - a.e
            dl = a.e - wB
            m1 += u / r + (0.0 if dl == 0 else math.inf)
            m2 += u * u / (2 * r)
            continue
        L = a.xi_b - a.xi_a
        if a.lam == 0.0:  # polynomial arc: 3-point Gauss–Legendre is exact to degree 5
            x, wt = np.polynomial.legendre.leggauss(3)
            y = np.array([a.w(0.5 * L * (1 + t)) for t in x]) - wB
            m1 += 0.5 * L * float(np.dot(wt, y))
            m2 += 0.5 * L * float(np.dot(wt, y * y))
            continue
        ua, ub = a.w_a - a.e, a.w_b - a.e
        I1 = (a.dw_b - a.dw_a) / a.lam
        I2 = (ub * a.dw_b - ua * a.dw_a - a.K * L) / (2 * a.lam)
        dl = a.e - wB
        m1 += dl * L + I1
        m2 += dl * dl * L + 2 * dl * I1 + I2
    return m1, m2


def evaluate_arcs(arcs: list[Arc], xi: np.ndarray, derivative: bool = False) -> np.ndarray:
    """w (or w′ with ``derivative``) at the points ``xi`` of the arcs, each on its own arc."""
    out = np.empty_like(xi)
    for a in arcs:
        m = (xi >= a.xi_a) & (xi <= a.xi_b)
        out[m] = (a.dw if derivative else a.w)(xi[m] - a.xi_a)
    return out
