"""Bounds on a force-law text before any algebra: degree, exponents, number sizes, nesting.

SymPy expands what it is given exactly: ``(w+1)**100000`` (degree 100000), ``w**99999999``,
``w*9**9**9`` (an integer of 370 million digits) or ``(1/2)**(10**100)`` each run for minutes or
exhaust memory, and a thread running them cannot be interrupted.  :func:`screen` reads the token
stream once (a recursive-descent parser of the grammar SymPy is given: numbers, ``w``, ``pi``,
``E``, the allowed functions, + - * / ** ^ ( ) and juxtaposition) and computes for every
subexpression an upper bound on

* its degree in w (sums: max; products: sum; powers: degree × exponent) — at most
  :data:`~fpucore.law.polynomial.MAX_DEGREE` — and its lowest power of w (a quotient by w**k
  lowers it) — at least −MAX_DEGREE;
* that it stays a Laurent polynomial in w, whose terms SymPy collects by power: a divisor, or
  a base raised to a negative power, that depends on w must be a monomial (c·w**k), and a power
  of an expression in w an integer.  ``(1/(w+1) + 1/(w+2) + … + 1/(w+5))**8`` or
  ``(w**(1/3) + w**(1/5) + …)**8`` are never polynomials, yet their expansion has as many terms
  as a multinomial in several variables (8.7 s, 0.3 s; minutes for more terms);
* the exponent of every power of an expression in w (at most MAX_DEGREE) and of every number
  (at most :data:`MAX_EXPONENT`);
* the value of every constant subexpression, in floating point: beyond the float range
  (|x| > 1.8e308, or a nonzero power below 1e-330), complex (``sqrt(-1)``) or undefined (``1/0``)
  it could not be a coefficient of the law;
* the digits of its exact (rational) value, which SymPy's exact arithmetic would carry: at most
  :data:`MAX_DIGITS` (``((1 + 10**-15)**1000)**1000`` is a harmless float but 15 million digits);
  a literal counts the decimal digits of its value in any base (``0x`` + 255 f's has 308);
* the nesting depth (parentheses, unary signs, chained powers): at most :data:`MAX_DEPTH`, and
  the number of tokens: at most :data:`MAX_TOKENS`;

and refuses the text (ParameterError naming the real cause, e.g. "degree 100000 exceeds the
maximum 16") in microseconds.  What passes is bounded work for SymPy (≤ a few ms measured).
Integer literals are measured by their digits before any ``int()`` conversion.
"""

from __future__ import annotations

import math
import tokenize
from collections.abc import Callable
from dataclasses import dataclass
from typing import NoReturn

from fpucore.errors import ParameterError
from fpucore.law.polynomial import MAX_DEGREE

MAX_LENGTH = 1000  # characters (a degree-16 law with repr coefficients is ~ 500)
MAX_TOKENS = 256  # a degree-16 law is ~ 100 tokens; SymPy parses 256 in ~ 0.1 s
MAX_DEPTH = 32  # nested parentheses / signs / chained powers
MAX_EXPONENT = 1100  # |exponent| of a number (2**1023 is the largest power of 2 in float range)
MAX_DIGITS = 2000  # digits of an exact rational constant SymPy would carry
MAX_LITERAL_DIGITS = 330  # digits of a literal (float range: 309; a few leading zeros)
LOG10_MAX = math.log10(1.7976931348623157e308)
LOG10_MIN = -330.0  # below the smallest subnormal 4.9e-324: a literal would be 0 in float


@dataclass(frozen=True)
class Node:
    """Bounds of a subexpression: ``deg`` (upper bound on the degree in w, 0 for a constant),
    ``val`` (its float value when constant and real, else None), ``digits`` (size of its exact
    value; 0 once a float enters, as SymPy's Float has fixed precision), ``text``, ``lo`` (lower
    bound on its lowest power of w), ``hasw`` (it depends on w) and ``mono`` (a monomial c·w**k:
    a constant, w, and their products, quotients and integer powers)."""

    deg: float
    val: float | None
    digits: float
    text: str
    lo: float = 0.0
    hasw: bool = False
    mono: bool = True


