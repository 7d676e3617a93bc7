"""Smooth force-law texts: ``"w + b*w**2 - c*w**3*exp(w/d)"`` → a SymPy expression, parse only.

The text is tokenized (standard library), ``^`` becomes ``**`` and juxtaposition (``2w``,
``2(w+1)``) a product; the result is parsed by :func:`ast.parse` (never evaluated) and the tree
is walked with an allow-list: numbers, the variable ``w``, ``pi``, ``E``, named constants (given
separately), the functions of :data:`FUNCS` with one argument, unary ± and the binary operators
+ − * / **.  SymPy objects are built from the allowed nodes only.  Bounds, checked in the walk
before SymPy sees a node: :data:`MAX_LENGTH` characters, :data:`MAX_TOKENS` tokens,
:data:`MAX_DEPTH` nesting, literals within the float range, powers of numbers with
|exponent| ≤ :data:`MAX_EXPONENT` and a finite float value, powers of an expression in w with a
numeric (rational) exponent of at most :data:`MAX_POWER` in size.  A refusal costs microseconds.
"""

from __future__ import annotations

import ast
import functools
import io
import keyword
import math
import re
import tokenize

import numpy as np

from fpucore.errors import ParameterError
from fpucore.law.expression_bounds import (
    MAX_DEPTH,
    MAX_LENGTH,
    MAX_TOKENS,
    abbreviate,
    parse_number,
)

FUNCS = ("exp", "log", "sqrt", "tanh", "sinh", "cosh", "atan")
CONSTS = ("pi", "E")
MAX_EXPONENT = 1100  # |exponent| of a number
MAX_POWER = 64  # |exponent| of a power of an expression in w
MAX_DENOMINATOR = 10**6  # of a rational exponent of an expression in w
NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,31}\Z")
VALID = (
    "a smooth expression in w built from numbers, named constants, + - * / ** (or ^), "
    f"{', '.join(FUNCS)}, pi, E, with f(0) = 0, e.g. 'w + b*w**2 - c*w**3*exp(w/d)' "
    "with constants b=10, c=1, d=50"
)
_OPS = {"+", "-", "*", "/", "**", "^", "(", ")"}
_SKIP = (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER, tokenize.INDENT, tokenize.DEDENT)


def refuse(text: str, reason: str, name: str = "expression"):
    raise ParameterError(name, abbreviate(text), VALID, reason)


def check_constant_name(name) -> str:
    """A constant's name: an identifier of ≤ 32 characters, not w, a function, pi/E or a Python
    keyword."""
    if (
        not isinstance(name, str)
        or not NAME_RE.match(name)
        or keyword.iskeyword(name)
        or (name in ("w",) + FUNCS + CONSTS)
    ):
        raise ParameterError(
            "constants",
            name,
            "names of letters, digits and _ (a letter first, <= 32 characters) "
            f"other than w, pi, E and the functions {', '.join(FUNCS)}",
        )
    return name


def check_constant_value(name: str, value) -> float:
    """A constant's value: a finite real number (bool and strings refused)."""
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    if not ok:
        try:
            ok = isinstance(value, np.integer | np.floating)
        except ImportError:  # pragma: no cover
            ok = False
    if not ok or not math.isfinite(float(value)):
        raise ParameterError(name, value, "a finite real number", "the value of a named constant")
    return float(value)


def _tokens(text: str) -> list[tokenize.TokenInfo]:
    try:
        toks = list(tokenize.generate_tokens(io.StringIO(text).readline))
    except (tokenize.TokenError, SyntaxError, IndentationError) as exc:
        refuse(text, f"could not parse: {exc}")
    return [t for t in toks if t.type not in _SKIP]


