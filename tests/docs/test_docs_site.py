"""The documentation site: ``make docs``'s build passes with warnings as errors, holds every page
it promises (getting started, guide, API reference, a gallery page per paper figure with its
figure, code and comparison rows), and its pages load nothing from another host (headless
Chromium records every request of the index and a gallery page).

The build runs the gallery at reduced size (FPU_DOCS_REDUCED=1: the paper's printed numbers are
still compared at its parameters) into build/docs-test/, with the figure cache of
``fpu paper`` (.fpu_cache): the first build computes the 17 figures, a rebuild with the same
fpucore reads them back.
"""

from __future__ import annotations

import functools
import html
import http.server
import os
import re
import subprocess
import sys
import threading
import time
import urllib.parse
from pathlib import Path

import pytest
from browser_harness import CHROMIUM, CHROMIUM_ARGS, ROOT

pytestmark = pytest.mark.slow
SPHINX = str(Path(sys.executable).with_name("sphinx-build"))
OUT = ROOT / "build" / "docs-test"


def sphinx(*extra: str) -> tuple[subprocess.CompletedProcess, float]:
    """The command of ``make docs`` (the same flags), reduced gallery, into build/docs-test/."""
    env = dict(os.environ, FPU_DOCS_REDUCED="1", PYTHONPATH=str(ROOT))
    cmd = [SPHINX, "-W", "--keep-going", "-n", "-q", "-b", "html", *extra, "docs",
           str(OUT / "html"), "-d", str(OUT / "doctrees")]  # fmt: skip
    t0 = time.monotonic()
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=1500)
    return proc, time.monotonic() - t0


@pytest.fixture(scope="module")
def site() -> Path:
    makefile = (ROOT / "Makefile").read_text()
    assert "sphinx-build -W --keep-going -n -q -b html docs" in makefile  # the same build
    proc, dt = sphinx()
    print(f"\n[docs] build {dt:.1f} s")
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-4000:]
    return OUT / "html"


def test_every_promised_page_is_built(site):
    from fpucore.paper import FIGURES

    for page in ("index", "getting_started", "guide/index", "guide/headless", "guide/floquet",
                 "api/index", "api/wave", "api/floquet", "gallery/index"):  # fmt: skip
        assert (site / f"{page}.html").is_file(), page
    api = (site / "api" / "wave.html").read_text()
    assert "solve_superkink" in api and "WaveResult" in api  # autodoc ran on the docstrings
    for label, fig in FIGURES.items():
        page = (site / "gallery" / f"{label}.html").read_text()
        text = html.unescape(re.sub(r"<[^>]+>", "", page))  # code is split by highlighting
        assert f'src="../_images/{label}.png"' in page, label  # the figure
        assert (site / "_images" / f"{label}.png").stat().st_size > 1000, label
        assert f'paper.compute("{label}")' in text, label  # the code that makes it
        assert f"def {fig.run.__name__}(" in text, label  # and the figure function's source
        assert page.count("<tr") >= 1 + 1, f"{label}: no comparison rows"
    index = (site / "gallery" / "index.html").read_text()
    assert all(f"{label}.html" in index for label in FIGURES)


def test_a_page_per_smooth_preset_with_its_figures(site):
    """docs/laws: one page per non-polynomial preset, each with its five routes' figures and
    numbers (the class check's α, w*, β, a converged superkink, a Floquet verdict, a Riemann run
    that reached its end time), computed by the same build."""
    from fpucore.law import SmoothLaw
    from fpucore.law.presets import PRESETS, preset_law

    names = [n for n in PRESETS if isinstance(preset_law(n), SmoothLaw)]
    assert set(names) == {"exponential", "tanh", "rational"}
    index = (site / "laws" / "index.html").read_text()
    for name in names:
        assert f"{name}.html" in index, name
        page = (site / "laws" / f"{name}.html").read_text()
        text = html.unescape(re.sub(r"<[^>]+>", "", page))
        for fig in ("force", "diagram", "superkink", "solitary", "floquet", "riemann"):
            assert f'src="../_images/{name}_{fig}.png"' in page, (name, fig)
            assert (site / "_images" / f"{name}_{fig}.png").stat().st_size > 1000, (name, fig)
        law = preset_law(name)
        assert f"{law.w_star:.10g}" in text and f"{law.beta:.10g}" in text, name
        assert text.count("converged True") == 2, name  # the superkink and the solitary wave
        verdict = r"max\|μ\| = [0-9.]+ ± [0-9.e-]+,\s+(stable|finite_size|unstable) — "
        assert re.search(verdict, text), name
        assert "Riemann run" in text and "reached t =" in text, name
        assert "def compute(" in text, name  # the code that computed the page


def test_rebuild_reads_the_cache(site):
    """A second build with the same fpucore computes nothing (cached figures, unchanged pages)."""
    proc, dt = sphinx()
    print(f"\n[docs] rebuild {dt:.1f} s")
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-4000:]
    assert dt < 120, dt


@pytest.fixture(scope="module")
def served(site):
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(site))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()
    httpd.server_close()


@pytest.mark.browser
@pytest.mark.skipif(not Path(CHROMIUM).exists(), reason="make browser installs chromium")
@pytest.mark.parametrize("page", ["index.html", "gallery/Riemann1.html"])
def test_pages_load_nothing_from_another_host(served, page, playwright):
    host = urllib.parse.urlparse(served).netloc
    requests: list[str] = []
    browser = playwright.chromium.launch(
        executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True
    )
    try:
        pg = browser.new_page()
        pg.on("request", lambda r: requests.append(r.url))
        # a request elsewhere is recorded, then refused (no waiting on a network that is not there)
        pg.route("**/*", lambda route: route.continue_()
                 if urllib.parse.urlparse(route.request.url).netloc == host
                 else route.abort())  # fmt: skip
        pg.goto(f"{served}/{page}", wait_until="networkidle")
        broken = pg.evaluate(
            "[...document.images].filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.src)"
        )
    finally:
        browser.close()
    foreign = [u for u in requests if urllib.parse.urlparse(u).netloc not in (host,)
               and not u.startswith(("data:", "blob:"))]  # fmt: skip
    assert not foreign, f"{page} requests other hosts: {foreign}"
    assert any(u.endswith(".css") for u in requests), requests  # the recorder saw the page load
    assert not broken, f"{page}: images not loaded: {broken}"
    if page.startswith("gallery/"):
        assert any(u.endswith("Riemann1.png") for u in requests), requests
