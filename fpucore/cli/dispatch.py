"""The ``fpu`` command line (also ``python -m fpucore``): dispatch only.

Each command lives in its own module here (a ``register(subparsers)`` function that sets ``func``
on its parser).  This module builds the parser and turns ParameterError into exit code 2 with a
one-line message on stderr, and an output that could not be written after the work
(:class:`~fpucore.cli.common.OutputError`) into exit code 1 with one line.
"""

from __future__ import annotations

import _thread
import importlib
import os
import signal
import sys
import threading

from fpucore.budget import require_env_budget
from fpucore.cli import atlas, floquet, paper, qc, serve, simulate, warm, wave
from fpucore.cli.common import OutputError, Parser, check_out_path
from fpucore.errors import MissingExtra, ParameterError

COMMANDS = (qc, warm, wave, floquet, simulate, atlas, paper, serve)
# what every computing command needs (the old eager ``import fpucore``): loaded after parsing
STACK = (
    "fpucore.parallel.threads",
    "fpucore.qc",
    "fpucore.wave",
    "fpucore.floquet",
    "fpucore.simulate",
)


def _interrupted(signum, frame):  # pragma: no cover (subprocess tests)
    sys.stderr.write("fpu: interrupted\n")
    sys.stderr.flush()
    os._exit(130)


def load_stack() -> None:
    """Import :data:`STACK`; Ctrl-C meanwhile gives one line and exit 130 at once.  Not left to
    ``except KeyboardInterrupt``: an interrupt inside an extension module's initialisation
    (NumPy's) surfaces as an ImportError with a traceback, not as KeyboardInterrupt."""
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, _interrupted) if main_thread else None
    if getattr(previous, "__module__", None) == "fpucore":
        # fpucore/__init__'s start-up handler of the `fpu` process: the command gets Python's own
        previous = signal.default_int_handler
    try:
        for name in STACK:
            importlib.import_module(name)
    finally:
        if main_thread:
            signal.signal(signal.SIGINT, previous)


LAWS_EPILOG = (
    "Force law (every command): the paper's cubic by --a/--b, or --law EXPR: a polynomial or a "
    "smooth expression in w (exp, log, sqrt, tanh, sinh, cosh, atan, quotients, integer and "
    "rational powers) with named constants given by --const NAME=VALUE, e.g. "
    "--law 'w + b*w**2 - c*w**3*exp(w/d)' --const b=10 --const c=1 --const d=50."
)


def build_parser() -> Parser:
    parser = Parser(prog="fpu", description=__doc__.splitlines()[0], epilog=LAWS_EPILOG)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for mod in COMMANDS:
        mod.register(sub)
    return parser


class SwallowedInterrupts:
    """Ctrl-C that lands inside a C callback (Numba writing its cache through ctypes) raises
    KeyboardInterrupt there, and Python only prints it ("Exception ignored …") and goes on: the
    command would run to its end and exit 0.  While installed, such an interrupt is raised
    again 10 ms later (from a timer thread, so it surfaces in Python code), and ``seen``
    remembers it for a command that still returns normally."""

    def __init__(self) -> None:
        self.seen = False
        self._previous = sys.unraisablehook
        self._timers: list[threading.Timer] = []

    def __enter__(self) -> SwallowedInterrupts:
        sys.unraisablehook = self._hook
        return self

    def __exit__(self, *exc) -> None:
        sys.unraisablehook = self._previous
        for timer in self._timers:  # the command has ended: nothing left to interrupt
            timer.cancel()

    def _hook(self, unraisable) -> None:
        if isinstance(unraisable.exc_value, KeyboardInterrupt):
            self.seen = True
            # raised again from another thread a moment later, once the callback has returned
            # (raised in this hook, it would be ignored again)
            timer = threading.Timer(0.01, _thread.interrupt_main)
            timer.daemon = True
            self._timers.append(timer)
            timer.start()
            return
        self._previous(unraisable)


def main(argv: list[str] | None = None) -> int:
    with SwallowedInterrupts() as swallowed:
        code = _main(argv)
    if swallowed.seen and code != 130:
        sys.stderr.write("fpu: interrupted\n")
        return 130
    return code


def _main(argv: list[str] | None) -> int:
    try:
        args = build_parser().parse_args(argv)  # --help exits here: no NumPy/Numba imported
        if getattr(args, "light", False):  # fpu serve: the work is another process's
            return int(args.func(args) or 0)
        load_stack()
        from fpucore.parallel.threads import apply_thread_policy, default_threads  # heavy: Numba

        # the thread budget (fpucore/parallel/threads.py): FPU_THREADS threads (default 1) for a
        # command computing one job; commands that fan out (atlas) set threads=1 for the parent
        threads = getattr(args, "threads", None)
        apply_thread_policy(default_threads() if threads is None else threads)
        require_env_budget()  # an invalid FPU_MEMORY_BUDGET is refused by every command
        out = getattr(args, "out", None)
        if out is not None and not getattr(args, "out_is_store", False):
            check_out_path(out)  # an unwritable output fails before the work (a store: its own)
        return int(args.func(args) or 0)
    except (ParameterError, MissingExtra) as exc:
        sys.stderr.write(f"fpu: error: {exc}\n")
        return 2
    except OutputError as exc:  # the work was done; its output could not be written
        sys.stderr.write(f"fpu: error: {exc}\n")
        return 1
    except KeyboardInterrupt:
        sys.stderr.write("fpu: interrupted\n")
        return 130
