"""Order conditions of Runge–Kutta–Nyström methods for q̈ = F(q), in exact arithmetic.

The conditions are indexed by special Nyström trees (Hairer, Nørsett & Wanner, *Solving ODEs I*,
§II.14): a fat root (one F evaluation) whose children are meagre vertices, each either a leaf
(a factor q̇, weight c_i) or the parent of one fat subtree u (weight Σ_j a_ij Φ_j(u)).  With ρ(t) the
number of vertices and γ(t) the usual tree density, the method has order p iff

    Σ_i b′_i Φ_i(t) = 1/γ(t)               for ρ(t) ≤ p       (velocity weights)
    Σ_i b_i  Φ_i(t) = 1/((ρ(t)+1) γ(t))    for ρ(t) ≤ p − 1   (position weights).

Tree counts by order 1…10: 1, 1, 2, 3, 6, 10, 20, 36, 72, 137.  Test support (not part of
fpucore): tests/tableaux/test_rkn.py checks the tableaux of :mod:`fpucore.tableaux.rkn`
coefficient by coefficient with it (imported as ``rkn_order``: pytest puts tests/support on
``sys.path``, pyproject's ``pythonpath``).
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

LEAF = "L"


@lru_cache(None)
def _items(k: int) -> tuple:
    """Meagre children of order k: a leaf (k = 1) or ('M', fat subtree of order k − 1)."""
    if k == 1:
        return (LEAF,)
    return tuple(("M", u) for u in trees(k - 1))


@lru_cache(None)
def trees(n: int) -> tuple:
    """All special Nyström trees of order n, each a sorted tuple of its root's children."""
    out = set()

    def rec(rem, maxkey, acc):
        if rem == 0:
            out.add(tuple(sorted(acc, key=repr)))
            return
        for k in range(1, rem + 1):
            for it in _items(k):
                key = (k, repr(it))
                if maxkey is None or key <= maxkey:  # non-increasing keys: each multiset once
                    rec(rem - k, key, acc + [it])

    rec(n - 1, None, [])
    return tuple(sorted(out, key=repr))


def order(t: tuple) -> int:
    return 1 + sum(1 if it == LEAF else 1 + order(it[1]) for it in t)


def density(t: tuple) -> int:
    g = order(t)
    for it in t:
        if it != LEAF:
            g *= (1 + order(it[1])) * density(it[1])
    return g


def residuals(c, A, b, bp, p: int) -> tuple[Fraction, Fraction, int]:
    """Largest |residual| of the velocity conditions up to order p and of the position conditions
    up to order p − 1, and the number of trees checked.  c (s,), A (s×s), b, bp (s,): Fractions."""
    s = len(c)
    memo: dict = {}

    def phi(t):
        if t not in memo:
            v = [Fraction(1)] * s
            for it in t:
                if it == LEAF:
                    v = [v[i] * c[i] for i in range(s)]
                else:
                    u = phi(it[1])
                    v = [v[i] * sum(A[i][j] * u[j] for j in range(s) if A[i][j]) for i in range(s)]
            memo[t] = v
        return memo[t]

    worst_v = worst_q = Fraction(0)
    count = 0
    for n in range(1, p + 1):
        for t in trees(n):
            count += 1
            ph, g = phi(t), density(t)
            worst_v = max(worst_v, abs(sum(x * y for x, y in zip(bp, ph)) - Fraction(1, g)))
            if n <= p - 1:
                r = abs(sum(x * y for x, y in zip(b, ph)) - Fraction(1, (n + 1) * g))
                worst_q = max(worst_q, r)
    return worst_v, worst_q, count
