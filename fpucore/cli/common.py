"""Helpers shared by every ``fpu`` command: JSON output, the argument parser, law options."""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys

import numpy as np

from fpucore.errors import ParameterError


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


def check_out_path(path: str, name: str = "--out") -> None:
    """Refuse an output file that cannot be written, before any computation: its directory must
    exist and be writable, and the path must not be a directory (issue 14: both failed only after
    the whole sweep, with a traceback)."""
    if not path:
        raise ParameterError(name, path, "a file name")
    target = os.path.abspath(os.path.expanduser(path))
    parent = os.path.dirname(target)
    if os.path.isdir(target):
        raise ParameterError(name, path, "a file path", "it is a directory")
    if not os.path.isdir(parent):
        raise ParameterError(name, path, "a file in an existing directory",
                             f"directory {parent} does not exist")  # fmt: skip
    if not os.access(parent, os.W_OK) or (
        os.path.exists(target) and not os.access(target, os.W_OK)
    ):
        raise ParameterError(name, path, "a writable file", "permission denied")


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b shared by every subcommand (defaults: the paper's a = -1, b = 10)."""
    p.add_argument("--a", type=float, default=-1.0, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=10.0, help="quadratic coefficient b > 0 (default 10)")
