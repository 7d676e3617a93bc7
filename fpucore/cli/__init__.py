"""The ``fpu`` command line: one module per command, dispatched by :mod:`.dispatch`.

common (JSON, parser, law options)  →  qc · wave · floquet · simulate · atlas · warm  →  dispatch

Imports inside functions.  Building the parser (and printing ``fpu … --help``) must not import
NumPy, SciPy, Numba, tqdm or threadpoolctl (tests/cli/test_cli_startup.py): every fpucore
subpackage a command uses loads at least NumPy, most Numba.  So a command imports what it computes
with inside its function, and only there: each such import ends with ``# heavy: <what it loads>``
(tests/project/test_architecture.py refuses one without), everything else sits at module level.
"""

from fpucore.cli.dispatch import build_parser, main

__all__ = ["build_parser", "main"]
