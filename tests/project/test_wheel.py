"""The wheel is the whole product: built by ``python -m build`` (sdist and wheel), installed with
its explorer extra into a fresh virtual environment outside the repository, and there the CLI,
the headless import and ``fpu serve`` (the Paper tab's 17 thumbnails in headless Chromium) work.

Slow (a fresh venv of ~110 packages at requirements/lock.txt's versions, from pip's cache when it
has them): kept in the suite, listed by ``-m slow``.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request
import zipfile
from pathlib import Path

import pytest
from browser_harness import CHROMIUM, CHROMIUM_ARGS, free_port

ROOT = Path(__file__).resolve().parents[2]
LOCK = ROOT / "requirements" / "lock.txt"
pytestmark = pytest.mark.slow


def _clean_env() -> dict:
    """The environment without this checkout on the path: with PYTHONPATH at a checkout (whose
    build left fpu_explorer.egg-info), pip took the project as installed and skipped the wheel."""
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}


def _run(cmd, cwd, env=None, timeout=900):
    env = _clean_env() if env is None else env
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    assert p.returncode == 0, f"{cmd}\n{p.stdout[-2000:]}\n{p.stderr[-3000:]}"
    return p


@pytest.fixture(scope="module")
def installed():
    """(venv's bin directory, wheel path, its directory): the wheel with [app] in a fresh venv.
    Not under pytest's basetemp: other pytest sessions prune old basetemps, and the install
    takes minutes."""
    tmp = Path(tempfile.mkdtemp(prefix="fpu-wheel-"))
    try:
        yield _install(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _install(tmp: Path):
    times = {}
    t = time.monotonic()
    _run([sys.executable, "-m", "build", "--outdir", str(tmp / "dist"), str(ROOT)], tmp)
    times["build_s"] = time.monotonic() - t
    (wheel,) = (tmp / "dist").glob("fpu_explorer-*.whl")
    assert list((tmp / "dist").glob("fpu_explorer-*.tar.gz")), "no sdist"
    t = time.monotonic()
    _run([sys.executable, "-m", "venv", str(tmp / "venv")], tmp)
    bin_ = tmp / "venv" / "bin"
    _run([str(bin_ / "pip"), "install", "-q", "-c", str(LOCK), f"{wheel}[app]"], tmp, timeout=1800)
    times["install_s"] = time.monotonic() - t
    print(f"\n[wheel] build {times['build_s']:.0f} s, install [app] {times['install_s']:.0f} s")
    return bin_, wheel, tmp


def test_wheel_holds_the_explorer_and_its_assets_and_no_top_level_app(installed):
    _, wheel, _ = installed
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names if not n.startswith("fpu_explorer-")}
    assert tops == {"fpucore", "fpu_explorer_app"}, tops
    thumbs = [n for n in names if n.startswith("fpu_explorer_app/assets/figures/")]
    assert len(thumbs) == 17 and "fpu_explorer_app/assets/paper_comparison.json" in names
    assert {"fpu_explorer_app/main.py", "fpu_explorer_app/warm.py"} <= set(names)


def test_cli_and_headless_import_outside_the_repository(installed):
    bin_, _, tmp = installed
    env = _clean_env()
    env["NUMBA_CACHE_DIR"] = str(tmp / "numba_cache")
    assert "serve" in _run([str(bin_ / "fpu"), "--help"], tmp, env).stdout
    qc = json.loads(_run([str(bin_ / "fpu"), "qc", "--w-plus", "1", "--V", "5", "--json"],
                         tmp, env).stdout)  # fmt: skip
    assert qc["w_plus"] == 1 and abs(qc["V_SK"] - (1 + 100 / 3 - (1 - 10 / 3) ** 2) ** 0.5) < 1e-9
    wave = json.loads(_run([str(bin_ / "fpu"), "wave", "superkink", "--V", "5.2", "--N", "64",
                            "--json"], tmp, env).stdout)  # fmt: skip
    assert wave["converged"] is True and wave["residual"] <= 1e-11
    probe = (
        "import importlib.util, sys, time; t = time.perf_counter(); import fpucore; "
        "dt = time.perf_counter() - t; "
        "assert 'site-packages' in fpucore.__file__, fpucore.__file__; "
        "assert not {'panel', 'bokeh', 'holoviews', 'matplotlib'} & set(sys.modules); "
        "assert importlib.util.find_spec('app') is None; "
        "print(f'{dt:.3f}')"
    )
    dt = float(_run([str(bin_ / "python"), "-c", probe], tmp, env).stdout)
    print(f"\n[wheel] import fpucore {dt:.2f} s")


def test_fpu_serve_answers_and_shows_the_papers_thumbnails(installed, playwright):
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} missing (make browser installs it)")
    bin_, _, tmp = installed
    port = free_port()
    env = _clean_env()
    env.update(NUMBA_CACHE_DIR=str(tmp / "numba_cache"), FPU_WARM_SCENES="force")
    log = open(tmp / "serve.log", "w+")
    cmd = [str(bin_ / "fpu"), "serve", "--port", str(port), "--address", "127.0.0.1"]
    proc = subprocess.Popen(cmd, cwd=tmp, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        t_end = time.monotonic() + 600
        while True:
            assert proc.poll() is None, (tmp / "serve.log").read_text()[-3000:]
            try:
                with urllib.request.urlopen(url + "/liveness", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            assert time.monotonic() < t_end, "fpu serve: no /liveness within 600 s"
            time.sleep(0.5)
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport={"width": 1500, "height": 1000})
            page.goto(f"{url}/main?tab=paper", timeout=120_000)
            imgs = page.locator(".paper-thumb img")
            imgs.nth(16).wait_for(timeout=120_000)
            assert imgs.count() == 17
            srcs = [imgs.nth(k).get_attribute("src") for k in range(17)]
            assert all(s.startswith("data:image/png;base64,") for s in srcs)
        finally:
            browser.close()
    finally:
        proc.terminate()
        try:
            proc.wait(30)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()
    assert "Traceback" not in (tmp / "serve.log").read_text()
