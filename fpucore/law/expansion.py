"""Expansion of a parsed force-law text into its coefficients, by exact arithmetic.

SymPy's ``expand`` builds every intermediate term as a symbolic object (~1 ms each: the product
(w+1)*(w+2)*...*(w+16) took 0.1-0.15 s, a few of them a second); here a polynomial is a dict
{power of w: coefficient} of at most 33 entries (the screen of :mod:`.expression_bounds` bounds
the powers to [-16, 16] and the exact numbers to 2000 digits).  Imported, with SymPy and mpmath,
only when a law text is parsed.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from fractions import Fraction
from typing import NoReturn

import mpmath

from fpucore.law.expression_bounds import abbreviate

Refuse = Callable[[str], NoReturn]  # raises ParameterError naming the reason

PREC = 128  # bits of an inexact coefficient (SymPy's 30-digit constants carry 100)


def expand(expr, w, refuse: Refuse) -> dict:
    """{power of w: coefficient} of the parsed text ``expr`` (see :func:`laurent`); ``refuse``
    raises the ParameterError with a reason."""
    with mpmath.workprec(PREC):
        return laurent(expr, w, refuse)


def laurent(expr, w, refuse: Refuse) -> dict:
    """The coefficients {power of w: c} of the parsed, unevaluated text: sums, products and
    powers of w and numbers (the screen has bounded them).  A coefficient is exact (Fraction)
    while every number it comes from is rational, else an mpmath number of :data:`PREC` bits:
    an exact product of floats would grow without bound (the screen sizes only rationals)."""
    if expr == w:
        return {1: Fraction(1)}
    if expr.is_Rational:
        return {0: Fraction(int(expr.p), int(expr.q))}
    if expr.is_Float and expr.is_finite:
        return {0: mpmath.mpf(expr)}
    if expr.is_Add or expr.is_Mul:
        out = laurent(expr.args[0], w, refuse)
        for arg in expr.args[1:]:
            out = (_add if expr.is_Add else _mul)(out, laurent(arg, w, refuse))
        return out
    if expr.is_Pow:
        base, exp = laurent(expr.base, w, refuse), laurent(expr.exp, w, refuse)
        e = exp.get(0, Fraction(0))
        if any(c for k, c in exp.items() if k != 0):
            refuse(f"not a polynomial in w: {abbreviate(str(expr), 60)} (exponent depends on w)")
        if e == int(e):
            return _power(base, int(e), expr, refuse)
        if any(c for k, c in base.items() if k != 0):
            refuse(f"not a polynomial in w: {abbreviate(str(expr), 60)} (a fractional power)")
        b = _mp(base.get(0, Fraction(0)))
        if b < 0:
            refuse(f"a coefficient is not real: {abbreviate(str(expr), 40)}")
        if b == 0 and e < 0:
            refuse("non-finite coefficient")
        return {0: _mp(b) ** _mp(e)}
    if expr.is_number and not expr.is_finite:
        refuse("non-finite coefficient")
    if expr.is_number and expr.is_real is False:
        refuse(f"a coefficient is not real: {str(expr)[:40]}")
    refuse(
        f"not a polynomial in w: {abbreviate(str(expr), 60)} (functions of w, negative or "
        "fractional powers are not allowed)"
    )


def _mp(x):
    return mpmath.mpf(x.numerator) / x.denominator if isinstance(x, Fraction) else x


def _num(op, a, b):
    if isinstance(a, Fraction) and isinstance(b, Fraction):
        return op(a, b)
    return op(_mp(a), _mp(b))


def _add(p: dict, q: dict) -> dict:
    out = dict(p)
    for k, c in q.items():
        out[k] = _num(operator.add, out[k], c) if k in out else c
    return out


def _mul(p: dict, q: dict) -> dict:
    out: dict = {}
    for i, a in p.items():
        for j, b in q.items():
            c = _num(operator.mul, a, b)
            out[i + j] = _num(operator.add, out[i + j], c) if i + j in out else c
    return out


def _power(base: dict, n: int, expr, refuse: Refuse) -> dict:
    if n < 0:
        nonzero = [(k, c) for k, c in base.items() if c]
        if not nonzero:
            refuse(f"non-finite coefficient: {abbreviate(str(expr), 40)} divides by zero")
        if len(nonzero) != 1:  # refused by the screen before (a negative power of a sum)
            refuse(f"not a polynomial in w: {abbreviate(str(expr), 60)}")
        ((k, c),) = nonzero
        return {k * n: c**n}  # c != 0; a Fraction's negative power is exact
    out = {0: Fraction(1)}
    for _ in range(n):  # n <= MAX_EXPONENT (a number) or MAX_DEGREE (an expression in w)
        out = _mul(out, base)
    return out
