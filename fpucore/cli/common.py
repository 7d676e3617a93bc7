"""Helpers shared by every ``fpu`` command: JSON output, the argument parser, law options."""

from __future__ import annotations

import argparse
import json
import math
import sys

import numpy as np

from fpucore.law import CubicLaw, HardeningSofteningLaw, law_from_expression


def jsonable(obj):
    """Recursively convert numpy scalars/arrays and non-finite floats for json.dumps."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def print_json(obj) -> None:
    """Print one JSON object on stdout (NaN/inf become null, numpy types become Python)."""
    sys.stdout.write(json.dumps(jsonable(obj)) + "\n")


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line on stderr, exit 2 (argparse default prints usage too)
        self.exit(2, f"fpu: error: {message}\n")


LAW_HELP = (
    'any hardening-softening polynomial f(w), replaces --a/--b, e.g. --law "w + 10*w**2 - w**3 '
    '- 0.01*w**4" (an expression with a leading minus: --law="-...")'
)


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b (the cubic; defaults: the paper's a = -1, b = 10) or --law EXPR (any
    hardening–softening polynomial; replaces --a/--b), shared by every subcommand."""
    p.add_argument("--a", type=float, default=-1.0, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=10.0, help="quadratic coefficient b > 0 (default 10)")
    p.add_argument("--law", default=None, metavar="EXPR", help=LAW_HELP)


def law_from_args(args) -> HardeningSofteningLaw:
    """The law of the command line: ``--law`` parsed by SymPy if given, else CubicLaw(a, b)."""
    if getattr(args, "law", None) is not None:
        return law_from_expression(args.law)
    return CubicLaw(args.a, args.b)


def law_fields(law: HardeningSofteningLaw) -> dict:
    """The law in JSON output: a, b for the cubic; the expression and coefficients otherwise."""
    if isinstance(law, CubicLaw):
        return {"a": law.a, "b": law.b, "law": law.describe()}
    return {"law": law.expression, "coeffs": list(law.coeffs)}
