"""One `fpu serve` of the explorer on a free local port for a benchmark (the README's server
with its warm-up), stopped on exit."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@contextlib.contextmanager
def served_app(**env_extra: str) -> Iterator[str]:
    """The server's URL once /liveness answers (RuntimeError if not within 300 s)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    env = dict(os.environ, NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", ".numba_cache"))
    for k, v in env_extra.items():
        env.setdefault(k, v)
    cmd = [sys.executable, "-m", "fpucore", "serve", "--port", str(port), "--address", "127.0.0.1"]
    proc = subprocess.Popen(
        cmd, cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    url = f"http://127.0.0.1:{port}"
    try:
        t_end = time.monotonic() + 300
        while True:
            try:
                with urllib.request.urlopen(url + "/liveness", timeout=2):
                    break
            except OSError:
                if time.monotonic() > t_end or proc.poll() is not None:
                    raise RuntimeError("fpu serve did not start") from None
                time.sleep(0.2)
        yield url
    finally:
        proc.terminate()
        proc.wait(15)
