"""The server's data directory, and the rule that a page never names a path of the server.

Stores (atlas stores) are read only below :func:`atlas_root` — ``$FPU_ATLAS_ROOT``, else the
directory the server was started in.  A message that names a store or a file names it relative
to that directory (:func:`data_name`); a message that repeats an exception's text has the
server's own directories taken out (:func:`hide_server_paths`): a stranger with a link learns
nothing of the server's layout ("no atlas store at /srv/…/clone/x.zarr" said where the clone
was).  What the visitor typed is repeated as typed (it is theirs, not the server's).
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
from pathlib import Path

#: how a message names the server's data directory itself
DATA_DIR_NAME = "the server's data directory"


def atlas_root() -> Path:
    """Where the Atlas scene may open stores (the server's data directory):
    ``$FPU_ATLAS_ROOT``, else the directory the server was started in.  A page (or a link)
    may open only stores below it, so no visitor can make the server read, or probe, any
    other directory."""
    return Path(os.environ.get("FPU_ATLAS_ROOT") or os.getcwd()).resolve()


def data_name(path: str | os.PathLike) -> str:
    """``path`` as a page may name it: relative to the data directory ("stores/x.zarr", "."
    for the directory itself); a path outside it (never opened) by its last part only."""
    p = Path(path)
    root = atlas_root()
    try:
        rel = p.resolve().relative_to(root) if p.is_absolute() else p
    except (ValueError, OSError, RuntimeError):
        return p.name or "."
    return rel.as_posix() or "."


def _server_dirs() -> list[tuple[str, str, str]]:
    """(directory, its name below it, its own name), longest first: the data directory (its
    paths become relative names) and the server's other directories (its working directory,
    the app's source, the Python installation, home, temp: a placeholder)."""
    root = atlas_root()
    dirs = {str(root): ("", DATA_DIR_NAME)}
    here = Path(__file__).resolve().parents[1]  # the checkout (app/, fpucore/)
    for d in (Path.cwd(), here, sys.prefix, sys.base_prefix, Path.home(), tempfile.gettempdir()):
        for form in (str(d), str(Path(d).resolve())):
            if len(form) > 1:
                dirs.setdefault(form, ("", DATA_DIR_NAME) if Path(form) == root else ("…/", "…"))
    return sorted(((d, *names) for d, names in dirs.items()), key=lambda t: -len(t[0]))


def hide_server_paths(text: str) -> str:
    """``text`` (an exception's message) with the server's directories taken out: below the
    data directory a path becomes its relative name, the directory itself ``DATA_DIR_NAME``;
    below another directory of the server (its Python, its source, home, temp) ``…/name``."""
    out = str(text)
    for d, below, itself in _server_dirs():
        # the directory, then a "/" (a path below it) or the end of the path
        pattern = re.compile(re.escape(d) + r"(?:(/)|(?![\w.~+-]))")
        out = pattern.sub(lambda m, b=below, i=itself: b if m.group(1) else i, out)
    return out
