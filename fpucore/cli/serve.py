"""``fpu serve``: the explorer (the Panel app of the ``app`` extra) with the server's warm-up and
guards — ``python -m panel serve <explorer>/main.py … --setup <explorer>/warm.py --warm``, where
<explorer> is the checkout's ``app/`` next to this fpucore, else the installed
``fpu_explorer_app`` package (the wheel's copy of ``app/``).  The Makefile's ``serve``, the
Dockerfile's CMD and the browser tests all start the server with this command.

    fpu serve                                # http://0.0.0.0:5006/main, /liveness
    fpu serve --port 8080 --address 127.0.0.1 --num-procs 2

The process is replaced by Panel's (``exec``): signals (Ctrl-C, a container's SIGTERM) reach the
server directly, and its exit code is the command's.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

from fpucore.errors import MissingExtra, ParameterError

#: the installed name of the repository's ``app/`` (setup.py maps it; never a top-level ``app``)
APP_PACKAGE = "fpu_explorer_app"
#: Panel's flags besides port, address and processes: any websocket origin (behind a proxy or in
#: a container the page's host is not known here), the /liveness endpoint, two threads for
#: callbacks, the warm-up before the first connection (warm.py) and one page rendered (--warm)
PANEL_FLAGS = ("--allow-websocket-origin=*", "--liveness", "--num-threads", "2")


def register(sub) -> None:
    p = sub.add_parser("serve", help="serve the explorer (needs the app extra)")
    p.add_argument("--port", type=int, default=5006, help="port (default 5006)")
    p.add_argument("--address", default="0.0.0.0", help="address to listen on (default 0.0.0.0)")
    p.add_argument(
        "--num-procs",
        type=int,
        default=1,
        metavar="N",
        help="server processes (default 1; each warms its own JIT)",
    )
    p.set_defaults(func=run, light=True)  # no NumPy/Numba in this process: Panel's does the work


def explorer_dir() -> Path:
    """The explorer's directory (holding main.py and warm.py): a checkout's ``app/`` when this
    fpucore runs from a checkout, else the installed :data:`APP_PACKAGE`."""
    here = Path(__file__).resolve().parents[2]  # the checkout's root, or site-packages
    if (here / "app" / "main.py").is_file() and (here / "pyproject.toml").is_file():
        return here / "app"
    spec = importlib.util.find_spec(APP_PACKAGE)
    if spec is None or not spec.submodule_search_locations:
        raise MissingExtra(APP_PACKAGE, "app", "fpu serve")
    return Path(next(iter(spec.submodule_search_locations)))


def command(port: int, address: str, num_procs: int, explorer: Path) -> list[str]:
    """The ``panel serve`` command line of ``fpu serve`` (``--num-procs`` only when above 1:
    Panel's single-process path otherwise, as ``make serve`` always ran)."""
    procs = ["--num-procs", str(num_procs)] if num_procs > 1 else []
    return [
        sys.executable,
        "-m",
        "panel",
        "serve",
        str(explorer / "main.py"),
        "--port",
        str(port),
        "--address",
        address,
        *PANEL_FLAGS,
        *procs,
        "--setup",
        str(explorer / "warm.py"),
        "--warm",
    ]


def run(args) -> int:
    if not 1 <= args.port <= 65535:
        raise ParameterError("--port", args.port, "an integer in [1, 65535]")
    if not args.address or any(c.isspace() for c in args.address):
        raise ParameterError("--address", args.address, "a host name or IP address")
    if not 1 <= args.num_procs <= 64:
        raise ParameterError("--num-procs", args.num_procs, "an integer in [1, 64]")
    for module in ("panel", "holoviews", "bokeh"):
        if importlib.util.find_spec(module) is None:
            raise MissingExtra(module, "app", "fpu serve")
    cmd = command(args.port, args.address, args.num_procs, explorer_dir())
    sys.stderr.write(f"fpu serve: http://{args.address}:{args.port}/main (warming up first)\n")
    sys.stderr.flush()
    os.execv(sys.executable, cmd)  # pragma: no cover (replaces the process)
    return 0  # pragma: no cover
