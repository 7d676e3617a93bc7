"""End-to-end tests of the dashboard in headless Chromium (Debian's /usr/bin/chromium).

The module starts the README's serve command (`panel serve app/main.py` with the Makefile's
flags, see SERVE_FLAGS) on a free port, waits for /liveness, and drives the page with
Playwright.  Waits are on selectors and URL/text changes with bounded timeouts, never sleeps.
Timings (page interactive, server time per slider move) are printed, not asserted.
Run: `.venv/bin/python -m pytest tests/test_browser.py -q -s`.
"""

from __future__ import annotations

import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
# The flags of the Makefile's `serve` target and the Dockerfile's CMD (checked below).
SERVE_FLAGS = [
    "--allow-websocket-origin=*",
    "--liveness",
    "--num-threads",
    "2",
    "--setup",
    "app/warm.py",
    "--warm",
]
TIMEOUT_MS = 60_000
# a small chain keeps the discrete scenes quick in CI; everything else at the defaults
FAST = "N=120&tol=1e-08"

if not Path(CHROMIUM).exists():  # pragma: no cover - CI installs it (make browser)
    pytest.skip("Debian chromium not installed (make browser)", allow_module_level=True)
sync_api = pytest.importorskip("playwright.sync_api")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def server():
    port = _free_port()
    env = dict(
        os.environ,
        FPU_WARM_SCENES="force,phase",
        NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", str(ROOT / ".numba_cache")),
    )
    panel = str(Path(sys.executable).with_name("panel"))
    log = tempfile.NamedTemporaryFile("w+", suffix=".log", delete=False)
    cmd = [
        panel,
        "serve",
        "app/main.py",
        "--port",
        str(port),
        "--address",
        "127.0.0.1",
        *SERVE_FLAGS,
    ]
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, cwd=ROOT, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        while True:
            if proc.poll() is not None:
                log.seek(0)
                pytest.fail(f"panel serve exited ({proc.returncode}):\n{log.read()[-3000:]}")
            try:
                with urllib.request.urlopen(url + "/liveness", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            if time.monotonic() - t0 > 240:
                pytest.fail("panel serve did not answer /liveness within 240 s")
            time.sleep(0.2)
        print(f"\n[browser] server up after {time.monotonic() - t0:.1f} s (incl. warm-up)")
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
        app_errors = [tb for tb in _tracebacks(text) if not _client_disconnect(tb)]
        assert not app_errors, "\n\n".join(app_errors)[-3000:]


# A page closed or navigated away while the server still writes to its websocket makes tornado
# log one of these: the client went away, nothing failed in the app.
_DISCONNECTS = ("tornado.websocket.WebSocketClosedError", "tornado.iostream.StreamClosedError")


def _tracebacks(log_text: str) -> list[str]:
    """Each 'Traceback …' block of a server log, up to its final exception line."""
    blocks, cur = [], None
    for line in log_text.splitlines():
        if line.lstrip().startswith("Traceback (most recent call last)"):
            cur = [line]
            blocks.append(cur)
        elif cur is not None:
            cur.append(line)
            if line and not line.startswith((" ", "\t")):  # the exception line ends the block
                cur = None
    return ["\n".join(b) for b in blocks]


def _client_disconnect(tb: str) -> bool:
    return tb.strip().splitlines()[-1].startswith(_DISCONNECTS)


def test_server_log_check_tells_app_errors_from_disconnects():
    log = (
        'Traceback (most recent call last):\n  File "x.py", line 1, in f\n'
        "tornado.websocket.WebSocketClosedError\n"
        'Traceback (most recent call last):\n  File "app/views/base.py", line 2, in g\n'
        "RuntimeError: boom\n"
    )
    tbs = _tracebacks(log)
    assert len(tbs) == 2
    assert [_client_disconnect(t) for t in tbs] == [True, False]


@pytest.fixture(scope="module")
def browser():
    profile = tempfile.mkdtemp(prefix="fpu-chromium-")
    with sync_api.sync_playwright() as p:
        ctx = p.chromium.launch_persistent_context(
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
    pg.server = server
    pg.js_errors = errors
    yield pg
    pg.close()
    assert not errors, f"JavaScript console errors: {errors}"


def open_app(page, query: str = "", scene: str = "force", timeout: float = 60.0):
    t0 = time.monotonic()
    page.goto(f"{page.server}/main" + (f"?{query}" if query else ""))
    wait_rendered(page, scene, timeout)
    return time.monotonic() - t0


def wait_rendered(page, scene: str, timeout: float = 60.0) -> str:
    """Wait (bounded) for a completed render of the scene; fail with its message if it shows
    one instead."""
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end:
        text = status_text(page, scene)
        if "Time:" in text and "computing the rest" not in text:
            return text
        page.wait_for_timeout(100)
    msg = " ".join(page.locator(f".scene-{scene} .scene-message").all_inner_texts())
    raise AssertionError(f"scene {scene} did not render in {timeout} s: {text!r} {msg!r}")


def status(page, scene: str):
    return page.locator(f".scene-{scene} .scene-status")


def status_text(page, scene: str) -> str:
    return " ".join(status(page, scene).locator("p").all_inner_texts())


def wait_status_change(page, scene: str, before: str) -> str:
    """Wait (bounded) until the scene's status shows a completed render different from before."""
    t_end = time.monotonic() + TIMEOUT_MS / 1000
    while time.monotonic() < t_end:
        now = status_text(page, scene)
        if now != before and "Time:" in now and "computing the rest" not in now:
            return now
        page.wait_for_timeout(100)
    raise AssertionError(f"scene {scene} did not change; still: {before}")


def query(page) -> dict:
    return dict(urllib.parse.parse_qsl(urllib.parse.urlparse(page.url).query))


def open_tab(page, title: str):
    page.locator(".bk-tab", has_text=title).first.click()


SCENES = [
    ("Force law", "force"),
    ("Phase plane", "phase"),
    ("Profiles", "profiles"),
    ("Diagrams", "diagram"),
    ("Floquet", "floquet"),
]


def test_every_scene_renders_a_plot(page):
    t = open_app(page, FAST)
    print(f"[browser] page interactive {t:.2f} s after navigation")
    for title, key in SCENES:
        open_tab(page, title)
        wait_rendered(page, key, 240.0)  # Floquet is the slow one
        page.locator(f".scene-{key} canvas").first.wait_for()
        assert "Error:" in status_text(page, key), status_text(page, key)
        print(f"[browser] {key}: {status_text(page, key)[:120]}")
    # simulation: runs on demand
    open_tab(page, "Simulation")
    page.locator(".scene-simulation .scene-message").get_by_text("Run simulation").wait_for()
    page.locator(".scene-simulation .bk-btn-group button", has_text="Riemann").click()
    for label, value in (("L (sites)", "300"), ("t_end", "10")):
        field = page.locator(".scene-simulation .bk-input-group", has_text=label).locator("input")
        field.fill(value)
        field.press("Enter")
    page.locator(".simulation-run button").click()
    wait_rendered(page, "simulation", 240.0)
    page.locator(".scene-simulation canvas").first.wait_for()
    print(f"[browser] simulation: {status_text(page, 'simulation')[:220]}")


@pytest.mark.parametrize(
    "slider, scene",
    [
        ("a", "force"),
        ("b", "force"),
        ("wplus", "force"),
        ("V", "force"),
        ("N", "profiles"),
        ("tol", "profiles"),
    ],
)
def test_moving_each_slider_changes_the_scene(page, slider, scene):
    open_app(page, FAST + f"&tab={scene}", scene=scene, timeout=180.0)
    before = status_text(page, scene)
    q0 = query(page)
    handle = page.locator(f".w-{slider} .noUi-handle").first
    handle.focus()
    t0 = time.monotonic()
    page.keyboard.press("ArrowLeft" if slider in ("V", "b", "tol") else "ArrowRight")
    after = wait_status_change(page, scene, before)
    dt = time.monotonic() - t0
    server = re.search(r"server ([\d.]+ m?s)", after)
    print(
        f"[browser] slider {slider}: view updated {dt:.2f} s after the key press "
        f"(server {server.group(1) if server else '?'})"
    )
    assert query(page) != q0  # the new value is in the URL too


def test_click_on_existence_diagram_picks_w_plus_and_V(page):
    open_app(page, "tab=diagram", scene="diagram")
    before = status_text(page, "diagram")
    canvas = page.locator(".scene-diagram .existence-diagram canvas").first
    canvas.wait_for()
    box = canvas.bounding_box()
    # inside the frame, left of w* (the pick may be outside the bands: then a message)
    page.mouse.click(box["x"] + 0.30 * box["width"], box["y"] + 0.45 * box["height"])
    after = wait_status_change(page, "diagram", before)
    w_plus = float(page.locator(".in-wplus input").input_value())
    V = float(page.locator(".in-V input").input_value())
    assert (w_plus, V) != (1.0, 5.0)
    assert f"current V = {V:.6g}" in after and f"w₊ = {w_plus:.6g}" in after
    assert float(page.locator(".in-wplus input").input_value()) == pytest.approx(w_plus, rel=1e-6)
    # the pick is in the URL too, like a slider move (bounded wait: the URL follows the state)
    t_end = time.monotonic() + TIMEOUT_MS / 1000
    while time.monotonic() < t_end and float(query(page).get("w_plus", "nan")) != w_plus:
        page.wait_for_timeout(100)
    q = query(page)
    assert float(q["w_plus"]) == pytest.approx(w_plus, rel=1e-9), q
    assert float(q["V"]) == pytest.approx(V, rel=1e-9), q
    assert q["tab"] == "diagram"


def test_out_of_range_setting_shows_the_message(page):
    page.goto(f"{page.server}/main?V=9&tab=phase")
    msg = page.locator(".scene-phase .scene-message")
    msg.get_by_text("V=9 is out of range: valid (4.242640687, 5.374838499) or").wait_for()
    assert "no plot" in status_text(page, "phase")
    # the server keeps serving: fix V from the exact input and the plot comes back
    inp = page.locator(".in-V input")
    inp.fill("5.1")
    inp.press("Enter")
    assert "V = 5.1" in wait_rendered(page, "phase")


def test_url_reproduces_the_view(page):
    open_app(page, "a=-1&b=10&w_plus=6&V=5.3&mode=solitary&tab=phase&N=200", scene="phase")
    text = status_text(page, "phase")
    assert "w₊ = 6" in text and "V = 5.3" in text and "tensile" in text, text
    assert page.locator(".in-V input").input_value() == "5.3"
    q = query(page)
    assert q["tab"] == "phase" and float(q["w_plus"]) == 6.0 and q["mode"] == "solitary"
    # the plot itself is framed on the computed data: no axis still at a placeholder [0, 1]
    # (a lazily built figure once kept its pre-render ranges on a page opened with ?tab=…)
    ranges = page.evaluate(
        """() => { const out = []; for (const d of Bokeh.documents) { for (const m of
        d.all_models) { if (m.type === 'Range1d' && m.visible !== false) out.push([m.start,
        m.end]); } } return out; }"""
    )
    assert ranges and all(r != [0, 1] for r in ranges), ranges
    open_app(page, "w_plus=6&mode=superkink&tab=profiles&N=200", scene="profiles")
    assert "superkink V = 5.21749" in status_text(page, "profiles")  # 7√5/3 (Fig. stabSW)


def test_serve_command_is_the_containers():
    """The tested command (SERVE_FLAGS) is the Makefile's serve target and the Dockerfile's."""
    make = (ROOT / "Makefile").read_text()
    docker = (ROOT / "Dockerfile").read_text()
    for flag in ("--liveness", "--num-threads 2", "--setup app/warm.py", "--warm"):
        assert flag in make, flag
        assert flag.replace(" ", '", "') in docker or flag in docker, flag
    assert "panel serve app/main.py" in make and '"panel", "serve", "app/main.py"' in docker


def test_atlas_scene_runs_a_small_atlas_through_the_executor(page):
    """The Atlas tab (app/views/atlas.py): a small atlas with Floquet, run in the server's
    background through fpucore.parallel's process pool, becomes a heat map with its error bars."""
    open_app(page, FAST)
    open_tab(page, "Atlas")
    page.locator(".scene-atlas .scene-message").get_by_text("atlas store").wait_for()
    for label, value in (("w₊ rows", "3"), ("velocities", "3")):
        field = page.locator(".scene-atlas .bk-input-group", has_text=label).locator("input")
        field.fill(value)
        field.press("Enter")
    page.locator(".scene-atlas button", has_text="Run a small atlas").click()
    text = wait_rendered(page, "atlas", 400.0)  # a process pool starts in the server
    page.locator(".scene-atlas canvas").first.wait_for()
    assert "max residual" in text and "atlas run (9 points" in text, text