def _source(text: str, names: frozenset) -> str:
    """The text with ^ → ** and juxtaposition → *, every token checked against the allow-list."""
    toks = _tokens(text)
    if len(toks) > MAX_TOKENS:
        refuse(text, f"{len(toks)} terms and operators exceed the maximum {MAX_TOKENS}")
    out: list[str] = []
    prev = None  # kind of the previous token: "atom" (number, name, ')'), "func", "op"
    for t in toks:
        if t.type == tokenize.NUMBER:
            if t.string[-1] in "jJ":
                refuse(text, f"complex number {t.string} not allowed")
            kind = "atom"
        elif t.type == tokenize.NAME:
            if t.string in FUNCS:
                kind = "func"
            elif t.string == "w" or t.string in CONSTS or t.string in names:
                kind = "atom"
            elif t.string in ("sin", "cos", "tan", "abs", "Abs"):
                refuse(
                    text, f"the function '{t.string}' is not allowed (allowed: {', '.join(FUNCS)})"
                )
            else:
                refuse(
                    text,
                    f"unknown name '{t.string}': the variable is w; give a named "
                    "constant's value separately (constants={'name': value}, CLI: "
                    "--const name=value)",
                )
        elif t.type == tokenize.OP and t.string in _OPS:
            kind = "open" if t.string == "(" else ("close" if t.string == ")" else "op")
        else:
            refuse(text, f"could not parse: unexpected '{t.string}'")
        # implicit product: atom followed by an atom, a function or '('
        if prev in ("atom", "close") and kind in ("atom", "func", "open"):
            out.append("*")
        out.append("**" if t.string == "^" else t.string)
        prev = kind
    return " ".join(out)


class _Walk:
    """The allowed AST → SymPy, with the bounds of the module docstring."""

    source: str  # the parsed source text, set by the caller (optional: error context only)

    def __init__(self, text: str, sp, w, symbols: dict):
        self.text, self.sp, self.w, self.symbols = text, sp, w, symbols
        self.nodes = 0

    def __call__(self, node, depth: int = 0):
        self.nodes += 1
        if depth > MAX_DEPTH:
            refuse(self.text, f"nesting depth exceeds the maximum {MAX_DEPTH}")
        sp = self.sp
        if isinstance(node, ast.Expression):
            return self(node.body, depth)
        if isinstance(node, ast.Constant):
            return self.number(node)
        if isinstance(node, ast.Name):
            if node.id == "w":
                return self.w
            if node.id == "pi":
                return sp.pi
            if node.id == "E":
                return sp.E
            return self.symbols[node.id]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            x = self(node.operand, depth + 1)
            return -x if isinstance(node.op, ast.USub) else x
        if isinstance(node, ast.BinOp):
            a = self(node.left, depth + 1)
            b = self(node.right, depth + 1)
            if isinstance(node.op, ast.Add):
                return a + b
            if isinstance(node.op, ast.Sub):
                return a - b
            if isinstance(node.op, ast.Mult):
                return a * b
            if isinstance(node.op, ast.Div):
                if b == 0:
                    refuse(self.text, "division by zero")
                return a / b
            if isinstance(node.op, ast.Pow):
                return self.power(a, b)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            if node.func.id in FUNCS and len(node.args) == 1 and not node.keywords:
                arg = self(node.args[0], depth + 1)
                if not arg.free_symbols:
                    self.constant_domain(node.func.id, arg)
                if node.func.id == "atan":
                    return sp.atan(arg)
                return getattr(sp, node.func.id)(arg)
            refuse(self.text, f"{node.func.id}(...) takes exactly one argument")
        refuse(self.text, f"could not parse: {type(node).__name__} is not allowed")

    def constant_domain(self, fn: str, arg) -> None:
        """A function of a number: real and finite, or refused with the reason."""
        try:
            x = float(arg)
        except (TypeError, ValueError, OverflowError):
            refuse(
                self.text,
                f"{fn}({abbreviate(str(arg), 30)}): the argument is not a finite real number",
            )
        if fn == "log" and not x > 0:
            refuse(self.text, f"log of a non-positive number: log({abbreviate(str(arg), 30)})")
        if fn == "sqrt" and not x >= 0:
            refuse(self.text, f"sqrt of a negative number: sqrt({abbreviate(str(arg), 30)})")
        if fn in ("exp", "sinh", "cosh") and abs(x) > 709.0:
            refuse(
                self.text, f"overflow of {fn}({abbreviate(str(arg), 30)}) (exceeds the float range)"
            )

    def number(self, node):
        v = node.value
        if isinstance(v, bool) or not isinstance(v, int | float):
            refuse(self.text, f"could not parse the literal {v!r}")
        src = ast.get_source_segment(self.source, node) if hasattr(self, "source") else None
        if isinstance(v, int):
            parse_number(str(v) if src is None else src, lambda r: refuse(self.text, r))
            return self.sp.Integer(v)
        if not math.isfinite(v):
            refuse(self.text, f"the literal {src or v} exceeds the float range")
        # the decimal the user typed, exactly (the 30-digit references see the same law)
        txt = src if src is not None else repr(v)
        try:
            return self.sp.Rational(txt.replace("_", ""))
        except (TypeError, ValueError):
            return self.sp.Rational(repr(v))

    def power(self, a, b):
        sp = self.sp
        if b.has(self.w):
            refuse(
                self.text,
                f"the exponent of ({abbreviate(str(a), 30)})**"
                f"({abbreviate(str(b), 30)}) depends on w",
            )
        if b.free_symbols:  # an exponent with named constants: its value is checked on use
            return sp.Pow(a, b)
        try:
            e = float(b)
        except (TypeError, ValueError):
            refuse(self.text, f"the exponent {abbreviate(str(b), 30)} is not a real number")
        if not math.isfinite(e):
            refuse(self.text, f"the exponent {abbreviate(str(b), 30)} is not finite")
        if a.has(self.w):
            if abs(e) > MAX_POWER:
                refuse(
                    self.text,
                    f"the exponent {e:.10g} of an expression in w exceeds the "
                    f"maximum {MAX_POWER} in size",
                )
            if isinstance(b, sp.Rational) and b.q > MAX_DENOMINATOR:
                refuse(self.text, f"the exponent {b} has a denominator above {MAX_DENOMINATOR}")
            if not isinstance(b, sp.Rational):
                b = sp.nsimplify(e, rational=True)  # an irrational number: its 17-digit value
            return sp.Pow(a, b)
        if a.free_symbols:
            return sp.Pow(a, b)
        # a power of numbers: its size first (SymPy would compute 9**9**9 exactly)
        try:
            base = float(a)
        except (TypeError, ValueError, OverflowError):
            refuse(self.text, f"the number {abbreviate(str(a), 30)} is not a finite real number")
        if abs(e) > MAX_EXPONENT:
            refuse(
                self.text, f"the exponent {e:.10g} of a number exceeds the maximum {MAX_EXPONENT}"
            )
        if base != 0.0 and abs(base) != 1.0:
            lg = e * math.log10(abs(base))
            if not -330.0 < lg < 308.25:
                refuse(
                    self.text,
                    f"the number {abbreviate(str(a), 20)}**{abbreviate(str(b), 20)} "
                    f"(about 10^{lg:.3g}) is outside the float range",
                )
        if base < 0 and not float(e).is_integer():
            refuse(
                self.text,
                f"the number ({abbreviate(str(a), 20)})**{abbreviate(str(b), 20)} "
                "is not real (a fractional power of a negative number)",
            )
        if base == 0 and e <= 0:
            refuse(self.text, "0 raised to a power <= 0 is not finite")
        return sp.Pow(a, b)


