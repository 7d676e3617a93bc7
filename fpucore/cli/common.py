"""Helpers shared by every ``fpu`` command: JSON output, the argument parser, law options."""

from __future__ import annotations

import argparse
import json
import math
import sys

import numpy as np


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


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b shared by every subcommand (defaults: the paper's a = -1, b = 10)."""
    p.add_argument("--a", type=float, default=-1.0, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=10.0, help="quadratic coefficient b > 0 (default 10)")
