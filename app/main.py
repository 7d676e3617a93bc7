"""Entry point, run by Panel once per session: ``fpu serve`` (= ``panel serve`` of this file with
the flags of fpucore/cli/serve.py).

Run as a file, not imported: its package is imported under the name of this file's directory —
``app`` in a checkout, ``fpu_explorer_app`` when installed from the wheel — so the same file
serves both without a top-level ``app`` package in site-packages.
"""

import importlib
import os
import sys
from pathlib import Path

# Components created later in worker threads must link Panel's CSS from this server, not from
# cdn.holoviz.org (the page must work offline and without console errors).
os.environ.setdefault("BOKEH_RESOURCES", "server")

HERE = Path(__file__).resolve().parent
if str(HERE.parent) not in sys.path:
    sys.path.insert(0, str(HERE.parent))
importlib.import_module(f"{HERE.name}.page").build_page()
