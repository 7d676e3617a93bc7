"""Helpers shared by every ``fpu`` command: JSON output, the argument parser, law options."""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
from typing import TYPE_CHECKING

from fpucore.errors import ParameterError

if TYPE_CHECKING:
    from fpucore.law import HardeningSofteningLaw


def jsonable(obj):
    """:func:`fpucore.result.jsonable`, imported when a command prints (NumPy stays out of
    ``fpu --help``)."""
    from fpucore.result import jsonable as convert  # heavy: NumPy

    return convert(obj)


def print_json(obj) -> None:
    """Print one JSON object on stdout (NaN/inf become null, numpy types become Python)."""
    sys.stdout.write(json.dumps(jsonable(obj)) + "\n")


# argparse takes "-1" and "-0.5" as values but "-1e-2" or "-inf" as an unknown option ("expected
# one argument"): every negative number, in any notation float() reads, is a value here.
NEGATIVE_NUMBER = re.compile(
    r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
)


class Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER  # argparse's hook for this decision

    def error(self, message):  # one line on stderr, exit 2 (argparse default prints usage too)
        self.exit(2, f"fpu: error: {message}\n")


def check_out_path(path: str, name: str = "--out", store: bool = False) -> None:
    """Refuse an output file that cannot be written, before any computation: its directory must
    exist and be writable, and the path must not be a directory (both once failed only after
    the whole sweep, with a traceback).  ``store``: the output is a directory store (the atlas's
    Zarr), which may exist already (resume)."""
    if not path:
        raise ParameterError(name, path, "a file name")
    target = os.path.abspath(os.path.expanduser(path))
    parent = os.path.dirname(target)
    if os.path.isdir(target) and not store:
        raise ParameterError(name, path, "a file path", "it is a directory")
    if not os.path.isdir(parent):
        raise ParameterError(name, path, "a file in an existing directory",
                             f"directory {parent} does not exist")  # fmt: skip
    if not os.access(parent, os.W_OK) or (
        os.path.exists(target) and not os.access(target, os.W_OK)
    ):
        raise ParameterError(name, path, "a writable file", "permission denied")


LAW_HELP = (
    "any hardening-softening law f(w), instead of --a/--b: a polynomial of degree <= 16 or a "
    "smooth expression with exp, log, sqrt, tanh, sinh, cosh, atan, quotients, integer and "
    "rational powers and named constants given by --const, e.g. --law "
    '"w + b*w**2 - c*w**3*exp(w/d)" --const b=10 --const c=1 --const d=50 (an expression with '
    'a leading minus: --law="-..."), or a piecewise-linear law: '
    '"trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)" or '
    '"piecewise(breakpoints=[0.5, 1.5], slopes=[1, 4, 0.2])"'
)
CONST_HELP = "a named constant of --law, NAME=VALUE (repeat for each constant)"
DEFAULT_A, DEFAULT_B = -1.0, 10.0  # the paper's cubic


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b (the cubic; defaults: the paper's a = -1, b = 10) or --law EXPR (any
    hardening–softening polynomial, instead of --a/--b), shared by every subcommand."""
    p.add_argument("--a", type=float, default=None, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=None, help="quadratic coefficient b > 0 (default 10)")
    p.add_argument("--law", default=None, metavar="EXPR", help=LAW_HELP)
    p.add_argument("--const", action="append", default=None, metavar="NAME=VALUE",
                   help=CONST_HELP)  # fmt: skip


def law_from_args(args) -> HardeningSofteningLaw:
    """The law of the command line: ``--law`` parsed by SymPy if given, else CubicLaw(a, b).
    Both at once is refused: --law would silently replace the cubic the user asked for."""
    from fpucore.law import CubicLaw, law_from_expression  # heavy: Numba, SciPy

    a, b = getattr(args, "a", None), getattr(args, "b", None)
    if getattr(args, "law", None) is not None:
        if a is not None or b is not None:
            given = " ".join(f"--{n} {v:g}" for n, v in (("a", a), ("b", b)) if v is not None)
            raise ParameterError(
                "--law", args.law, "either --law EXPR or the cubic's --a/--b, not both",
                f"{given} given too; write the cubic into the law (a*w**3 + b*w**2 + w)",
            )  # fmt: skip
        return law_from_expression(args.law, _constants_of(getattr(args, "const", None)))
    if getattr(args, "const", None):
        raise ParameterError("--const", args.const[0], "constants of a --law EXPR",
                             "--const needs --law")  # fmt: skip
    return CubicLaw(DEFAULT_A if a is None else a, DEFAULT_B if b is None else b)


def _constants_of(items) -> dict | None:
    """{name: value} from --const NAME=VALUE items (ParameterError naming the item)."""
    if not items:
        return None
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        try:
            val = float(value)
        except ValueError:
            val = None
        if not sep or val is None:
            raise ParameterError("--const", item, "NAME=VALUE with a real VALUE, e.g. b=10")
        if name.strip() in out:
            raise ParameterError("--const", item, "each constant once")
        out[name.strip()] = val
    return out


def law_fields(law: HardeningSofteningLaw) -> dict:
    """The law in JSON output: a, b for the cubic; the expression and coefficients otherwise."""
    from fpucore.law import CubicLaw  # heavy: Numba, SciPy

    if isinstance(law, CubicLaw):
        return {"a": law.a, "b": law.b, "law": law.describe()}
    if hasattr(law, "breakpoints"):  # piecewise-linear
        return {"law": law.expression, "breakpoints": list(law.breakpoints),
                "slopes": list(law.slopes)}  # fmt: skip
    if hasattr(law, "coeffs"):
        return {"law": law.expression, "coeffs": list(law.coeffs)}
    err = law.representation_error
    return {"law": law.expression, "constants": law.constants_dict,
            "represented_interval": list(law.interval),
            "representation_error": {"f": err.f, "df": err.df, "ddf": err.ddf}}  # fmt: skip