def _product_val(a: float | None, b: float | None, op: str) -> float | None:
    if a is None or b is None or (op == "/" and b == 0.0):
        return None  # x/0: SymPy's zoo, refused later as a non-finite coefficient
    return a * b if op == "*" else a / b  # overflow gives inf: refused by check()


class _Screen:
    def __init__(self, expression: str, toks: list[tokenize.TokenInfo], valid: str, funcs, consts):
        self.expression, self.valid, self.funcs, self.consts = expression, valid, funcs, consts
        self.toks = [t for t in toks if t.type not in _SKIP]
        self.i = 0
        self.depth = 0

    # ----- helpers
    def refuse(self, reason: str) -> NoReturn:
        raise ParameterError("expression", abbreviate(self.expression), self.valid, reason)

    def peek(self) -> str:
        return self.toks[self.i].string if self.i < len(self.toks) else ""

    def take(self) -> tokenize.TokenInfo:
        t = self.toks[self.i]
        self.i += 1
        return t

    def enter(self):
        self.depth += 1
        if self.depth > MAX_DEPTH:
            self.refuse(f"nesting depth exceeds the maximum {MAX_DEPTH}")

    def check(self, node: Node) -> Node:
        if node.deg > MAX_DEGREE:
            self.refuse(
                f"degree {node.deg:.10g} of {abbreviate(node.text, 40)} exceeds the maximum "
                f"{MAX_DEGREE}"
            )
        if node.lo < -MAX_DEGREE:
            self.refuse(
                f"the power w^{node.lo:.10g} in {abbreviate(node.text, 40)} is below the "
                f"minimum w^-{MAX_DEGREE}"
            )
        if node.val is not None:
            if not math.isfinite(node.val):
                self.refuse(f"the number {abbreviate(node.text, 40)} exceeds the float range")
        elif not node.hasw:  # complex (sqrt(-1), (-8)**(1/3)), x/0, log(0): never a coefficient;
            # an imaginary unit would also be a second variable to SymPy's expansion (0.4 s)
            self.refuse(f"the constant {abbreviate(node.text, 40)} is not a finite real number")
        if node.digits > MAX_DIGITS:
            self.refuse(
                f"the exact value of {abbreviate(node.text, 40)} would have about "
                f"{node.digits:.3g} digits (maximum {MAX_DIGITS})"
            )
        return node

    # ----- grammar: sum := term (('+'|'-') term)*
    def sum_(self) -> Node:
        node = self.term()
        while self.peek() in ("+", "-"):
            op = self.take().string
            rhs = self.term()
            val = None
            if node.val is not None and rhs.val is not None:
                val = node.val + rhs.val if op == "+" else node.val - rhs.val
            hasw = node.hasw or rhs.hasw
            node = self.check(
                Node(
                    max(node.deg, rhs.deg),
                    val,
                    node.digits + rhs.digits,
                    f"{node.text}{op}{rhs.text}",
                    min(node.lo, rhs.lo),
                    hasw,
                    not hasw,
                )
            )
        return node

    # term := factor (('*'|'/') factor | factor)*   (juxtaposition = SymPy's implicit product)
    def term(self) -> Node:
        node = self.factor()
        while True:
            nxt = self.peek()
            if nxt in ("*", "/"):
                op = self.take().string
            elif nxt == "(" or (self.i < len(self.toks) and self.toks[self.i].type in _ATOMS):
                op = "*"
            else:
                return node
            rhs = self.factor()
            text = f"{node.text}{op}{rhs.text}"
            if op == "*":
                deg, lo = node.deg + rhs.deg, node.lo + rhs.lo
            else:  # SymPy cancels a monomial divisor term by term, never a sum
                if not rhs.mono:
                    self.refuse(
                        f"not a polynomial in w: {abbreviate(text, 40)} divides by "
                        f"{abbreviate(rhs.text, 30)}, a sum depending on w (a divisor may "
                        "depend on w only as c*w**k)"
                    )
                deg, lo = node.deg - rhs.lo, node.lo - rhs.deg
            node = self.check(
                Node(
                    deg,
                    _product_val(node.val, rhs.val, op),
                    node.digits + rhs.digits,
                    text,
                    lo,
                    node.hasw or rhs.hasw,
                    node.mono and rhs.mono,
                )
            )

    # factor := ('+'|'-') factor | power
    def factor(self) -> Node:
        if self.peek() in ("+", "-"):
            op = self.take().string
            self.enter()
            inner = self.factor()
            self.depth -= 1
            val = None if inner.val is None else (-inner.val if op == "-" else inner.val)
            return Node(
                inner.deg, val, inner.digits, op + inner.text, inner.lo, inner.hasw, inner.mono
            )
        return self.power()

    # power := atom (('**'|'^') factor)?   (right-associative; the exponent may carry a sign)
    def power(self) -> Node:
        base = self.atom()
        if self.peek() not in ("**", "^"):
            return base
        self.take()
        self.enter()
        exp = self.factor()
        self.depth -= 1
        text = f"{base.text}**{exp.text}"
        if exp.hasw:
            self.refuse(f"the exponent of {abbreviate(text, 40)} depends on w: not a polynomial")
        e = exp.val
        if e is None:
            self.refuse(f"the exponent of {abbreviate(text, 40)} is not a finite real number")
        if base.hasw:
            if abs(e) > MAX_DEGREE:
                self.refuse(
                    f"degree {abs(e) * max(base.deg, -base.lo, 1):.10g} of "
                    f"{abbreviate(text, 40)} exceeds the maximum {MAX_DEGREE}"
                )
            if not float(e).is_integer():
                self.refuse(
                    f"not a polynomial in w: {abbreviate(text, 40)} is a fractional power of an "
                    "expression in w"
                )
            if e < 0 and not base.mono:
                self.refuse(
                    f"not a polynomial in w: {abbreviate(text, 40)} is a negative power of a sum "
                    "depending on w"
                )
            deg, lo = (base.deg * e, base.lo * e) if e >= 0 else (base.lo * e, base.deg * e)
            return self.check(
                Node(deg, None, base.digits * max(abs(e), 1), text, lo, True, base.mono)
            )
        val = None
        b = base.val
        if b is not None and b != 0.0 and abs(b) != 1.0:  # its size first: the real cause
            lg = e * math.log10(abs(b))
            if lg > LOG10_MAX:
                self.refuse(
                    f"the number {abbreviate(text, 40)} (about 10^{lg:.3g}) exceeds the "
                    "float range (|x| <= 1.8e308)"
                )
            if lg < LOG10_MIN:
                self.refuse(
                    f"the number {abbreviate(text, 40)} (about 10^{lg:.3g}) is below the "
                    "float range (|x| >= 4.9e-324)"
                )
        if abs(e) > MAX_EXPONENT:  # a base near 1: its exact value would still be huge
            self.refuse(
                f"the exponent {e:.10g} of {abbreviate(text, 40)} exceeds the maximum "
                f"{MAX_EXPONENT}"
            )
        if b is not None and not (b == 0.0 and e <= 0):
            try:
                v = b**e
            except (OverflowError, ZeroDivisionError):
                v = None
            val = v if isinstance(v, float | int) else None  # a complex root: SymPy decides
        digits = base.digits * abs(e) if float(e).is_integer() else base.digits + exp.digits
        return self.check(Node(0.0, val, digits, text))

    # atom := NUMBER | w | pi | E | FUNC '(' sum ')' | '(' sum ')'
    def atom(self) -> Node:
        if self.i >= len(self.toks):
            self.refuse("could not parse: unexpected end of the expression")
        t = self.take()
        if t.type == tokenize.NUMBER:
            return self.check(parse_number(t.string, self.refuse))
        if t.type == tokenize.NAME:
            if t.string == "w":
                return Node(1.0, None, 0.0, "w", 1.0, True, True)
            if t.string in self.consts:
                return Node(0.0, math.pi if t.string == "pi" else math.e, 0.0, t.string)
            if t.string in self.funcs:
                if self.peek() != "(":
                    self.refuse(f"could not parse: {t.string} without '(...)'")
                self.take()
                self.enter()
                arg = self.sum_()
                self.depth -= 1
                self.expect_close()
                text = f"{t.string}({arg.text})"
                if arg.hasw:
                    self.refuse(
                        f"not a polynomial in w: {abbreviate(text, 40)} (functions of w, negative "
                        "or fractional powers are not allowed)"
                    )
                return self.check(Node(0.0, _function(t.string, arg.val), arg.digits, text))
        if t.string == "(":
            self.enter()
            inner = self.sum_()
            self.depth -= 1
            self.expect_close()
            return Node(
                inner.deg,
                inner.val,
                inner.digits,
                f"({inner.text})",
                inner.lo,
                inner.hasw,
                inner.mono,
            )
        self.refuse(f"could not parse: unexpected '{t.string}'")

    def expect_close(self):
        if self.peek() != ")":
            self.refuse("could not parse: missing ')'")
        self.take()


