"""A smooth law's expression as plain tuples, and its evaluation — without SymPy.

The parsed SymPy expression (:mod:`.smooth_parse`) is converted once into nested tuples
(:func:`fpucore.law.smooth_eval.to_node`); a law keeps those, so a law pickled to another process
(the explorer's server, an atlas worker) evaluates itself there without importing SymPy.  Nodes::

    ("w",)  ("const", name)  ("num", p, q)  (exact rational p/q)  ("flt", "digits")
    ("add", (a, b, ...))  ("mul", (a, b, ...))  ("ipow", base, k)  ("rpow", base, p, q)
    ("pow", base, exponent)  ("fn", "exp" | "log" | "tanh" | "sinh" | "cosh" | "atan", arg)

:func:`compile_node` turns a tree into a closure x ↦ value on the back end ``"float"`` (NumPy
float64), ``"long"`` (NumPy longdouble) or ``"mp"`` (mpmath at the current precision).
"""

from __future__ import annotations

import decimal

import numpy as np

_NP = {
    "exp": np.exp,
    "log": np.log,
    "tanh": np.tanh,
    "sinh": np.sinh,
    "cosh": np.cosh,
    "atan": np.arctan,
}


def _ratio(dt, p: int, q: int):
    """p/q in ``dt``.  An exact rational of hundreds of digits (e.g. 1.000…01**131 simplified)
    is divided in 40-digit decimal: p and q beyond ~1e300 would each round to inf (inf/inf =
    NaN), and ``str`` of an int over 4300 digits raises ValueError."""
    if max(abs(p).bit_length(), abs(q).bit_length()) < 1000:
        return dt(str(p)) / dt(str(q))
    return dt(str(decimal.Context(prec=40).divide(decimal.Decimal(p), decimal.Decimal(q))))


def compile_node(node: tuple, values: dict, backend: str):
    """x ↦ node(x); ``values`` {constant name: float}."""
    mp = backend == "mp"
    if mp:
        import mpmath

        fns = {
            "exp": mpmath.exp,
            "log": mpmath.log,
            "tanh": mpmath.tanh,
            "sinh": mpmath.sinh,
            "cosh": mpmath.cosh,
            "atan": mpmath.atan,
        }
        num = lambda p, q: mpmath.mpf(p) / q  # noqa: E731
        flt = mpmath.mpf
        const = mpmath.mpf
        sqrt, power = mpmath.sqrt, mpmath.power
    else:
        dt = np.float64 if backend == "float" else np.longdouble
        fns = _NP
        num = lambda p, q: _ratio(dt, p, q)  # noqa: E731
        flt = dt
        const = dt
        sqrt, power = np.sqrt, np.power

    def build(n):
        kind = n[0]
        if kind == "w":
            return lambda x: x
        if kind in ("const", "num", "flt"):
            c = (
                const(values[n[1]])
                if kind == "const"
                else (num(n[1], n[2]) if kind == "num" else flt(n[1]))
            )
            return lambda x: c
        if kind in ("add", "mul"):
            parts = [build(a) for a in n[1]]
            if kind == "add":

                def add(x):
                    acc = parts[0](x)
                    for p in parts[1:]:
                        acc = acc + p(x)
                    return acc

                return add

            def mul(x):
                acc = parts[0](x)
                for p in parts[1:]:
                    acc = acc * p(x)
                return acc

            return mul
        if kind == "ipow":
            base, k = build(n[1]), n[2]
            if mp:
                return lambda x: power(base(x), k)
            if k == 2:
                return lambda x: (lambda b: b * b)(base(x))
            if k == -1:
                return lambda x: 1 / base(x)
            return (lambda x: base(x) ** k) if k > 0 else (lambda x: 1 / base(x) ** (-k))
        if kind == "rpow":
            base, p, q = build(n[1]), n[2], n[3]
            if (p, q) == (1, 2):
                return lambda x: sqrt(base(x))
            if (p, q) == (-1, 2):
                return lambda x: 1 / sqrt(base(x))
            r = num(p, q)
            return lambda x: power(base(x), r)
        if kind == "pow":
            base, ex = build(n[1]), build(n[2])
            return lambda x: power(base(x), ex(x))
        if kind == "fn":
            fn, arg = fns[n[1]], build(n[2])
            return lambda x: fn(arg(x))
        raise ValueError(f"unknown node {kind!r}")

    return build(node)
