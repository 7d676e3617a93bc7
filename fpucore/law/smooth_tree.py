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
from collections.abc import Callable
from typing import Any

import numpy as np

#: the NumPy functions of the "float" and "long" back ends, by node name
NUMPY_FNS = {
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


def _last_value(fn: Callable[[Any], Any], context: Callable[[], Any]) -> Callable[[Any], Any]:
    """``fn`` remembering its last argument and value: a subtree shared by f, f′ and f″ (sinh(w)
    in all three of w·sinh(sinh(w))) is evaluated once per argument.  Identity, not equality:
    the argument is held, so its id cannot be reused, and the back ends that share (longdouble,
    mpmath) get fresh arrays and immutable numbers, never one buffer changed in place.  A value
    is reused only in the same ``context()`` (mpmath's working precision)."""
    last: list = [None, None, None]

    def cached(x: Any) -> Any:
        ctx = context()
        if last[0] is x and last[2] == ctx:
            return last[1]
        v = fn(x)
        last[0], last[1], last[2] = x, v, ctx
        return v

    return cached


def compile_node(node: tuple, values: dict, backend: str, shared: dict | None = None):
    """x ↦ node(x); ``values`` {constant name: float}.  Closures compiled with one ``shared``
    dict (longdouble and mpmath only: see :func:`_last_value`) evaluate a subtree that occurs
    several times, in one tree or across them, once per argument; the values are the same
    operations on the same numbers, bit for bit."""
    if shared is not None and backend == "float":
        raise ValueError("shared subtrees are for the 'long' and 'mp' back ends only")
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
        precision = lambda: mpmath.mp.prec  # noqa: E731
    else:
        dt = np.float64 if backend == "float" else np.longdouble
        fns = NUMPY_FNS
        num = lambda p, q: _ratio(dt, p, q)  # noqa: E731
        flt = dt
        const = dt
        sqrt, power = np.sqrt, np.power
        precision = lambda: None  # noqa: E731

    def build(n):
        if shared is None or n[0] in ("w", "const", "num", "flt"):
            return build_node(n)
        if n not in shared:
            shared[n] = _last_value(build_node(n), precision)
        return shared[n]

    def build_node(n):
        kind = n[0]
        if kind == "w":
            return lambda x: x
        if kind in ("const", "num", "flt"):

            def constant():
                if kind == "const":
                    return const(values[n[1]])
                return num(n[1], n[2]) if kind == "num" else flt(n[1])

            if mp:  # rounded at the working precision of the call, not of the compile
                return lambda x: constant()
            c = constant()
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
