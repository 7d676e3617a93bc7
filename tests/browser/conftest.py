"""Fixtures of the browser tests: one `panel serve` of the app (the README's command) on a free port
for the whole session, checked at its end for tracebacks and leaked semaphores; one headless
Chromium; a page per test that fails on any console error or request to another host."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest
from browser_harness import (
    CHROMIUM,
    CHROMIUM_ARGS,
    ROOT,
    SERVE_COMMAND,
    SERVER_LOG,
    TIMEOUT_MS,
    client_disconnect,
    free_port,
    record_foreign_requests,
    tracebacks,
)

collect_ignore_glob = [] if Path(CHROMIUM).exists() else ["test_*.py"]  # make browser installs it


@pytest.fixture(scope="session")
def server():
    port = free_port()
    env = dict(
        os.environ,
        FPU_WARM_SCENES="force,phase",
        NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", str(ROOT / ".numba_cache")),
    )
    log = tempfile.NamedTemporaryFile("w+", suffix=".log", delete=False)
    cmd = [*SERVE_COMMAND, "--port", str(port), "--address", "127.0.0.1"]
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, cwd=ROOT, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        while True:
            if proc.poll() is not None:
                log.seek(0)
                pytest.fail(f"fpu serve exited ({proc.returncode}):\n{log.read()[-3000:]}")
            try:
                with urllib.request.urlopen(url + "/liveness", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            if time.monotonic() - t0 > 240:
                pytest.fail("fpu serve did not answer /liveness within 240 s")
            time.sleep(0.2)
        print(f"\n[browser] server up after {time.monotonic() - t0:.1f} s (incl. warm-up)")
        SERVER_LOG["path"] = log.name
        SERVER_LOG["pid"] = str(proc.pid)
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.seek(0)
        text = log.read()
        log.close()
        os.unlink(log.name)
        if os.environ.get("FPU_SERVER_LOG"):  # kept for a look at the whole run
            Path(os.environ["FPU_SERVER_LOG"]).write_text(text)
        app_errors = [tb for tb in tracebacks(text) if not client_disconnect(tb)]
        assert not app_errors, "\n\n".join(app_errors)[-3000:]
        # the worker pools and the law worker release their semaphores at shutdown (the
        # resource tracker names any left: "There appear to be N leaked semaphore objects")
        assert "leaked" not in text, [ln for ln in text.splitlines() if "leaked" in ln]
        assert proc.returncode == 0 or proc.returncode == -15, proc.returncode


@pytest.fixture(scope="session")
def browser(playwright):
    profile = tempfile.mkdtemp(prefix="fpu-chromium-")
    ctx = playwright.chromium.launch_persistent_context(
        profile,
        executable_path=CHROMIUM,
        args=CHROMIUM_ARGS,
        headless=True,
        viewport={"width": 1500, "height": 1000},
    )
    yield ctx
    ctx.close()
    shutil.rmtree(profile, ignore_errors=True)


@pytest.fixture
def page(browser, server):
    pg = browser.new_page()
    pg.set_default_timeout(TIMEOUT_MS)
    errors: list[str] = []
    pg.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    pg.on("pageerror", lambda e: errors.append(f"pageerror: {e}"))
    pg.on(
        "requestfailed",
        lambda r: (
            errors.append(f"request failed: {r.url} {r.failure}"),
            print("[browser] FAILED", r.url),
        ),
    )
    foreign = record_foreign_requests(pg, server)
    pg.server = server
    pg.js_errors = errors
    yield pg
    pg.close()
    assert not errors, f"JavaScript console errors: {errors}"
    # every resource (CSS, JS, fonts) comes from the server itself: the page works offline
    assert not foreign, f"requests to other hosts: {foreign}"
