"""Evaluation of a parsed smooth law without ``eval``: a SymPy expression → a tree of closures.

Three back ends walk the same tree: NumPy float64 (the law's ``f, df, ddf``), NumPy longdouble
(the 64-bit-mantissa values the Chebyshev representation is fitted to, :mod:`.chebyshev`) and
mpmath at any precision (the extended-precision references of the error measurement and of the
roots α, β, w*).  :func:`diagnose` walks the tree in Python floats at one strain and names the
first operation that leaves the real numbers or the float range (log of a non-positive number,
a fractional power of a negative one, exp overflow, division by zero).
"""

from __future__ import annotations

import math

import sympy as sp

from fpucore.law.smooth_tree import compile_node


class UnsupportedNode(ValueError):
    """A SymPy node outside the allow-list (e.g. Abs from sqrt(w**2))."""


_FN_NAMES = {
    sp.exp: "exp",
    sp.log: "log",
    sp.tanh: "tanh",
    sp.sinh: "sinh",
    sp.cosh: "cosh",
    sp.atan: "atan",
}


def to_node(e, w) -> tuple:
    """The SymPy expression as plain tuples (:mod:`.smooth_tree`); UnsupportedNode outside the
    allow-list (e.g. Abs)."""
    if e == w:
        return ("w",)
    if e.is_Symbol:
        return ("const", e.name)
    if isinstance(e, sp.Rational):
        return ("num", int(e.p), int(e.q))
    if e.is_Number or e.is_NumberSymbol:
        return ("flt", str(sp.N(e, 40)))
    if e.is_Add:
        return ("add", tuple(to_node(a, w) for a in e.args))
    if e.is_Mul:
        return ("mul", tuple(to_node(a, w) for a in e.args))
    if e.is_Pow:
        base, ex = to_node(e.base, w), e.exp
        if ex.is_Integer:
            return ("ipow", base, int(ex))
        if isinstance(ex, sp.Rational):
            return ("rpow", base, int(ex.p), int(ex.q))
        return ("pow", base, to_node(ex, w))
    name = _FN_NAMES.get(e.func)
    if name is None or len(e.args) != 1:
        raise UnsupportedNode(f"{e.func.__name__} is not a smooth function of the allow-list")
    return ("fn", name, to_node(e.args[0], w))


def compile_tree(expr, w, values: dict, backend: str):
    """A function x ↦ expr(x) on the back end ``"float"``, ``"long"`` (NumPy arrays) or ``"mp"``
    (one mpmath number at the current mpmath precision); named constants from ``values``
    ({Symbol: float})."""
    return compile_node(to_node(expr, w), {k.name: v for k, v in values.items()}, backend)


def _reason(e, w, x: float, values: dict) -> tuple[float, str | None]:
    """(value, None) or (nan, reason) for one float x: the first failing operation, innermost."""
    if e == w:
        return x, None
    if e.is_Symbol:
        return float(values[e]), None
    if e.is_Number or e.is_NumberSymbol:
        return float(e), None
    vals = []
    for a in e.args:
        v, why = _reason(a, w, x, values)
        if why:
            return math.nan, why
        vals.append(v)
    txt = sp.sstr(e)
    txt = txt if len(txt) <= 40 else txt[:37] + "..."
    try:
        if e.is_Add:
            out = math.fsum(vals)
        elif e.is_Mul:
            out = math.prod(vals)
        elif e.is_Pow:
            b, k = vals
            if b == 0.0 and k < 0:
                return math.nan, f"division by zero in {txt}"
            if b < 0 and not float(k).is_integer():
                return math.nan, (
                    f"a fractional power of a negative number in {txt} (base {b:.6g})"
                )
            out = b**k
        elif e.func == sp.log:
            if vals[0] <= 0:
                return math.nan, f"log of a non-positive number in {txt} (argument {vals[0]:.6g})"
            out = math.log(vals[0])
        else:
            out = {
                sp.exp: math.exp,
                sp.tanh: math.tanh,
                sp.sinh: math.sinh,
                sp.cosh: math.cosh,
                sp.atan: math.atan,
            }[e.func](vals[0])
    except OverflowError:
        return math.nan, f"overflow of {txt} (exceeds the float range)"
    except ZeroDivisionError:
        return math.nan, f"division by zero in {txt}"
    if isinstance(out, complex) or not math.isfinite(out):
        return math.nan, f"{txt} is not a finite real number"
    return float(out), None


def diagnose(expr, w, x: float, values: dict) -> str:
    """Why expr is not a finite real number at w = x (the first failing operation)."""
    why = _reason(expr, w, float(x), values)[1]
    return why or "a non-finite intermediate result"


def derivative(e, w):
    """d e / d w built unevaluated (SymPy's own ``diff`` spends ~0.1–0.3 s in assumption
    queries for an exp or tanh law); None for an identically zero derivative."""
    if e == w:
        return sp.Integer(1)
    if not e.has(w):
        return None
    if e.is_Add:
        terms = [t for t in (derivative(a, w) for a in e.args) if t is not None]
        return (
            None if not terms else (terms[0] if len(terms) == 1 else sp.Add(*terms, evaluate=False))
        )
    if e.is_Mul:
        terms = []
        for i, a in enumerate(e.args):
            da = derivative(a, w)
            if da is not None:
                rest = [b for j, b in enumerate(e.args) if j != i]
                terms.append(sp.Mul(*rest, da, evaluate=False))
        return (
            None if not terms else (terms[0] if len(terms) == 1 else sp.Add(*terms, evaluate=False))
        )
    if e.is_Pow:
        b, x = e.args
        db = derivative(b, w)
        if db is None:
            return None
        return sp.Mul(x, sp.Pow(b, x - 1, evaluate=False), db, evaluate=False)
    if len(e.args) != 1:
        raise UnsupportedNode(f"{e.func.__name__} is not a smooth function of the allow-list")
    u = e.args[0]
    du = derivative(u, w)
    if du is None:
        return None
    if e.func == sp.exp:
        outer = e
    elif e.func == sp.log:
        outer = sp.Pow(u, -1, evaluate=False)
    elif e.func == sp.tanh:
        outer = sp.Add(1, sp.Mul(-1, sp.Pow(e, 2, evaluate=False), evaluate=False), evaluate=False)
    elif e.func == sp.sinh:
        outer = sp.cosh(u, evaluate=False)
    elif e.func == sp.cosh:
        outer = sp.sinh(u, evaluate=False)
    elif e.func == sp.atan:
        outer = sp.Pow(sp.Add(1, sp.Pow(u, 2, evaluate=False), evaluate=False), -1, evaluate=False)
    else:
        raise UnsupportedNode(f"{e.func.__name__} is not a smooth function of the allow-list")
    return sp.Mul(outer, du, evaluate=False)
