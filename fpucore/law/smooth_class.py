"""The hardening–softening class check of a smooth law on its own convex interval (paper §2).

Roots in float64 by bracketing (brentq on the exact expression); the class is decided on those, and
only a law that passes has them polished by mpmath at 30 digits (:meth:`Root.polished`: a refusal
costs no extended precision), each with an error bar |x_float − x_30 digits| + 2 ulp.  The
steps, each refused with the reason and the place:

* f(0) = 0 (|f(0)| at 40 digits ≤ 1e-25 max(1, f′(0))) and f′(0) > 0;
* β: the first zero of f′ above 0 found on the geometric grid 10^(−30 … 30) (16 points a decade),
  then bracketed; α likewise below 0, or −∞ when f′ > 0 down to −1e30 (or f′ overflows only
  beyond −4β); a non-finite value before f′ vanishes is a domain error inside (α, β);
* w*: the sign changes of f″ on a grid of ≥ 20001 points of (α, β) — exactly one, from + to −,
  at w* > 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EPS = float(np.finfo(float).eps)
GRID = np.logspace(-30, 30, 961)
N_INFLECTION = 20001


class ClassFailure(ValueError):
    """A law outside the class (the message is the reason, with the place)."""


def _finite(fn, x):
    with np.errstate(all="ignore"):
        v = np.asarray(fn(np.asarray(x, dtype=float)), dtype=float)
    return np.broadcast_to(v, np.shape(x))


def polish(mp_fn, mp_dfn, x: float, a: float, b: float) -> tuple[float, float]:
    """(root, error bar) of mp_fn near the float root x in [a, b], at 30 digits."""
    import mpmath

    try:
        with mpmath.workdps(30):
            r = mpmath.findroot(
                lambda z: mp_fn(z), (mpmath.mpf(a), mpmath.mpf(b)), solver="anderson", verify=False
            )
            r = float(r)
    except (ValueError, ZeroDivisionError, TypeError):
        return x, max(abs(b - a), 4 * EPS * abs(x))
    if not (min(a, b) <= r <= max(a, b)):
        return x, max(abs(b - a), 4 * EPS * abs(x))
    return r, abs(r - x) + 2 * EPS * abs(r)


@dataclass(frozen=True)
class Root:
    """A float64 root ``x`` of a bracket [a, b] (brentq to 4 ulp), not yet polished: the class
    check decides on these, and only a law that passes pays for the 30-digit polish."""

    x: float
    a: float
    b: float

    def polished(self, mp_fn) -> tuple[float, float]:
        """(root, error bar) at 30 digits (:func:`polish`); an exact zero on the grid: 2 ulp."""
        if self.a == self.b:
            return self.x, 2 * EPS * abs(self.x)
        return polish(mp_fn, None, self.x, self.a, self.b)


def root(fn, a: float, b: float) -> Root:
    from scipy.optimize import brentq  # SciPy on first use: `import fpucore.law` stays light

    g = lambda z: float(_finite(fn, z))  # noqa: E731
    x = brentq(g, a, b, xtol=4 * EPS * max(abs(a), abs(b)), rtol=4 * EPS, maxiter=500)
    return Root(float(x), float(a), float(b))


def convex_end(df, sign: float, diagnose) -> Root | None:
    """The end of the convex interval on the side ``sign`` of 0 (float64, unpolished; an exact
    zero on the grid has a = b = x), or None when that end is −∞."""
    x = sign * GRID
    v = _finite(df, x)
    bad = ~(v > 0) | ~np.isfinite(v)
    if not np.any(bad):
        if sign > 0:
            raise ClassFailure(
                "no softening: f'(w) > 0 for every w in (0, 1e30], so the convex interval has "
                "no upper end beta and no superkink exists"
            )
        return None
    j = int(np.argmax(bad))
    if not np.isfinite(v[j]):
        if sign < 0:
            return None  # decided by the caller against beta
        raise ClassFailure(
            f"f' is not finite at w = {x[j]:.6g} before it vanishes: {diagnose(x[j])}"
        )
    a = x[j - 1] if j > 0 else 0.0
    if v[j] == 0.0:
        return Root(float(x[j]), float(x[j]), float(x[j]))
    return root(df, a, float(x[j]))


def inflection(ddf, alpha: float, beta: float, n: int) -> Root:
    """The unique sign change of f″ in (α, β), + to −, at w* > 0 (ClassFailure otherwise;
    float64, unpolished)."""
    x = np.linspace(alpha, beta, max(n, N_INFLECTION))[1:-1]
    v = _finite(ddf, x)
    if not np.all(np.isfinite(v)):
        raise ClassFailure(f"f'' is not finite at w = {x[~np.isfinite(v)][0]:.6g}")
    s = np.sign(v)
    nz = s != 0
    xs, ss = x[nz], s[nz]
    idx = np.nonzero(ss[1:] != ss[:-1])[0]
    where = ", ".join(f"{0.5 * (xs[i] + xs[i + 1]):.6g}" for i in idx[:8])
    iv = f"(alpha, beta) = ({alpha:.6g}, {beta:.6g})"
    if idx.size == 0:
        what = "hardening only (f'' > 0)" if ss.size and ss[0] > 0 else "softening only (f'' < 0)"
        raise ClassFailure(
            f"f'' does not change sign on {iv}: {what}; a hardening-softening law needs "
            "f'' > 0 on (alpha, w*) and f'' < 0 on (w*, beta)"
        )
    if idx.size > 1:
        raise ClassFailure(
            f"f'' changes sign {idx.size} times on {iv}: at w ~ {where}; the law "
            "must change from hardening to softening exactly once"
        )
    i = idx[0]
    if ss[i] < 0:
        raise ClassFailure(
            f"f'' changes from - to + at w ~ {where}: softening-hardening, not hardening-softening"
        )
    r = root(ddf, float(xs[i]), float(xs[i + 1]))
    if not r.x > 0:
        raise ClassFailure(
            f"the inflection w* = {r.x:.10g} must lie at positive strain "
            "(hardening at w = 0, paper §2)"
        )
    return r
