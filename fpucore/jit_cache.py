"""Key Numba's on-disk cache by the source of the whole package.

Numba invalidates a cached function only when *its own* file changes; a kernel that calls (and
inlines) a jitted function from another module keeps the old machine code after that module is
edited (documented limitation).  Here that happened for real: ``simulate.rkn.rkn_chunk`` kept an
observer whose array layout had changed in ``simulate.kernels``.  So when NUMBA_CACHE_DIR is set
(the Makefile and the Dockerfile set it), the cache goes to a subdirectory named by a hash of every
``fpucore/**/*.py`` (every subpackage): any edit anywhere in the package starts a fresh cache.
Must run before the first ``@njit(cache=True)`` function is compiled, i.e. first thing in
``fpucore/__init__``."""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path


def source_hash(root: Path | None = None) -> str:
    """12 hex digits of SHA-1 over every ``*.py`` below ``root`` (default: this package)."""
    h = hashlib.sha1()
    root = Path(__file__).parent if root is None else Path(root)
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:12]


def key_cache_dir() -> str | None:
    """Point NUMBA_CACHE_DIR (if set) at <dir>/fpucore-<hash>; returns the directory used."""
    base = os.environ.get("NUMBA_CACHE_DIR")
    if not base:
        return None
    if os.path.basename(base.rstrip("/")).startswith("fpucore-"):
        return base  # already keyed (e.g. inherited by a child process)
    keyed = os.path.join(base, f"fpucore-{source_hash()}")
    os.environ["NUMBA_CACHE_DIR"] = keyed
    if "numba" in sys.modules:  # numba imported first: its config has already read the variable
        sys.modules["numba"].config.CACHE_DIR = keyed
    return keyed
