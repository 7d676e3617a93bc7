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
    "any hardening-softening polynomial f(w) of degree <= 16, instead of --a/--b, e.g. --law "
    '"w + 10*w**2 - w**3 - 0.01*w**4" (an expression with a leading minus: --law="-...")'
)
DEFAULT_A, DEFAULT_B = -1.0, 10.0  # the paper's cubic


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b (the cubic; defaults: the paper's a = -1, b = 10) or --law EXPR (any
    hardening–softening polynomial, instead of --a/--b), shared by every subcommand."""
    p.add_argument("--a", type=float, default=None, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=None, help="quadratic coefficient b > 0 (default 10)")
    p.add_argument("--law", default=None, metavar="EXPR", help=LAW_HELP)


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
        return law_from_expression(args.law)
    return CubicLaw(DEFAULT_A if a is None else a, DEFAULT_B if b is None else b)


def law_fields(law: HardeningSofteningLaw) -> dict:
    """The law in JSON output: a, b for the cubic; the expression and coefficients otherwise."""
    from fpucore.law import CubicLaw  # heavy: Numba, SciPy

    if isinstance(law, CubicLaw):
        return {"a": law.a, "b": law.b, "law": law.describe()}
    return {"law": law.expression, "coeffs": list(law.coeffs)}  # type: ignore[attr-defined]
