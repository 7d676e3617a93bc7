"""Server warm-up script (``panel serve … --setup app/warm.py``, as ``fpu serve`` runs it): once
before the server accepts connections; the work is :func:`app.warmup.setup`.  Run as a file: its
package is imported by its directory's name (see main.py)."""

import importlib
import os
import sys
from pathlib import Path

os.environ.setdefault("BOKEH_RESOURCES", "server")  # see main.py; before panel is imported

HERE = Path(__file__).resolve().parent
if str(HERE.parent) not in sys.path:
    sys.path.insert(0, str(HERE.parent))
if __name__ in ("__main__", "panel_setup_module"):
    importlib.import_module(f"{HERE.name}.warmup").setup()
