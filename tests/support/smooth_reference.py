"""The smooth presets' f and Φ = ∫₀ʷ f written here from their formulas in mpmath (independent of
fpucore's parser and kernels): the references of the smooth-law tests."""

from __future__ import annotations

import mpmath

from fpucore.law.presets import PRESETS


def antiderivative(name):
    """Φ(w) = ∫₀ʷ f of the preset, in closed form (mpmath)."""
    c = {k: mpmath.mpf(repr(v)) for k, v in PRESETS[name].constants_dict.items()}
    if name == "exponential":
        b, cc, d = c["b"], c["c"], c["d"]

        def P(w):  # ∫ w³ e^{w/d} = d e^{w/d} (w³ − 3d w² + 6d² w − 6d³)
            return d * mpmath.exp(w / d) * (w**3 - 3 * d * w**2 + 6 * d**2 * w - 6 * d**3)

        return lambda w: w**2 / 2 + b * w**3 / 3 - cc * (P(w) - P(0))
    if name == "tanh":
        k, m, s, cc = c["k"], c["m"], c["s"], c["c"]
        return lambda w: (w**2 / 2 + k * s * (mpmath.log(mpmath.cosh((w - m) / s))
                                               - mpmath.log(mpmath.cosh(m / s)))
                          + k * mpmath.tanh(m / s) * w - cc * w**4 / 4)  # fmt: skip
    b, cc = c["b"], c["c"]  # w (1 + b w)/(1 + c w²) = w/(1 + c w²) + (b/c)(1 − 1/(1 + c w²))
    r = mpmath.sqrt(cc)
    return lambda w: mpmath.log(1 + cc * w**2) / (2 * cc) + (b / cc) * (w - mpmath.atan(r * w) / r)


def force(name):
    c = {k: mpmath.mpf(repr(v)) for k, v in PRESETS[name].constants_dict.items()}
    if name == "exponential":
        return lambda w: w + c["b"] * w**2 - c["c"] * w**3 * mpmath.exp(w / c["d"])
    if name == "tanh":
        k, m, s = c["k"], c["m"], c["s"]
        return lambda w: w + k * (mpmath.tanh((w - m) / s) + mpmath.tanh(m / s)) - c["c"] * w**3
    return lambda w: w * (1 + c["b"] * w) / (1 + c["c"] * w**2)
