"""Tails of discrete traveling waves and the automatic chain length N.

Linearising eq. TW_discrete at a tail state w_∞ with w − w_∞ ∝ e^{−λ|ξ|} gives

    V² λ² = 4 f′(w_∞) sinh²(λ/2)                                  (discrete decay rate)

which has a real root λ > 0 exactly when the wave is supersonic, V² > f′(w_∞) (the QC model's
rate, λ_QC² = 12 (V² − c²)/c², is its small-λ approximation and overestimates it).  The chain must
reach from the core of the wave (taken from the QC profile) to where the tail has decayed to the
requested tolerance; the waves widen without bound near V_SK (plateau) and near the sonic limits
(λ → 0), so N is chosen per wave rather than fixed; a state is moved to another N by
:func:`resize` (padded with the tail states).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

N_MIN = 64  # measured: at N = 32–48 Newton from the QC guess often fails for narrow waves
N_MAX = 20_000


def decay_rate(law, w_inf: float, V: float) -> float:
    """Positive root λ of V λ = 2 c sinh(λ/2), c² = f′(w_∞); NaN unless V² > f′(w_∞).
    A zero-modulus tail state (f′(w_∞) = 0, the degenerate PL law): ∞, the tail is reached
    exactly (compact waves, :mod:`fpucore.wave.compact`)."""
    c2 = float(law.df(w_inf))
    if c2 == 0.0 and V > 0.0:
        return math.inf
    if not (c2 > 0 and V * V > c2):
        return math.nan
    c = math.sqrt(c2)
    g = lambda lam: 2.0 * c * math.sinh(0.5 * lam) - V * lam  # noqa: E731
    hi = 1.0
    while g(hi) <= 0.0:
        hi *= 2.0
    lo = hi
    while g(lo) >= 0.0 and lo > 1e-300:  # g < 0 just above 0 because V > c
        lo *= 0.5
    return brentq(g, lo, hi, xtol=1e-15, rtol=1e-14)


def _core_edge(profile, w_inf: float, level: float, side: int, xi_max: float = 1e7) -> float:
    """Largest |ξ| on one side (side = ±1) where |profile − w_∞| ≥ level (bisection on ξ)."""
    dev = lambda x: abs(float(profile(side * x)) - w_inf)  # noqa: E731
    if dev(0.0) < level:
        return 0.0
    hi = 1.0
    while dev(hi) >= level:
        hi *= 2.0
        if hi > xi_max:
            return math.inf
    lo = 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if dev(mid) >= level else (lo, mid)
    return hi


def required_half_width(
    law, V: float, profile, w_left: float, w_right: float, amplitude: float, tail_tol: float
) -> float:
    """Sites needed on each side of ξ = 0 so both tails have decayed below ``tail_tol``.

    Core edge: where the QC profile's deviation from the tail state falls to 1e-3 × amplitude;
    beyond it the discrete tail decays at the discrete rate λ(w_∞, V); a margin of 4 sites covers
    the boundary layer the fixed end strain imposes.
    """
    L = 0.0
    for side, w_inf in ((-1, w_left), (1, w_right)):
        lam = decay_rate(law, w_inf, V)
        if math.isnan(lam):  # not supersonic (λ = ∞: a compact tail, reached at the core)
            return math.inf
        start = 1e-3 * amplitude
        xc = _core_edge(profile, w_inf, start, side)
        L = max(L, xc + max(0.0, math.log(start / tail_tol)) / lam + 4.0)
    return L


def auto_N(half_width: float) -> int:
    """Even N with N/2 − 1 ≥ half-width, at least N_MIN (may exceed N_MAX: caller checks)."""
    if not math.isfinite(half_width):
        return 2**62
    return max(N_MIN, 2 * (int(math.ceil(half_width)) + 1))


def tail_error(w: np.ndarray, wd: np.ndarray, w_left: float, w_right: float, k: int = 3) -> float:
    """Largest |w − w_∞| and |ẇ| over the k outermost sites at each end (the truncation by N)."""
    return float(
        max(
            np.max(np.abs(w[:k] - w_left)),
            np.max(np.abs(w[-k:] - w_right)),
            np.max(np.abs(wd[:k])),
            np.max(np.abs(wd[-k:])),
        )
    )


def resize(x: np.ndarray, N_old: int, N_new: int, w_left: float, w_right: float) -> np.ndarray:
    """Re-centre an interleaved state on a chain of N_new sites (pad with the tail states).

    Parameters
    ----------
    x : ndarray, shape (2 N_old,)
        Interleaved state (w_n, ẇ_n) on N_old sites, n = −N_old/2 … N_old/2−1.
    N_old, N_new : int
        Site counts of ``x`` and of the result.
    w_left, w_right : float
        Strains given to new sites left (n < 0) and right (n >= 0) of the old chain; their ẇ is 0.

    Returns
    -------
    ndarray, shape (2 N_new,)
        The interleaved state on N_new sites, aligned on site n = 0.
    """
    n_new = np.arange(N_new) - N_new // 2
    y = np.empty(2 * N_new)
    y[0::2] = np.where(n_new < 0, w_left, w_right)
    y[1::2] = 0.0
    idx = n_new + N_old // 2
    ok = (idx >= 0) & (idx < N_old)
    y[0::2][ok] = x[0::2][idx[ok]]
    y[1::2][ok] = x[1::2][idx[ok]]
    return y


def fmt_N(N: int) -> str:
    """A site count as the messages print it ("unbounded" from 10⁹ on)."""
    return str(N) if N < 10**9 else "unbounded"
