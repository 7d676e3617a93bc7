"""The container: a small build context (.dockerignore) and, where Docker and the base image are
available, the image built from the Dockerfile serving /liveness and the explorer's page.

No image registry is reachable on the development machines and CI: ``FROM python:3.11-slim``
builds only where that image is already loaded (``docker load``); the build test is skipped with
the reason otherwise.
"""

from __future__ import annotations

import fnmatch
import os
import shutil
import subprocess
import time
import urllib.request
from pathlib import Path

import pytest
from browser_harness import free_port

ROOT = Path(__file__).resolve().parents[2]
BASE = "python:3.11-slim"
MAX_CONTEXT = 50 * 2**20


def _dockerignore() -> list[tuple[bool, str]]:
    """(negated, pattern) of .dockerignore, in order (the last match decides, as Docker's)."""
    rules = []
    for line in (ROOT / ".dockerignore").read_text().splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            neg = line.startswith("!")
            rules.append((neg, line[1:] if neg else line))
    return rules


def _ignored(rel: str, rules) -> bool:
    out = False
    parts = rel.split("/")
    prefixes = ["/".join(parts[: k + 1]) for k in range(len(parts))]
    for neg, pat in rules:
        pat = pat.rstrip("/")
        hit = any(fnmatch.fnmatchcase(p, pat) or fnmatch.fnmatchcase(p, pat.replace("**/", ""))
                  for p in prefixes) or ("**/" in pat and any(
                      fnmatch.fnmatchcase(seg, pat.split("**/")[-1]) for seg in parts))  # fmt: skip
        if hit:
            out = not neg
    return out


def context_bytes() -> int:
    """Bytes of the files a ``docker build`` of the repository would send (.dockerignore)."""
    rules, total = _dockerignore(), 0
    for dirpath, _dirs, filenames in os.walk(ROOT):
        rel_dir = os.path.relpath(dirpath, ROOT)
        for f in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, f))
            if not _ignored(rel, rules):
                total += os.path.getsize(os.path.join(dirpath, f))
    return total


def test_build_context_is_small_and_holds_what_the_dockerfile_copies():
    assert context_bytes() < MAX_CONTEXT
    rules = _dockerignore()
    sent = "pyproject.toml setup.py README.md requirements/lock.txt fpucore/__init__.py"
    for needed in (*sent.split(), "app/main.py", "app/assets/figures/pplane.png"):
        assert not _ignored(needed, rules), needed
    kept_out = ".venv/bin/python .git/HEAD .numba_cache/x.nbi tests/x.py atlas.zarr/.zattrs"
    for left_out in (*kept_out.split(), "fpucore/__pycache__/x.pyc", ".fpu_cache/x"):
        assert _ignored(left_out, rules), left_out


def _docker_ready() -> str | None:
    """None when an image can be built here, else the reason it cannot."""
    if shutil.which("docker") is None:
        return "docker is not installed (apt-get install docker.io)"
    if subprocess.run(["docker", "info"], capture_output=True).returncode != 0:
        return "the Docker daemon is not running (dockerd)"
    p = subprocess.run(["docker", "image", "inspect", BASE], capture_output=True)
    if p.returncode != 0:
        return f"base image {BASE} not loaded and no registry reachable to pull it"
    return None


@pytest.mark.slow
def test_image_builds_and_serves_liveness_and_a_page():
    reason = _docker_ready()
    if reason:
        pytest.skip(reason)
    tag = "fpu-explorer-test"
    p = subprocess.run(["docker", "build", "-t", tag, str(ROOT)], capture_output=True,
                       text=True, timeout=3600)  # fmt: skip
    assert p.returncode == 0, p.stderr[-3000:]
    size = int(subprocess.run(["docker", "image", "inspect", tag, "--format", "{{.Size}}"],
                              capture_output=True, text=True).stdout)  # fmt: skip
    print(f"\n[container] image {size / 1e9:.2f} GB")
    port = free_port()
    cid = subprocess.run(["docker", "run", "-d", "--rm", "-e", "FPU_WARM_SCENES=force", "-p",
                          f"127.0.0.1:{port}:5006", tag], capture_output=True, text=True,
                         check=True).stdout.strip()  # fmt: skip
    try:
        url, t_end = f"http://127.0.0.1:{port}", time.monotonic() + 600
        while True:
            try:
                with urllib.request.urlopen(url + "/liveness", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            assert time.monotonic() < t_end, "no /liveness within 600 s"
            time.sleep(1)
        with urllib.request.urlopen(url + "/main", timeout=120) as r:
            assert r.status == 200 and b"bokeh" in r.read().lower()
    finally:
        subprocess.run(["docker", "rm", "-f", cid], capture_output=True)