@functools.lru_cache(maxsize=64)
def parse_smooth(text: str, names: frozenset):
    """(expr, w, {name: Symbol}) for a law text with the named constants ``names`` (a frozenset):
    a SymPy expression in the real symbol w, parse only (module docstring).  Cached per text:
    a slider moving one constant does not parse again."""
    if not isinstance(text, str):
        raise ParameterError("expression", text, VALID, "the expression must be a string")
    if not text.strip():
        refuse(text, "empty expression")
    if len(text) > MAX_LENGTH:
        refuse(text, f"{len(text)} characters exceed the maximum {MAX_LENGTH}")
    one_line = " ".join(text.split())
    src = _source(one_line, names)
    try:
        tree = ast.parse(src, mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
        refuse(text, f"could not parse: {type(exc).__name__}: {getattr(exc, 'msg', exc)}")
    import sympy as sp

    # no assumptions: SymPy's diff then skips assumption queries (3x faster for exp laws)
    w = sp.Symbol("w")
    symbols = {n: sp.Symbol(n) for n in sorted(names)}
    walk = _Walk(text, sp, w, symbols)
    walk.source = src
    expr = walk(tree)
    if not expr.has(w):
        refuse(text, "the expression does not depend on w")
    unused = sorted(n for n, s in symbols.items() if not expr.has(s))
    if unused:
        refuse(
            text,
            f"the constant(s) {', '.join(unused)} do not appear in the expression",
            "constants",
        )
    return expr, w, symbols
