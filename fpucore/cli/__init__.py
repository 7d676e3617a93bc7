"""The ``fpu`` command line: one module per command, dispatched by :mod:`.dispatch`.

common (JSON, parser, law options)  →  qc · wave · floquet · simulate · atlas · warm  →  dispatch
"""

from fpucore.cli.dispatch import build_parser, main

__all__ = ["build_parser", "main"]
