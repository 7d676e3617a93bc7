"""First start: seconds from `make serve` on a fresh clone (venv present, empty Numba cache) to
/liveness and to the first full /main page.

    .venv/bin/python -m benchmarks.bench_first_start                 # HEAD
    .venv/bin/python -m benchmarks.bench_first_start --baseline REV  # HEAD and REV, same run

Each checkout is a `git clone` of this repository into a temporary directory that uses this
repository's .venv (so the venv build is not timed) and an empty NUMBA_CACHE_DIR; the server is
started with the Makefile's own `serve` target and killed after the first page.  With
--baseline the two checkouts run alternately (HEAD, REV, HEAD, REV …) so machine load affects
both alike; the ratio is the figure to read.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def checkout(rev: str) -> Path:
    d = Path(tempfile.mkdtemp(prefix="fpu-first-start-"))
    subprocess.run(["git", "clone", "-q", str(ROOT), str(d / "repo")], check=True)
    subprocess.run(["git", "-C", str(d / "repo"), "checkout", "-q", rev], check=True)
    (d / "repo" / ".venv").symlink_to(ROOT / ".venv")
    return d / "repo"


def first_start(repo: Path, port: int, timeout: float = 600.0) -> tuple[float, float]:
    cache = tempfile.mkdtemp(prefix="nc-first-start-")
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=str(repo))
    # the venv is ours: make's stamp must not trigger a reinstall
    (ROOT / ".venv" / ".installed-stamp").touch()
    t0 = time.perf_counter()
    p = subprocess.Popen(
        ["make", "-s", "serve", f"PORT={port}", f"NUMBA_CACHE_DIR={cache}"],
        cwd=repo,
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    live = page = float("nan")
    try:
        while time.perf_counter() - t0 < timeout:
            try:
                if live != live:
                    urllib.request.urlopen(f"http://127.0.0.1:{port}/liveness", timeout=2)
                    live = time.perf_counter() - t0
                urllib.request.urlopen(f"http://127.0.0.1:{port}/main", timeout=120).read()
                page = time.perf_counter() - t0
                break
            except OSError:
                time.sleep(0.2)
    finally:
        os.killpg(p.pid, 15)
        p.wait(30)
        shutil.rmtree(cache, ignore_errors=True)
    return live, page


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", help="git revision to compare against, in the same run")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--port", type=int, default=5097)
    args = ap.parse_args(argv)
    revs = ["HEAD"] + ([args.baseline] if args.baseline else [])
    repos = {rev: checkout(rev) for rev in revs}
    pages: dict[str, list[float]] = {rev: [] for rev in revs}
    try:
        for _ in range(args.repeat):
            for rev in revs:
                live, page = first_start(repos[rev], args.port)
                pages[rev].append(page)
                print(f"{rev:>12}: /liveness {live:6.1f} s, first /main page {page:6.1f} s")
    finally:
        for repo in repos.values():
            shutil.rmtree(repo.parent, ignore_errors=True)
    if args.baseline:
        h, b = statistics.median(pages["HEAD"]), statistics.median(pages[args.baseline])
        print(f"first page: HEAD {h:.1f} s vs {args.baseline} {b:.1f} s -> ratio {h / b:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
