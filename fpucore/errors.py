"""Exceptions raised by fpucore.

Every refusal names the argument, the value it got and the valid range (or the reason), so the
same text can be shown verbatim by the CLI and the dashboard.  The wording fits the value: a
number outside its range "is out of range: valid ..."; anything else (a path, an expression, a
name, NaN, a missing value) "is not valid: expected ...".
"""

from __future__ import annotations

import importlib
import math
import numbers
from types import ModuleType
from typing import Any


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
        v = f"{value:.10g}" if isinstance(value, float) else _short_repr(value)
        if _is_ordered_number(value):  # a number outside the range where the object exists
            msg = f"{name}={v} is out of range: valid {valid}"
        else:  # not a matter of range: a path, an expression, a name, NaN, a missing value
            msg = f"{name}={v} is not valid: expected {valid}"
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


def _is_ordered_number(value) -> bool:
    """A real number that lies somewhere on the line (not NaN, not a bool, not a string)."""
    if isinstance(value, bool) or _is_numpy_bool(value) or not isinstance(value, numbers.Real):
        return False
    if isinstance(value, numbers.Integral):  # math.isnan(10**400) raises OverflowError
        return True
    try:
        return not math.isnan(value)
    except (TypeError, ValueError, OverflowError):
        return False


REPR_MAX = 80  # characters of a value shown in a message


def _short_repr(value) -> str:
    """repr(value), cut to :data:`REPR_MAX` characters (a 400-digit int, a long list); an int
    too long for ``repr`` (Python's 4300-digit limit) by its size."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 256:
        digits = int(value.bit_length() * 0.30103) + 1
        return f"{'-' if value < 0 else ''}<an integer of about {digits} digits>"
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001  (a repr that fails: the type is enough)
        return f"<{type(value).__name__}>"
    return text if len(text) <= REPR_MAX else text[: REPR_MAX - 20] + f"... ({len(text)} chars)"


def _is_numpy_bool(value) -> bool:
    """numpy.bool_ without importing NumPy here (errors is imported by the CLI's help)."""
    t = type(value)
    return t.__module__ == "numpy" and t.__name__ in ("bool_", "bool")


def require_finite(name: str, value: Any) -> float:
    """Return ``float(value)`` or raise ParameterError if it is not a finite real number.

    Strings and bools are refused even though ``float()`` would take them: ``CubicLaw(a="-1")`` or
    ``b=True`` is a caller's mistake, not a number."""
    if isinstance(value, (str, bytes, bool)) or _is_numpy_bool(value):
        raise ParameterError(name, value, "a finite real number", "not a number")
    try:
        x = float(value)
    except OverflowError:  # a Python int beyond double precision (10**400)
        raise ParameterError(
            name, value, "a finite real number", "beyond double precision"
        ) from None
    except (TypeError, ValueError):
        raise ParameterError(name, value, "a finite real number") from None
    if not math.isfinite(x):
        raise ParameterError(name, x, "a finite real number")
    return x


def require_int(name: str, value: Any, lo: int, hi: int) -> int:
    """Return ``int(value)`` for an integer (Python or NumPy, not bool) in [lo, hi], else raise.

    The one rule for counts (N, m, L, n_snapshots, max_steps, ...): a float is refused even when
    its value is whole (``500.0``), as a string or a bool is — a count given as a float is a
    caller's mistake (the CLI parses integers; JSON keeps 500 and 500.0 apart)."""
    # numbers.Integral: Python and NumPy integers (numpy.bool_ is not one)
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ParameterError(name, value, f"an integer in [{lo}, {hi}]")
    if not lo <= int(value) <= hi:
        raise ParameterError(name, int(value), f"an integer in [{lo}, {hi}]")
    return int(value)


def require_in(name: str, value: Any, lo: float, hi: float, reason: str = "") -> float:
    """Return ``float(value)`` for a finite real number in [lo, hi], else raise (the one rule
    for bounded reals: :func:`require_finite` first, then the range)."""
    x = require_finite(name, value)
    if not lo <= x <= hi:
        raise ParameterError(name, x, f"[{lo:g}, {hi:g}]", reason)
    return x


TOL_RANGE = (1e-15, 1e-3)
"""Relative residual tolerances of wave solves (and so of sweeps and atlases) accepted."""


def require_tol(tol: Any, name: str = "tol") -> float:
    """A wave solve's relative tolerance: a finite float in :data:`TOL_RANGE`."""
    x = require_finite(name, tol)
    if not (TOL_RANGE[0] <= x <= TOL_RANGE[1]):
        raise ParameterError(name, x, f"[{TOL_RANGE[0]:g}, {TOL_RANGE[1]:g}]")
    return x


def fmt_interval(lo: float, hi: float, open_: bool = True) -> str:
    l, r = ("(", ")") if open_ else ("[", "]")
    return f"{l}{lo:.10g}, {hi:.10g}{r}"


class MissingExtra(ImportError):
    """An optional dependency is not installed: the message names the extra that installs it
    (``pip install 'fpu-explorer[atlas]'``).  The CLI prints it as one line (exit 2)."""

    def __init__(self, module: str, extra: str, needed_for: str):
        self.module, self.extra, self.needed_for = module, extra, needed_for
        super().__init__(
            f"{needed_for} needs {module}, which is not installed: "
            f"pip install 'fpu-explorer[{extra}]'",
            name=module,
        )

    def __reduce__(self):
        return (type(self), (self.module, self.extra, self.needed_for))


def import_extra(module: str, extra: str, needed_for: str) -> ModuleType:
    """``importlib.import_module(module)``, or :class:`MissingExtra` naming ``extra`` when the
    module (not one of its own imports) is missing."""
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name is None or exc.name.split(".")[0] != module.split(".")[0]:
            raise
        raise MissingExtra(module, extra, needed_for) from None
