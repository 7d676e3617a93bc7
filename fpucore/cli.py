"""The ``fpu`` command line (also ``python -m fpucore``).

Each feature registers its own subcommand from ``cli_<feature>.py`` (a ``register(subparsers)``
function that sets ``func`` on its parser).  This file only dispatches and turns
ParameterError into exit code 2 with a one-line message on stderr.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

import numpy as np

from .errors import ParameterError


def _jsonable(obj):
    """Recursively convert numpy scalars/arrays and non-finite floats for json.dumps."""
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
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
    sys.stdout.write(json.dumps(_jsonable(obj)) + "\n")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line on stderr, exit 2 (argparse default prints usage too)
        self.exit(2, f"fpu: error: {message}\n")


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b shared by every subcommand (defaults: the paper's a = -1, b = 10)."""
    p.add_argument("--a", type=float, default=-1.0, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=10.0, help="quadratic coefficient b > 0 (default 10)")


def build_parser() -> argparse.ArgumentParser:
    from . import cli_floquet, cli_qc, cli_warm, cli_wave

    parser = _Parser(prog="fpu", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    for mod in (cli_qc, cli_warm, cli_wave, cli_floquet):
        mod.register(sub)
    __import__(f"{__package__}.cli_simulate", fromlist=["register"]).register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ParameterError as exc:
        sys.stderr.write(f"fpu: error: {exc}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("fpu: interrupted\n")
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