_SKIP = (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER, tokenize.INDENT, tokenize.DEDENT)
_ATOMS = (tokenize.NUMBER, tokenize.NAME)


def parse_number(text: str, refuse: Callable[[str], NoReturn]) -> Node:
    """A literal's float value, refused beyond the float range before any int() conversion; an
    integer's exact size is the decimal digits of its value, whatever its base."""
    chars = sum(ch.isalnum() for ch in text)  # digits of any base (and the 0x/0o/0b prefix)
    if chars > MAX_LITERAL_DIGITS:
        refuse(
            f"the literal {abbreviate(text, 24)} has {chars} digits (at most "
            f"{MAX_LITERAL_DIGITS}: beyond the float range)"
        )
    clean = text.replace("_", "")
    exact = not any(ch in clean.lower() for ch in ".e") or clean.lower().startswith("0x")
    try:
        # at most 330 characters: int() is linear in them for a base-2/8/16 literal, and below
        # CPython's 4300-digit limit for a decimal one
        n = int(clean, 0) if exact else None
    except ValueError:
        refuse(f"could not parse the number {abbreviate(text, 24)}")
    try:
        val = float(n) if exact else float(clean)  # type: ignore[arg-type]
    except OverflowError:
        val = math.inf
    except ValueError:
        refuse(f"could not parse the number {abbreviate(text, 24)}")
    if not math.isfinite(val):
        refuse(
            f"the literal {abbreviate(text, 24)} exceeds the float range (|x| <= 1.8e308): "
            "non-finite in double precision"
        )
    # decimal digits of the value: 0x + 255 f's is 1 token but 308 digits of SymPy's exact work
    digits = math.floor(n.bit_length() * math.log10(2)) + 1 if exact else 0.0  # type: ignore[union-attr]
    return Node(0.0, val, float(digits), text)


