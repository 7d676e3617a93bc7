"""Exceptions raised by fpucore.

Every refusal names the argument, the value it got and the valid range (or the reason), so the
same text can be shown verbatim by the CLI and the dashboard.
"""

from __future__ import annotations

import math


class ParameterError(ValueError):
    """An input outside the range where the requested object exists.

    Attributes
    ----------
    name : the argument's name as the user typed it (``"V"``, ``"w_plus"``, ``"a"`` ...).
    value : the offending value.
    valid : human-readable description of the valid range, e.g. ``"(4.2426, 5.3748)"``.
    """

    def __init__(self, name: str, value: object, valid: str, reason: str = ""):
        self.name, self.value, self.valid, self.reason = name, value, valid, reason
        v = f"{value:.10g}" if isinstance(value, float) else repr(value)
        msg = f"{name}={v} is out of range: valid {valid}"
        if reason:
            msg += f" ({reason})"
        super().__init__(msg)

    def __reduce__(self):
        # rebuilt from its four fields (the default pickles only the message, and __init__ needs
        # all four): a ParameterError raised in a worker process arrives as itself
        return (type(self), (self.name, self.value, self.valid, self.reason), self.__dict__)


class ConvergenceError(RuntimeError):
    """A result that did not converge, raised only on request by
    :meth:`fpucore.result.Result.require_converged` (solvers return a result with
    ``converged=False``, ``status`` and ``message`` instead of raising)."""


def require_finite(name: str, value: float) -> float:
    """Return ``float(value)`` or raise ParameterError if it is not a finite real number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "a finite real number") from None
    if not math.isfinite(x):
        raise ParameterError(name, x, "a finite real number")
    return x


def fmt_interval(lo: float, hi: float, open_: bool = True) -> str:
    l, r = ("(", ")") if open_ else ("[", "]")
    return f"{l}{lo:.10g}, {hi:.10g}{r}"
