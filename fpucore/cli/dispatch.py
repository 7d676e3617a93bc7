"""The ``fpu`` command line (also ``python -m fpucore``): dispatch only.

Each command lives in its own module here (a ``register(subparsers)`` function that sets ``func``
on its parser).  This module builds the parser and turns ParameterError into exit code 2 with a
one-line message on stderr.
"""

from __future__ import annotations

import sys

from fpucore.budget import require_env_budget
from fpucore.cli import atlas, floquet, paper, qc, simulate, warm, wave
from fpucore.cli.common import Parser, check_out_path
from fpucore.errors import ParameterError
from fpucore.parallel.threads import apply_thread_policy

COMMANDS = (qc, warm, wave, floquet, simulate, atlas, paper)


def build_parser() -> Parser:
    parser = Parser(prog="fpu", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for mod in COMMANDS:
        mod.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    try:
        args = build_parser().parse_args(argv)
        # the thread budget (fpucore/parallel/threads.py): a command computing one job uses every
        # core for it; commands that fan out (sweeps, atlas) run their jobs in 1-thread workers
        apply_thread_policy(getattr(args, "threads", None))
        require_env_budget()  # an invalid FPU_MEMORY_BUDGET is refused by every command
        if getattr(args, "out", None) is not None:  # an unwritable output fails before the work
            check_out_path(args.out, store=getattr(args, "out_is_store", False))
        return int(args.func(args) or 0)
    except ParameterError as exc:
        sys.stderr.write(f"fpu: error: {exc}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("fpu: interrupted\n")
        return 130
