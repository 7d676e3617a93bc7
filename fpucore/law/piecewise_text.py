"""The text form of piecewise-linear laws, parsed (Python's ``ast``), never evaluated::

    trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)
    piecewise(breakpoints=[0.5, 1.5, 3], slopes=[1, 4, 0.5, 0.1])

Only one call with keyword arguments whose values are numbers (a unary sign allowed) or lists of
numbers is accepted; anything else is refused with :class:`ParameterError` naming ``expression``.
"""

from __future__ import annotations

import ast
from typing import cast

from fpucore.errors import ParameterError
from fpucore.law.piecewise import PiecewiseLinearLaw, TrilinearLaw

_TEXT_VALID = (
    "trilinear(w1=..., w2=..., E1=..., E2=..., E3=...) or "
    "piecewise(breakpoints=[b1, b2, ...], slopes=[s0, s1, ...]) with numbers only"
)
_TEXT_MAX = 2000


def is_piecewise_text(text) -> bool:
    """True when the text is meant as a PL law (starts with ``trilinear(`` or ``piecewise(``)."""
    if not isinstance(text, str):
        return False
    head = text.strip().split("(", 1)[0].strip().lower()
    return head in ("trilinear", "piecewise")


def _number(node, text: str) -> float:
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        v = _number(node.operand, text)
        return -v if isinstance(node.op, ast.USub) else v
    if (
        isinstance(node, ast.Constant)
        and type(node.value) in (int, float)
        and isinstance(node.value, (int, float))  # the same test, for the type checker
    ):
        return float(node.value)
    raise ParameterError(
        "expression",
        text,
        _TEXT_VALID,
        f"only numbers are allowed as values, got {ast.dump(node)[:60]}",
    )


def law_from_piecewise_text(text: str) -> TrilinearLaw | PiecewiseLinearLaw:
    """Parse (never evaluate) a PL law's text form (module docstring) into a
    :class:`TrilinearLaw` or :class:`PiecewiseLinearLaw`; ParameterError naming ``expression``
    for malformed text, then the law's own checks name the offending argument."""
    if not isinstance(text, str) or not text.strip():
        raise ParameterError("expression", text, _TEXT_VALID, "empty or not a string")
    if len(text) > _TEXT_MAX:
        raise ParameterError(
            "expression", text[:40] + "...", _TEXT_VALID, f"longer than {_TEXT_MAX} characters"
        )
    try:
        tree = ast.parse(" ".join(text.split()), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
        raise ParameterError("expression", text, _TEXT_VALID, f"could not parse: {exc}") from None
    call = tree.body
    if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)):
        raise ParameterError("expression", text, _TEXT_VALID, "expected one call")
    kind = call.func.id.lower()
    if kind not in ("trilinear", "piecewise") or call.args:
        raise ParameterError(
            "expression", text, _TEXT_VALID, "keyword arguments of trilinear(...) or piecewise(...)"
        )
    kw: dict[str, float | tuple[float, ...]] = {}
    for k in call.keywords:
        if k.arg is None or k.arg in kw:
            raise ParameterError(
                "expression", text, _TEXT_VALID, f"bad or repeated keyword {k.arg}"
            )
        if isinstance(k.value, (ast.List, ast.Tuple)):
            kw[k.arg] = tuple(_number(e, text) for e in k.value.elts)
        else:
            kw[k.arg] = _number(k.value, text)
    want = ("w1", "w2", "E1", "E2", "E3") if kind == "trilinear" else ("breakpoints", "slopes")
    if set(kw) != set(want):
        missing, extra = sorted(set(want) - set(kw)), sorted(set(kw) - set(want))
        raise ParameterError(
            "expression",
            text,
            _TEXT_VALID,
            f"{kind} takes exactly {', '.join(want)}"
            + (f"; missing {', '.join(missing)}" if missing else "")
            + (f"; unknown {', '.join(extra)}" if extra else ""),
        )
    if kind == "trilinear":
        for n in want:
            if isinstance(kw[n], tuple):
                raise ParameterError("expression", text, _TEXT_VALID, f"{n} must be one number")
        return TrilinearLaw(**cast(dict[str, float], kw))
    for n in want:
        if not isinstance(kw[n], tuple):
            raise ParameterError("expression", text, _TEXT_VALID, f"{n} must be a list [..]")
    tables = cast("dict[str, tuple[float, ...]]", kw)  # all lists, checked just above
    return PiecewiseLinearLaw(tables["breakpoints"], tables["slopes"])