def _function(name: str, x: float | None) -> float | None:
    """A function of a constant, in float (None when not real); OverflowError → inf (refused)."""
    if x is None:
        return None
    fn = {
        "sin": math.sin,
        "cos": math.cos,
        "tan": math.tan,
        "exp": math.exp,
        "sinh": math.sinh,
        "cosh": math.cosh,
        "tanh": math.tanh,
        "abs": abs,
        "Abs": abs,
        "log": math.log,
        "sqrt": math.sqrt,
    }[name]
    try:
        return float(fn(x))  # type: ignore[operator]
    except OverflowError:
        return math.inf
    except ValueError:  # log/sqrt of a negative number or 0: complex or infinite, SymPy decides
        return None


def abbreviate(text: str, n: int = 80) -> str:
    """The text, cut to n characters with '...' (a refusal repeats the offending text)."""
    return text if len(text) <= n else text[: n - 3] + "..."


def screen(expression: str, toks: list[tokenize.TokenInfo], valid: str, funcs, consts) -> None:
    """Refuse (ParameterError) a law text whose algebra would not be bounded (module docstring).
    ``toks``: its token stream, already restricted to the allowed tokens."""
    s = _Screen(expression, toks, valid, funcs, consts)
    if len(s.toks) > MAX_TOKENS:
        s.refuse(f"{len(s.toks)} terms and operators exceed the maximum {MAX_TOKENS}")
    s.sum_()
    if s.i != len(s.toks):
        s.refuse(f"could not parse: unexpected '{s.peek()}'")
