"""Force laws from text: ``law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")``.

The text is tokenized (standard library) and only numbers, the operators + - * / ** ^ ( ), the
variable ``w`` and a few function names (so that ``sin(w)`` is reported as *not a polynomial*
rather than as an unknown name) reach SymPy's parser, unevaluated, after the bounds of
:mod:`.expression_bounds`; the text is then expanded by exact rational arithmetic (inexact numbers
at 128 bits), not by SymPy; the coefficients must be real and finite and the constant term
zero.  The result is a :class:`.PolynomialLaw`, whose construction checks the
hardening–softening hypotheses of paper §2.
"""

from __future__ import annotations

import io
import math
import tokenize
from collections.abc import Mapping
from typing import NoReturn

from fpucore.errors import ParameterError
from fpucore.law.base import HardeningSofteningLaw
from fpucore.law.expression_bounds import MAX_LENGTH, abbreviate, screen
from fpucore.law.piecewise_text import is_piecewise_text, law_from_piecewise_text
from fpucore.law.polynomial import MAX_DEGREE, PolynomialLaw
from fpucore.law.smooth import SmoothLaw, checked_constants

_FUNCS = ("sin", "cos", "tan", "exp", "log", "sqrt", "sinh", "cosh", "tanh", "Abs", "abs")
_CONSTS = ("pi", "E")
_OPS = {"+", "-", "*", "/", "**", "^", "(", ")"}
_VALID = (
    f"a polynomial in w of degree <= {MAX_DEGREE} with real finite coefficients and f(0) = 0, "
    "e.g. 'w + 10*w**2 - w**3'"
)


_DIGITS = 30  # precision of constants such as sqrt(2), pi (the coefficients are then rounded)


def _numeric(fn):
    """``fn`` of a number, unevaluated (SymPy's ``sqrt(9...9)`` would try to factor its argument:
    80 ms for 200 digits), then evaluated numerically to :data:`_DIGITS` digits."""
    return lambda *args, **_: fn(*args, evaluate=False).evalf(_DIGITS)


def law_from_expression(
    expression: str, constants: Mapping[str, float] | None = None
) -> HardeningSofteningLaw:
    """A force law from text: a :class:`PolynomialLaw` when the text is a polynomial in w (the
    same law, bit for bit, as before smooth laws existed), else a
    :class:`~fpucore.law.SmoothLaw` (exp, log, sqrt, tanh, sinh, cosh, atan, rational and
    integer powers, quotients).

    ``constants``: {name: value} of named constants in the text, e.g.
    ``law_from_expression("w + b*w**2 - c*w**3*exp(w/d)", {"b": 10, "c": 1, "d": 50})``; a
    polynomial text with constants is the polynomial with their values (``repr``) put in.
    Refused with :class:`ParameterError` (name ``"expression"``, or the constant's name) with
    the reason.

    Piecewise-linear laws: ``trilinear(w1=.., w2=.., E1=.., E2=.., E3=..)`` or
    ``piecewise(breakpoints=[..], slopes=[..])`` (parsed, never evaluated, by
    :func:`fpucore.law.piecewise_text.law_from_piecewise_text`; no constants).
    """
    if is_piecewise_text(expression):
        if constants:
            raise ParameterError(
                "constants", constants, "none", "a piecewise-linear law takes its numbers inline"
            )
        return law_from_piecewise_text(expression)

    consts = checked_constants(constants)
    text = expression
    if consts and isinstance(expression, str) and len(expression) <= MAX_LENGTH:
        text = _substitute(expression, dict(consts))
        unused = [n for n, _ in consts if f"({dict(consts)[n]!r})" not in text]
        if unused:
            raise ParameterError(
                "constants",
                ", ".join(unused),
                "names that appear in the expression",
                f"the constant(s) {', '.join(unused)} do not appear in {abbreviate(expression)}",
            )
    try:
        return polynomial_law_from_expression(text)
    except ParameterError as exc:
        if not _not_polynomial(exc):
            raise
    return SmoothLaw(expression, consts)


_NOT_POLY = ("not a polynomial", "depends on w", "unknown name", "could not parse: unexpected '='")


def _not_polynomial(exc: ParameterError) -> bool:
    """A refusal of the polynomial route that the smooth route may answer (a function of w, a
    quotient, a fractional power, a name outside the polynomial grammar)."""
    return any(k in exc.reason for k in _NOT_POLY)


def _substitute(text: str, values: dict) -> str:
    """The text with each named constant replaced by ``(repr(value))`` (token by token)."""
    try:
        toks = list(tokenize.generate_tokens(io.StringIO(" ".join(text.split())).readline))
    except (tokenize.TokenError, SyntaxError, IndentationError):
        return text
    out = []
    for t in toks:
        if t.type == tokenize.NAME and t.string in values:
            out.append(f"({values[t.string]!r})")
        elif t.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER):
            out.append(t.string)
    return " ".join(out)


