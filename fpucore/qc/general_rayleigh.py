"""The Rayleigh line's other intersections with f for any hardening–softening law (paper §3,
eqs. Rline, wS): the centre w_C and the saddle w_S by bracketed roots on the monotone pieces of
f − R (the method: :mod:`fpucore.qc.general`)."""

from __future__ import annotations

import math

import numpy as np

from fpucore.errors import require_finite
from fpucore.law import HardeningSofteningLaw
from fpucore.qc.general_roots import bracket_to_end, bracketed_root, df_at, scalar_slope


def rayleigh_roots_at(law, w_plus: float, V: float):
    """(w_near, w_far, err_near, err_far) for one scalar V (:func:`rayleigh_roots`)."""
    V2 = V * V
    nan = math.nan
    if not V2 < law.c_max**2:
        return nan, nan, nan, nan
    ws = law.w_star
    fdv = lambda w: df_at(law, w) - V2  # noqa: E731
    h = lambda w: (w - w_plus) * (scalar_slope(law, w_plus, w - w_plus) - V2)  # noqa: E731
    step = max(abs(ws - w_plus), abs(ws) * 1e-3, 1e-3)
    # f′ = V² left of w* (p1) and right of it (p2)
    p1 = bracketed_root(fdv, *bracket_to_end(fdv, ws, law.alpha, -1.0, step))[0]
    p2 = bracketed_root(fdv, *bracket_to_end(fdv, ws, law.beta, 1.0, step))[0]
    piece = 0 if w_plus < p1 else (2 if w_plus > p2 else 1)
    roots = [(nan, nan)] * 3  # one per monotone piece of h: (−∞, p1), (p1, p2), (p2, ∞)
    if piece != 1 and (h(p1) < 0) != (h(p2) < 0):
        roots[1] = bracketed_root(h, p1, p2)
    if piece != 0:
        br = bracket_to_end(h, p1, law.alpha, -1.0, step)
        roots[0] = bracketed_root(h, *br) if br else (nan, nan)
    if piece != 2:
        br = bracket_to_end(h, p2, law.beta, 1.0, step)
        roots[2] = bracketed_root(h, *br) if br else (nan, nan)
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
    out = [rayleigh_roots_at(law, w_plus, float(v))[:2] for v in Va.ravel()]
    near = np.array([o[0] for o in out]).reshape(Va.shape)
    far = np.array([o[1] for o in out]).reshape(Va.shape)
    if Va.ndim == 0:
        return float(near), float(far)
    return near, far


def w_S(law: HardeningSofteningLaw, w_plus: float, V):
    """Saddle w_S(V) ≠ w₊ of eq. wS (the far Rayleigh root)."""
    return rayleigh_roots(law, w_plus, V)[1]