def polynomial_law_from_expression(expression: str) -> PolynomialLaw:
    """Build a :class:`PolynomialLaw` from text, e.g. ``"w + 10*w**2 - w**3 - 0.01*w**4"``.

    The text is tokenized first and only numbers, the operators + - * / ** ^ ( ), the variable
    ``w`` and a few function names (so that ``sin(w)`` is reported as *non-polynomial* rather
    than *unknown*) are let through to SymPy's parser (``^`` means power, ``2w`` means 2*w).
    Refused with :class:`ParameterError` (name ``"expression"``), in microseconds and before any
    algebra, when the degree, an exponent, a number or the nesting exceeds the bounds of
    :mod:`.expression_bounds` (degree <= MAX_DEGREE); then unparsable text, unknown names,
    non-polynomial expressions, non-real or non-finite coefficients, a constant term (f(0) ≠ 0);
    the law's own hypotheses are then checked by :class:`PolynomialLaw`.

    """
    if not isinstance(expression, str):
        raise ParameterError("expression", expression, _VALID, "the expression must be a string")
    if not expression.strip():
        raise ParameterError("expression", expression, _VALID, "empty expression")
    if len(expression) > MAX_LENGTH:
        raise ParameterError(
            "expression",
            abbreviate(expression),
            _VALID,
            f"{len(expression)} characters exceed the maximum {MAX_LENGTH}",
        )
    # one line, single spaces: a leading space or a line break is not Python indentation here
    text = " ".join(expression.split())
    try:
        toks = list(tokenize.generate_tokens(io.StringIO(text).readline))
    except (tokenize.TokenError, SyntaxError, IndentationError) as exc:
        raise ParameterError("expression", expression, _VALID, f"could not parse: {exc}") from None
    for t in toks:
        if t.type in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER):
            continue
        if t.type == tokenize.NUMBER:
            if t.string[-1] in "jJ":
                raise ParameterError(
                    "expression", expression, _VALID, f"complex number {t.string} not allowed"
                )
            continue
        if t.type == tokenize.NAME:
            if t.string != "w" and t.string not in _FUNCS + _CONSTS:
                raise ParameterError(
                    "expression",
                    expression,
                    _VALID,
                    f"unknown name '{t.string}': the only variable allowed is w",
                )
            continue
        if t.type == tokenize.OP and t.string in _OPS:
            continue
        raise ParameterError(
            "expression", expression, _VALID, f"could not parse: unexpected '{t.string}'"
        )
    # degree, exponents, number sizes and nesting bounded before SymPy expands anything: SymPy's
    # exact algebra on (w+1)**100000 or 9**9**9 runs for minutes and cannot be interrupted
    screen(expression, toks, _VALID, _FUNCS, _CONSTS)
    # SymPy (~0.3 s) is imported on first use, not by every `import fpucore`: the CLI, the
    # server and each worker pool start without it unless a law is typed
    import sympy
    from sympy.parsing.sympy_parser import (
        convert_xor,
        implicit_multiplication,
        parse_expr,
        standard_transformations,
    )

    from fpucore.law.expansion import expand

    w = sympy.Symbol("w", real=True)
    # constants become 30-digit numbers at once (the screen has refused functions of w): a power
    # of a sum of symbolic constants, (w + sqrt(2) + sqrt(3) + pi + E)**16, expands into
    # thousands of symbolic terms; numbers merge, so the expansion stays at degree + 1 terms
    names = {"w": w, "pi": sympy.pi.evalf(_DIGITS), "E": sympy.E.evalf(_DIGITS)}
    names.update({n: _numeric(getattr(sympy, "Abs" if n == "abs" else n)) for n in _FUNCS})
    glob = {
        n: getattr(sympy, n)
        for n in ("Integer", "Float", "Rational", "Symbol", "Add", "Mul", "Pow")
    }
    glob["__builtins__"] = {}
    try:
        # unevaluated: SymPy's own evaluation of 9...9**(1/2) factors the integer (80 ms for 200
        # digits) and its expand() costs ~1 ms a term ((w+1)*...*(w+16): 0.1-0.15 s)
        expr = parse_expr(
            text,
            local_dict=names,
            global_dict=glob,
            transformations=standard_transformations + (convert_xor, implicit_multiplication),
            evaluate=False,
        )
    except Exception as exc:  # SymPy raises SyntaxError, TypeError, TokenError, SympifyError...
        raise ParameterError(
            "expression", expression, _VALID, f"could not parse: {type(exc).__name__}: {exc}"
        ) from None

    def refuse(reason: str) -> NoReturn:
        raise ParameterError("expression", abbreviate(expression), _VALID, reason)

    # expanded here, exactly while the numbers are rational (module docstring of _laurent)
    terms = expand(sympy.sympify(expr), w, refuse)
    if any(k < 0 for k, c in terms.items() if c):
        refuse(
            f"not a polynomial in w: {abbreviate(str(expr), 60)} (functions of w, negative or "
            "fractional powers are not allowed)"
        )
    coeffs: list[float] = []
    for k, ck in sorted(terms.items()):
        if k < 0:  # a zero coefficient of a negative power (0/w)
            continue
        try:
            z = float(ck)
        except OverflowError:
            z = math.inf
        if not math.isfinite(z):
            refuse(f"non-finite coefficient of w^{k}: {str(ck)[:24]}... overflows float64")
        while len(coeffs) < k + 1:
            coeffs.append(0.0)
        coeffs[k] = z
    while coeffs and coeffs[-1] == 0.0:
        coeffs.pop()
    if not coeffs:
        raise ParameterError("expression", expression, _VALID, "the expression is zero")
    if coeffs[0] != 0.0:
        raise ParameterError(
            "expression",
            expression,
            _VALID,
            f"constant term {coeffs[0]:g}: f(0) must be 0 (the unstrained spring carries no force)",
        )
    return PolynomialLaw(tuple(coeffs[1:]))
