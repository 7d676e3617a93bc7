"""End-to-end tests of the dashboard in headless Chromium (Debian's /usr/bin/chromium).

The module starts the README's serve command (`panel serve app/main.py` with the Makefile's
flags, see SERVE_FLAGS) on a free port, waits for /liveness, and drives the page with
Playwright.  Waits are on selectors and URL/text changes with bounded timeouts, never sleeps.
Timings (page interactive, server time per slider move) are printed, not asserted.
Run: `.venv/bin/python -m pytest tests/test_browser.py -q -s`.
"""

from __future__ import annotations

import os
import random
import re
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

from app.state import URL_PARAMS

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
        app_errors = [tb for tb in _tracebacks(text) if not _client_disconnect(tb)]
        assert not app_errors, "\n\n".join(app_errors)[-3000:]
        # the worker pools and the law worker release their semaphores at shutdown (the
        # resource tracker names any left: "There appear to be N leaked semaphore objects")
        assert "leaked" not in text, [ln for ln in text.splitlines() if "leaked" in ln]
        assert proc.returncode == 0 or proc.returncode == -15, proc.returncode


#: the running server's log file (read by the tests that check it after every step)
SERVER_LOG: dict[str, str] = {}


def app_tracebacks() -> list[str]:
    """Tracebacks of the app in the server log so far (client disconnects excluded)."""
    text = Path(SERVER_LOG["path"]).read_text(errors="replace")
    return [tb for tb in _tracebacks(text) if not _client_disconnect(tb)]


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
    # (Bokeh's "assert self._session is not None" at a browser's close is no longer excused:
    # app/server_guards.py handles it)
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
    foreign = record_foreign_requests(pg, server)
    pg.server = server
    pg.js_errors = errors
    yield pg
    pg.close()
    assert not errors, f"JavaScript console errors: {errors}"
    # every resource (CSS, JS, fonts) comes from the server itself: the page works offline
    assert not foreign, f"requests to other hosts: {foreign}"


def record_foreign_requests(pg, server: str) -> list[str]:
    """The list the page's requests to other hosts than the server are appended to."""
    host = urllib.parse.urlparse(server).netloc
    foreign: list[str] = []
    pg.on(
        "request",
        lambda r: (
            foreign.append(r.url)
            if urllib.parse.urlparse(r.url).netloc not in (host, "")
            and not r.url.startswith(("data:", "blob:"))
            else None
        ),
    )
    return foreign


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


def inputs_reach_the_server(page) -> None:
    """Pause between typing values and clicking a button that uses them: Panel applies a
    widget's value change after a 50 ms debounce (``Syncable._debounce``; holoviz/panel#6155)
    and the server handles events on 2 threads (--num-threads 2), so a click sent right after
    the values can be handled before them (a person takes longer than this between the two)."""
    page.wait_for_timeout(500)


def run_riemann(page, t_end: str, L: str = "300") -> str:
    """On the open Simulation tab: a Riemann run of L sites to t_end; its status once shown."""
    page.locator(".scene-simulation .bk-btn-group button", has_text="Riemann").click()
    for label, value in (("L (sites)", L), ("t_end", t_end)):
        field = page.locator(".scene-simulation .bk-input-group", has_text=label).locator("input")
        field.fill(value)
        field.press("Enter")
    inputs_reach_the_server(page)
    page.locator(".simulation-run button").click()
    return wait_rendered(page, "simulation", 240.0)


def open_tab(page, title: str):
    page.locator(".bk-tab", has_text=title).first.click()


SCENES = [
    ("Force law", "force"),
    ("Phase plane", "phase"),
    ("Wave profiles", "profiles"),
    ("Amplitude, energy, existence", "diagram"),
    ("Floquet stability", "floquet"),
]


def test_every_scene_renders_a_plot(page):
    t = open_app(page, FAST)
    print(f"[browser] page interactive {t:.2f} s after navigation")
    for title, key in SCENES:
        open_tab(page, title)
        wait_rendered(page, key, 240.0)  # Floquet is the slow one
        page.locator(f".scene-{key} canvas").first.wait_for()
        assert "Error:" in status_text(page, key), status_text(page, key)
        if key == "diagram":  # the energy criterion's sentence
            assert "Energy criterion" in status_text(page, key), status_text(page, key)
        print(f"[browser] {key}: {status_text(page, key)[:120]}")
    # simulation: runs on demand
    open_tab(page, "Simulation")
    page.locator(".scene-simulation .scene-message").get_by_text("Run simulation").wait_for()
    run_riemann(page, t_end="10")
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
        d.all_models) { if (m.name === 'phase-x' || m.name === 'phase-y') out.push([m.start,
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
    inputs_reach_the_server(page)
    page.locator(".scene-atlas button", has_text="Run a small atlas").click()
    text = wait_rendered(page, "atlas", 400.0)  # a process pool starts in the server
    page.locator(".scene-atlas canvas").first.wait_for()
    assert "max residual" in text and "atlas run (9 points" in text, text


# ------------------------------------------------------------ scene robustness in the page
TAB_TITLES = {key: title for title, key in SCENES} | {"simulation": "Simulation"}

JS_SOURCE = """(name) => { for (const d of Bokeh.documents) { for (const m of d.all_models) {
  if (m.name === name && m.data) { return {x: Array.from(m.data.x), y: Array.from(m.data.y)}; }
} } return null; }"""


def source(page, name: str) -> dict:
    """The browser's copy of a named ColumnDataSource (what the plot draws)."""
    return page.evaluate(JS_SOURCE, name)


URL_KEYS = {"a", "b", "w_plus", "V", "N", "tol", "mode", "tab"}


def stamp(q: dict) -> str:
    """The parameters line a scene writes under its status, from the URL query (the law only
    when the URL has one: an expression, which replaces a, b)."""
    rest = f"w_plus={q['w_plus']} V={q['V']} N={q['N']} tol={q['tol']} mode={q['mode']}"
    if q.get("law"):
        return f"Parameters: {rest} law={q['law']}"
    return f"Parameters: a={q['a']} b={q['b']} {rest}"


def message_text(page, scene: str) -> str:
    loc = page.locator(f".scene-{scene} .scene-message p")
    return " ".join(t for t in loc.all_inner_texts() if t.strip())


def url_message(page) -> str:
    return " ".join(page.locator(".url-message p").all_inner_texts())


def wait_url(page, pred, timeout: float = 20.0) -> dict:
    """Wait (bounded, no failure) until the URL query satisfies ``pred``; the query."""
    t_end = time.monotonic() + timeout
    q = query(page)
    while not pred(q) and time.monotonic() < t_end:
        page.wait_for_timeout(50)
        q = query(page)
    return q


def settled(page, timeout: float = 90.0) -> tuple[str, str, dict]:
    """Wait (bounded) until the active scene shows a completed render — a plot or a message —
    of exactly the state in the URL; (status, message, query).  Fails if the scene is dead."""
    t_end = time.monotonic() + timeout
    text, q = "", {}
    while time.monotonic() < t_end:
        q = query(page)
        scene = q.get("tab", "force")
        if scene not in TAB_TITLES:
            scene = "force"
        text = status_text(page, scene)
        if (
            URL_KEYS <= set(q)
            and stamp(q) in text
            and "computing the rest" not in text
            and ("Time:" in text or "no plot" in text)
        ):
            return text, message_text(page, scene), q
        page.wait_for_timeout(80)
    raise AssertionError(f"scene dead or stale after {timeout} s: url {q}, status {text!r}")


def check_consistent(page, text: str, msg: str, q: dict, wait_s: float = 5.0) -> None:
    """What the plot's data sources hold matches the status text — within ``wait_s``: status
    and data reach the browser in separate messages, so the data may trail by a few ms."""
    t_end = time.monotonic() + wait_s
    while True:
        try:
            return check_consistent_now(page, text, msg, q)
        except AssertionError:
            if time.monotonic() > t_end:
                raise
            page.wait_for_timeout(100)


def check_consistent_now(page, text: str, msg: str, q: dict) -> None:
    scene = q["tab"]
    if "no plot" in text:
        assert msg, f"{scene}: no plot and no message"
        return
    if scene == "floquet":
        N = int(q["N"])
        assert f"N = {N}: {2 * N} multipliers" in text, text
        assert len(source(page, "floquet-multipliers")["x"]) == 2 * N
    elif scene == "diagram" and "current V = " in text:
        cur = source(page, "diagram-current")
        assert cur["x"] == [pytest.approx(float(q["w_plus"]), rel=1e-12)], (cur, q)
        assert cur["y"] == [pytest.approx(float(q["V"]), rel=1e-12)], (cur, q)
    elif scene == "profiles":
        dots = len(source(page, "profile-discrete")["x"])
        assert (dots > 0) == ("discrete amplitude" in text), (dots, text)
        assert len(source(page, "profile-qc")["x"]) > 0
    elif scene == "force" and q["mode"] == "solitary" and "current V not drawn" not in msg:
        line = source(page, "force-rayleigh-V")
        assert len(line["x"]) == 2
        # the Rayleigh line of the URL's V: slope V² (f(w₊) + V² (w − w₊))
        (x0, x1), (y0, y1) = line["x"], line["y"]
        assert (y1 - y0) / (x1 - x0) == pytest.approx(float(q["V"]) ** 2, rel=1e-9), (line, q)


def run_floquet_sweep(page, total: int) -> None:
    """On the open Floquet tab: type the sweep's number of velocities, press Sweep and wait
    (bounded) until panel (c)'s data reach the browser."""
    field = page.locator(".scene-floquet .bk-input-group", has_text="velocities").locator("input")
    field.fill(str(total))
    field.press("Enter")
    inputs_reach_the_server(page)
    page.locator(".floquet-sweep button").click()
    t_end = time.monotonic() + 240
    while not source(page, "floquet-sweep")["x"] and time.monotonic() < t_end:
        page.wait_for_timeout(200)


def test_floquet_plot_follows_N_and_shows_the_sweep_without_reload(page):
    """N = 200 → three key presses; the plot holds the new 2N multipliers."""
    page.goto(f"{page.server}/main?tab=floquet&N=200&tol=1e-08")
    text, msg, q = settled(page, 240)
    check_consistent(page, text, msg, q)
    handle = page.locator(".w-N .noUi-handle").first
    handle.focus()
    for _ in range(3):
        page.keyboard.press("ArrowRight")
    t_end = time.monotonic() + 60
    while query(page).get("N") != "206" and time.monotonic() < t_end:
        page.wait_for_timeout(100)
    text, msg, q = settled(page, 240)
    assert q["N"] == "206" and "N = 206: 412 multipliers" in text, text
    check_consistent(page, text, msg, q)
    run_floquet_sweep(page, 6)  # the total: 3 velocities on each interval
    assert len(source(page, "floquet-sweep")["x"]) >= 1  # panel (c) without a reload
    # the energy criterion on (c): E_ren is monotone along w₊ = 1, so no mark
    t_end = time.monotonic() + 60
    while "Energy criterion" not in status_text(page, "floquet") and time.monotonic() < t_end:
        page.wait_for_timeout(200)
    assert "no minimum or maximum" in status_text(page, "floquet")
    assert source(page, "floquet-energy-extremum")["x"] == []
    assert not app_tracebacks()


def test_bad_url_values_are_named_and_the_rest_is_kept(page):
    """Invalid values named with their range, the others kept, the address
    bar rewritten to what is shown; a 5000-digit value is a message, not a blank page."""
    page.goto(f"{page.server}/main?N=-5&V=5.2&tab=phase&b=1e200&mode=bogus&tol=0")
    text, msg, q = settled(page)
    note = url_message(page)
    for needle in ("N=-5", "b=1e+200", "mode='bogus'", "tol=0", "valid"):
        assert needle in note, (needle, note)
    assert q["V"] == "5.2" and q["tab"] == "phase" and q["N"] == "500" and q["b"] == "10.0"
    assert "V = 5.2" in text
    page.goto(f"{page.server}/main?tab=force&N=" + "9" * 5000)
    text, msg, q = settled(page)
    assert "at most 40 characters" in url_message(page)
    page.goto(f"{page.server}/main?tab=force&N=3000&V=5.1")
    text, msg, q = settled(page)
    assert q["N"] == "3000"
    page.locator(".w-N").get_by_text("3000").first.wait_for(timeout=10_000)  # slider = computed
    assert not app_tracebacks()


def test_downloads_record_the_parameters(page):
    """The profile CSV's header records a, b, w₊, V, N, tol and the version."""
    page.goto(f"{page.server}/main?tab=profiles&N=120&tol=1e-08&V=5.1")
    text, msg, q = settled(page, 120)
    with page.expect_download() as dl:
        page.locator(".scene-profiles .scene-download").first.click()
    body = Path(dl.value.path()).read_text()
    for needle in ("a=-1.0", "b=10.0", "w_plus=1.0", "V=5.1", "N=120", "tol=1e-08", "fpucore"):
        assert needle in body, needle
    assert "n,w,wdot,w_qc" in body


def test_state_walk(page):
    """A seeded, bounded random walk through what users do — slider moves, mode switches, tab
    changes, invalid values typed or in the URL, and recoveries — checking after every step
    that the active scene renders the URL's state (none is dead), that the plot's data sources
    match the status text, and that the server log has no traceback."""
    rng = random.Random(13)
    base = "a=-1&b=10&w_plus=1&V=5&N=80&tol=1e-08&mode=solitary"
    page.goto(f"{page.server}/main?{base}&tab=force")
    settled(page, 120)
    t_end = time.monotonic() + 150  # bounded: the step count adapts to the machine
    steps, kinds = 0, {}
    history: list[str] = []
    while steps < 300 and time.monotonic() < t_end:
        r = rng.random()
        if r < 0.45:
            kind = "slider"
            name = rng.choice(["a", "b", "wplus", "V", "V", "N"])
            before = query(page)
            page.locator(f".w-{name} .noUi-handle").first.focus()
            for _ in range(rng.randint(1, 3)):
                page.keyboard.press(rng.choice(["ArrowLeft", "ArrowRight"]))
            wait_url(page, lambda q, b=before: q != b, 3.0)  # unchanged at a slider's end
        elif r < 0.6:
            kind = "tab"
            key = rng.choice(["force", "phase", "profiles", "diagram", "floquet", "simulation"])
            open_tab(page, TAB_TITLES[key])
            wait_url(page, lambda q, k=key: q.get("tab") == k)
        elif r < 0.7:
            kind = "mode"
            mode = rng.choice(["superkink", "solitary"])
            page.locator(".w-mode button", has_text=mode).click()
            wait_url(page, lambda q, m=mode: q.get("mode") == m)
        elif r < 0.75:
            # typed into the exact box: V_SK itself (invalid in solitary mode), out of range,
            # or a valid V — the slider must show it without echoing another value back
            kind = "typed V"
            V = rng.choice(["5.374838498865699", "9", "4.1", "5.2", "5.45"])
            inp = page.locator(".in-V input")
            inp.fill(V)
            inp.press("Enter")
            wait_url(page, lambda q, v=V: q.get("V") in (v, repr(float(v))))
        elif r < 0.85:
            kind = "invalid URL"
            bad = rng.choice(["N=-5", "N=101", "tol=0", "V=abc", "mode=bogus", "b=1e200"])
            tab = rng.choice(["force", "phase", "diagram", "profiles"])
            page.goto(f"{page.server}/main?{base}&tab={tab}&{bad}")
        else:
            kind = "recovery"
            V = rng.choice(["4.6", "5.1", "5.45"])
            tab = rng.choice(["force", "phase", "diagram", "profiles", "floquet"])
            page.goto(f"{page.server}/main?{base.replace('V=5', 'V=' + V)}&tab={tab}")
        # (each step above waits until the URL shows it: a status that matches a URL still
        # showing the previous step would pass `settled` and compare the wrong state)
        text, msg, q = settled(page)
        if kind == "typed V":
            # the state keeps the typed value: no slider echo moved it (a late echo would
            # arrive within a few hundred ms of the slider update)
            page.wait_for_timeout(300)
            V_now = query(page).get("V")
            assert float(V_now) == float(V), f"step {steps}: typed V={V}, URL V={V_now}"
        try:
            check_consistent(page, text, msg, q)
        except AssertionError as exc:
            raise AssertionError(f"step {steps} ({kind}, after {history[-3:]}): {exc}") from None
        history.append(kind)
        assert "Traceback" not in msg and "computation failed" not in msg, msg
        tbs = app_tracebacks()
        assert not tbs, f"step {steps} ({kind}): {tbs[-1][-2000:]}"
        steps += 1
        kinds[kind] = kinds.get(kind, 0) + 1
    print(f"[browser] state walk: {steps} steps {kinds}")
    # bounded by time: on 2 cores shared with other jobs ~40 steps fit, on an idle machine 300
    assert steps >= 20 and len(kinds) >= 4


JS_WIDGET_VALUE = """(cls) => { for (const d of Bokeh.documents) { for (const m of d.all_models) {
  if ((m.css_classes || []).includes(cls) && 'value_throttled' in m) return m.value;
} } return null; }"""


def widget_value(page, css_class: str) -> float:
    """The value of the browser's model of a sidebar widget (slider or number box)."""
    return page.evaluate(JS_WIDGET_VALUE, css_class)


def type_into(page, css_class: str, text: str, url_name: str, url_value: str) -> tuple:
    """Type ``text`` + Enter into a box; wait (bounded) until the URL shows ``url_value`` and the
    page settles; then a pause in which a late echo would arrive.  (status, message, query)"""
    box = page.locator(f".{css_class} input")
    box.fill(text)
    box.press("Enter")
    wait_url(page, lambda q: q.get(url_name) == url_value, 20.0)
    page.wait_for_timeout(500)
    return settled(page)


def press_on_slider(page, css_class: str, key: str) -> dict:
    """Focus a slider's handle and press ``key``; wait (bounded) for the URL to change."""
    before = query(page)
    page.locator(f".{css_class} .noUi-handle").first.focus()
    page.keyboard.press(key)
    wait_url(page, lambda q: q != before, 20.0)
    page.wait_for_timeout(500)
    return settled(page)[2]


def test_a_value_typed_again_after_the_state_moved_is_kept(page):
    """A box or slider returned by the user to the value it last sent, after the state had moved
    it elsewhere, still reaches the state.  (Panel never sent value_throttled to the browser:
    its stale copy equalled the new value, so nothing was sent — the state walk's V = 5.2 typed
    a second time stayed at 5.200694 while the box showed 5.2.)  Checked after each step: the
    URL, the box, the slider and the plot's parameters line show the same value."""

    def agree(name: str, box_class: str, slider_class: str, text, msg, q) -> None:
        x = float(q[name])
        assert float(page.locator(f".{box_class} input").input_value()) == x, (name, q)
        assert widget_value(page, box_class) == x, (name, q)
        assert widget_value(page, slider_class) == pytest.approx(x, rel=1e-12), (name, q)
        assert stamp(q) in text, (text, q)
        check_consistent(page, text, msg, q)

    # superkink mode: V typed (the w₊ slider follows off its grid), moved by a slider step, typed
    # again; then w₊ the same way with a value off its slider's grid
    page.goto(f"{page.server}/main?a=-1&b=10&w_plus=1&mode=superkink&tab=force&{FAST}")
    settled(page)
    for name, box, slider, typed in (
        ("V", "in-V", "w-V", "5.2"),
        ("w_plus", "in-wplus", "w-wplus", "0.61234567"),
    ):
        text, msg, q = type_into(page, box, typed, name, typed)
        assert q[name] == typed, q  # no slider snapped it and sent it back
        agree(name, box, slider, text, msg, q)
        q = press_on_slider(page, slider, "ArrowRight")
        assert q[name] != typed, q
        text, msg, q = type_into(page, box, typed, name, typed)
        assert q[name] == typed, (name, q)
        agree(name, box, slider, text, msg, q)
    # a slider sent to its end, moved by its box, and sent to its end again (solitary V, N)
    page.goto(f"{page.server}/main?a=-1&b=10&w_plus=1&V=5&mode=solitary&tab=force&{FAST}")
    settled(page)
    for name, box, slider, typed in (("V", "in-V", "w-V", "5.1"), ("N", "in-N", "w-N", "120")):
        end = press_on_slider(page, slider, "End")[name]
        assert end != typed
        type_into(page, box, typed, name, typed)
        text, msg, q = settled(page)
        q = press_on_slider(page, slider, "End")
        assert q[name] == end, (name, end, q)
        assert widget_value(page, slider) == float(end)
        assert float(page.locator(f".{box} input").input_value()) == float(end), (name, q)
    # a coefficient slider of a typed law: to its end, the law typed again, to its end again
    page.locator(".w-law-kind button", has_text="expression").click()
    law = "w + 10*w**2 - w**3"
    type_into(page, "in-law", law, "law", law)
    moved = press_on_slider(page, "w-c2", "End")["law"]
    assert moved != law
    type_into(page, "in-law", law, "law", law)
    q = press_on_slider(page, "w-c2", "End")
    assert q["law"] == moved, (moved, q)
    assert page.locator(".in-law input").input_value() == moved
    assert not app_tracebacks()


def _liveness(server: str) -> float:
    t = time.monotonic()
    with urllib.request.urlopen(server + "/liveness", timeout=30) as r:
        assert r.status == 200
    return time.monotonic() - t


def test_heavy_floquet_in_one_session_does_not_block_another(browser, server):
    """Session A starts a Floquet spectrum at N = 1400 (tens of seconds, in a worker process);
    session B moves a QC slider five times and gets each answer in time, /liveness answers,
    and A's Cancel stops the job."""
    a, b = browser.new_page(), browser.new_page()
    try:
        a.goto(f"{server}/main?tab=floquet&N=1400&V=5.15&tol=1e-10")
        a.locator(".scene-floquet .scene-cancel button").wait_for(state="visible", timeout=60_000)
        b.goto(f"{server}/main?tab=force&V=5.05")
        text, _, _ = settled(b)
        handle = b.locator(".w-V .noUi-handle").first
        handle.focus()
        times = []
        for _ in range(5):
            before = status_text(b, "force")
            t = time.monotonic()
            b.keyboard.press("ArrowLeft")
            wait_status_change(b, "force", before)
            times.append(time.monotonic() - t)
        live = [_liveness(server) for _ in range(3)]
        print(f"[browser] QC answers while a spectrum runs: {times}; /liveness {live}")
        # generous (the machine is shared; the ≤ 100 ms figure is in benchmarks/bench_app.py):
        # before the fix a spectrum held the server for tens of seconds
        assert statistics.median(times) < 2.0 and max(times) < 10.0 and max(live) < 2.0
        # if the heavy session is still computing, Cancel stops it
        if "N = 1400" not in status_text(a, "floquet"):
            a.locator(".scene-floquet .scene-cancel button").click(timeout=10_000)
            a.locator(".scene-floquet .scene-message p", has_text="Cancelled").wait_for(
                timeout=30_000
            )
    finally:
        a.close()
        b.close()
    assert not app_tracebacks()


def test_ten_sessions_without_cross_talk(browser, server):
    """Ten sessions with ten velocities: each shows its own; a slider move in one changes no
    other."""
    Vs = [f"{4.4 + 0.09 * k:.2f}" for k in range(10)]
    pages = [browser.new_page() for _ in Vs]
    try:
        for pg, V in zip(pages, Vs):
            pg.goto(f"{server}/main?tab=phase&V={V}")
        for pg, V in zip(pages, Vs):
            text, _, q = settled(pg)
            assert float(q["V"]) == float(V) and f"V = {float(V):.6g}" in text
        before = [status_text(pg, "phase") for pg in pages]
        pages[0].locator(".w-V .noUi-handle").first.focus()
        pages[0].keyboard.press("ArrowRight")
        wait_status_change(pages[0], "phase", before[0])
        pages[-1].wait_for_timeout(500)
        for pg, old in zip(pages[1:], before[1:]):
            assert status_text(pg, "phase") == old
    finally:
        for pg in pages:
            pg.close()
    assert not app_tracebacks()


# ------------------------------------------------------------------------------ a typed law
QUARTIC = "w + 10*w**2 - w**3 - 0.01*w**4"


def test_typed_law_reaches_every_scene_and_the_url(page):
    """Choose "expression", type the quartic, and every scene renders for it — its
    status has "Time:" and the law in its parameters line, the URL carries law=…, a coefficient
    slider rewrites the law, and the server log has no traceback."""
    open_app(page, FAST)
    page.locator(".w-law-kind button", has_text="expression").click()
    box = page.locator(".in-law input")
    box.wait_for()
    box.fill(QUARTIC)
    box.press("Enter")
    t_end = time.monotonic() + TIMEOUT_MS / 1000
    while time.monotonic() < t_end and query(page).get("law") != QUARTIC:
        page.wait_for_timeout(100)
    assert query(page).get("law") == QUARTIC, query(page)
    text, msg, q = settled(page, 120)
    assert f"law={QUARTIC}" in text and "Time:" in text, (text, msg)
    assert "V_SK = 5.284298946" in " ".join(page.locator(".ranges p").all_inner_texts())
    for title, key in SCENES:
        open_tab(page, title)
        text = wait_rendered(page, key, 240.0)
        page.locator(f".scene-{key} canvas").first.wait_for()
        assert f"law={QUARTIC}" in text, (key, text)
        assert not message_text(page, key), (key, message_text(page, key))
        print(f"[browser] quartic {key}: {text[:110]}")
        assert not app_tracebacks(), app_tracebacks()[-1][-2000:]
    open_tab(page, "Simulation")
    text = run_riemann(page, t_end="5")
    assert f"law={QUARTIC}" in text, text
    # a coefficient slider (c₄) rewrites the law: status, URL and text box follow
    open_tab(page, "Force law")
    before = wait_rendered(page, "force")
    page.locator(".w-c4 .noUi-handle").first.focus()
    page.keyboard.press("ArrowRight")
    after = wait_status_change(page, "force", before)
    law = query(page).get("law", "")
    assert law != QUARTIC and "w**4" in law and f"law={law}" in after, (law, after)
    assert page.locator(".in-law input").input_value() == law
    assert not app_tracebacks(), app_tracebacks()[-1][-2000:]


def test_invalid_law_in_the_url_is_named_and_the_rest_kept(page):
    page.goto(f"{page.server}/main?law=w%2Bw**2&V=5.1&tab=phase")
    page.locator(".url-message").get_by_text("law=").wait_for()
    assert "no softening" in url_message(page), url_message(page)
    text = wait_rendered(page, "phase")
    assert "V = 5.1" in text and "law=" not in text  # the cubic, with the URL's V


# ----------------------------------------------------------------------------- user text
#: OWASP-style payloads (each ≤ 40 characters, so a URL message repeats it whole)
PAYLOADS = [
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(7)>",
    '"><svg onload=alert(1)>',
    "<iframe src=javascript:alert(1)>",
    "<details open ontoggle=alert(1)>",
    "javascript:alert(1)",
    "[x](javascript:alert(1))",
    "';alert(1)//",
    "__import__('os')",
    "**b** _i_ `c` $x$ &amp; # h",
    "<svg onload=alert(1)>",
    "<iframe srcdoc=<svg/onload=alert(1)>>",
    "<javascript:alert(1)>",
    "&lt;img src=x onerror=alert(1)&gt;",
    "&#60;svg onload=alert(1)&#62;",
    "</textarea><script>alert(1)</script>",
    '" onmouseover="alert(1)',
    "' autofocus onfocus='alert(1)",
    "`${alert(1)}`{{7*7}}",
    "\u200b<img src=x onerror=alert(1)>",
    "\u202e<svg onload=alert(1)>",
    # percent-encoded text (on the wire: double-encoded), decoded once by the server only
    "%3Cscript%3Ealert(1)%3C%2Fscript%3E",
    "%253Csvg%2520onload%253Dalert(1)%253E",
    # Markdown's linkify made links of these
    "http://evil.example //evil.example",
]
#: a 5000-character value (a URL message repeats its first 12 characters; a text box takes
#: at most 5000, Panel's TextInput.max_length)
LONG_PAYLOAD = ("<img src=x onerror=alert(1)>" * 179)[:5000]
# every URL parameter but the atlas store, whose value is a path (any text below the server's
# directory is a valid one): it gets its own loop below
URL_NAMES = ("a", "b", "law", "w_plus", "V", "mode", "tab", "N", "tol")

#: every element of the page, through Bokeh's shadow roots: injected markup (an element whose
#: attribute is an event handler, a javascript: URL or a payload's link, or a script that
#: calls alert)
JS_INJECTED = """() => { const bad = []; const walk = (root) => {
  for (const el of root.querySelectorAll('*')) {
    for (const at of el.attributes) {
      const v = (at.value || '').toLowerCase();
      if (at.name.startsWith('on') || v.includes('javascript:') || v.includes('alert(') ||
          v.includes('evil.example'))
        bad.push(el.tagName + ' ' + at.name + '=' + at.value);
    }
    if (el.tagName === 'SCRIPT' && (el.textContent || '').includes('alert(')) bad.push('SCRIPT');
    if (el.shadowRoot) walk(el.shadowRoot);
  } }; walk(document); return bad; }"""


def injected(page) -> list[str]:
    return page.evaluate(JS_INJECTED)


def test_the_payload_list_covers_every_url_parameter():
    assert set(URL_NAMES) | {"atlas"} == set(URL_PARAMS)


def test_user_text_is_shown_literally_and_never_runs(page):
    """Every URL parameter and every text input gets the payload list: no dialog fires, no
    element with an event handler / javascript: URL appears in the DOM, and the messages repeat
    each value exactly as typed (the old Markdown rendering ran ``V`` and ``tab`` payloads as
    script and showed ``__import__('os')`` as ``import('os')``)."""
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    for payload in PAYLOADS:
        q = urllib.parse.urlencode({n: payload for n in URL_NAMES})
        page.goto(f"{page.server}/main?{q}")
        page.locator(".url-message").get_by_text("tab=").wait_for()
        settled(page)
        page.wait_for_timeout(300)  # an onerror fires once the image has failed to load
        # the law's refusal may follow the page (a law the worker has not answered within
        # URL_LAW_WAIT_S is named once it has): bounded wait for every name
        t_end = time.monotonic() + 20
        note = ""
        while time.monotonic() < t_end:
            note = " ".join(url_message(page).split())
            if all(f"{name}=" in note for name in URL_NAMES):
                break
            page.wait_for_timeout(100)
        for name in URL_NAMES:
            assert f"{name}={payload!r}" in note, (name, payload, note)
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the law box: the typed text is repeated in the scene's parameters line and message
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    page.locator(".w-law-kind button", has_text="expression").click()
    box = page.locator(".in-law input")
    for payload in PAYLOADS:
        box.fill(payload)
        box.press("Enter")
        wait_url(page, lambda q, p=payload: q.get("law") == p.strip())
        text, msg, q = settled(page)
        assert f"law={payload.strip()}" in " ".join(text.split()), (payload, text)
        assert msg, (payload, text)  # no law: the scene says why
        page.wait_for_timeout(300)
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the atlas store from the URL: the scene's message names the path, nothing runs
    for payload in PAYLOADS:
        q = urllib.parse.urlencode({"tab": "atlas", "atlas": payload, "N": "120"})
        page.goto(f"{page.server}/main?{q}")
        msg = page.locator(".scene-atlas .scene-message").get_by_text("no atlas store")
        msg.wait_for(timeout=20_000)
        page.wait_for_timeout(300)
        if "/" not in payload:  # a path keeps its text (a slash may be normalised away)
            assert payload in msg.inner_text(), (payload, msg.inner_text())
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the atlas store's path box: its message names the path as typed
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    open_tab(page, "Atlas")
    store = page.locator(".scene-atlas .bk-input-group", has_text="atlas store").locator("input")
    for payload in [p for p in PAYLOADS if "/" not in p]:
        store.fill(payload)
        store.press("Enter")
        page.locator(".scene-atlas .scene-message").get_by_text(payload).wait_for(timeout=20_000)
        page.wait_for_timeout(300)
        assert not injected(page), (payload, injected(page))
    store.fill(LONG_PAYLOAD)
    store.press("Enter")
    message = page.locator(".scene-atlas .scene-message")
    message.get_by_text(f"atlas store={LONG_PAYLOAD[:12] + '…'!r}").wait_for(timeout=20_000)
    assert not injected(page), injected(page)
    assert not dialogs, dialogs
    assert not app_tracebacks()


def test_a_5000_character_value_is_cut_in_its_message_and_never_runs(page):
    """LONG_PAYLOAD in each URL parameter alone and in the law box: the URL message names the
    parameter with the value's first 12 characters, the law box's text is the law shown in the
    parameters line, nothing runs and the server logs no traceback."""
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    for name in URL_PARAMS:
        page.goto(f"{page.server}/main?" + urllib.parse.urlencode({name: LONG_PAYLOAD}))
        page.locator(".url-message").get_by_text(f"{name}=").wait_for()
        settled(page)
        page.wait_for_timeout(300)
        note = " ".join(url_message(page).split())
        assert f"{name}={LONG_PAYLOAD[:12] + '…'!r}" in note, (name, note)
        assert not injected(page), (name, injected(page))
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    page.locator(".w-law-kind button", has_text="expression").click()
    box = page.locator(".in-law input")
    box.fill(LONG_PAYLOAD)
    box.press("Enter")
    wait_url(page, lambda q: q.get("law") == LONG_PAYLOAD)
    text, msg, q = settled(page)
    assert f"law={LONG_PAYLOAD}" in text and msg, (text[:300], msg[:300])
    page.wait_for_timeout(300)
    assert not injected(page), injected(page)
    assert not dialogs, dialogs
    assert not app_tracebacks()


# ----------------------------------------------------------------------------- laws off the loop
DOS_LAWS = ["(w+1)**100000", "w*9**9**9"]


def server_rss_mb() -> float:
    for line in Path(f"/proc/{SERVER_LOG['pid']}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


class LivenessProbe(threading.Thread):
    """Polls /liveness (and the server's RSS) every 0.1 s until stopped."""

    def __init__(self, server: str):
        super().__init__(daemon=True)
        self.server, self.times, self.rss = server, [], []
        self.halt = threading.Event()

    def run(self):
        while not self.halt.is_set():
            self.times.append(_liveness(self.server))
            self.rss.append(server_rss_mb())
            self.halt.wait(0.1)

    def stop(self) -> LivenessProbe:
        self.halt.set()
        self.join(30)
        return self


def test_a_pathological_law_never_freezes_the_server(browser, server):
    """Session A opens DoS links (a law whose expansion takes minutes and gigabytes) and types
    one in the law box; meanwhile session B moves a slider: B's renders and /liveness answer
    within 1 s (FPU_STRICT_TIMING=1; 5 s otherwise), the server's RSS grows < 100 MB, and A names
    the refused law.  (Before: the server froze for ~111 s on the first link and > 6 min on the
    second.)"""
    a, b = browser.new_page(), browser.new_page()
    try:
        b.goto(f"{server}/main?tab=force&V=5.05")
        settled(b)
        rss0 = server_rss_mb()
        probe = LivenessProbe(server)
        probe.start()
        renders = []
        for law in DOS_LAWS:
            a.goto(f"{server}/main?" + urllib.parse.urlencode({"law": law, "tab": "force"}))
            handle = b.locator(".w-V .noUi-handle").first
            handle.focus()
            for key in ("ArrowLeft", "ArrowRight", "ArrowLeft"):
                before = status_text(b, "force")
                t = time.monotonic()
                b.keyboard.press(key)
                wait_status_change(b, "force", before)
                renders.append(time.monotonic() - t)
            a.locator(".url-message").get_by_text(f"law={law!r}").wait_for(timeout=30_000)
            note = url_message(a)
            assert "URL value ignored" in note, note
            wait_url(a, lambda q: "law" not in q)  # the message and the state: two updates
            text, msg, q = settled(a)  # the cubic, with the URL rewritten to it
            assert "law" not in q, q
        # typed in the law box
        a.locator(".w-law-kind button", has_text="expression").click()
        box = a.locator(".in-law input")
        box.fill(DOS_LAWS[1])
        box.press("Enter")
        before = status_text(b, "force")
        b.locator(".w-V .noUi-handle").first.focus()
        t = time.monotonic()
        b.keyboard.press("ArrowRight")
        wait_status_change(b, "force", before)
        renders.append(time.monotonic() - t)
        a.locator(".ranges").get_by_text("invalid law").wait_for(timeout=30_000)
        ranges = " ".join(a.locator(".ranges p").all_inner_texts())
        assert DOS_LAWS[1] in ranges, ranges
        probe.stop()
        growth = max(probe.rss) - rss0
        print(
            f"[browser] DoS laws: B renders {[round(x, 3) for x in renders]} s, /liveness max "
            f"{max(probe.times):.3f} s over {len(probe.times)} polls, RSS +{growth:.0f} MB"
        )
        assert growth <= 100, growth
        # the target (1 s) with FPU_STRICT_TIMING=1 under `flock /tmp/bench.lock`; else a bound
        # a busy CI machine keeps (before: the server froze for minutes)
        limit = 1.0 if os.environ.get("FPU_STRICT_TIMING") == "1" else 5.0
        assert max(renders) <= limit and max(probe.times) <= limit, (renders, max(probe.times))
    finally:
        a.close()
        b.close()
    assert not app_tracebacks()


# ----------------------------------------------------------------------------- ten sessions
#: the targets on 2 cores (/liveness max was 17.6-21.7 s when the server computed); asserted as
#: such only with FPU_STRICT_TIMING=1 (run under `flock /tmp/bench.lock`), else the looser CI
#: bound below
LIVENESS_MAX_S, LIVENESS_P95_S = 2.0, 0.5
LOOSE_MAX_S, LOOSE_P95_S = 8.0, 2.0


@pytest.mark.slow
def test_ten_sessions_stay_responsive_and_consistent(browser, server):
    """Ten sessions open at once and move their V slider for a bounded time while /liveness is
    polled (an eleventh is closed in the middle of a Floquet job); then every page settles to
    exact box = URL = plot (its status stamp and its Rayleigh line), the server log has no
    traceback (none at the pages' close either), and no request leaves the server."""
    probe = LivenessProbe(server)
    probe.start()
    Vs = [f"{4.4 + 0.09 * k:.2f}" for k in range(10)]
    pages = [browser.new_page() for _ in Vs]
    foreign = [record_foreign_requests(pg, server) for pg in pages]
    for pg in pages:
        pg.set_default_timeout(TIMEOUT_MS)
    try:
        for pg, V in zip(pages, Vs):  # all ten page builds at once
            pg.goto(f"{server}/main?tab=force&V={V}&{FAST}", wait_until="commit")
        for pg in pages:
            settled(pg, 180)
        # one more session starts a long Floquet job and is closed mid-job: its job is stopped
        # and the server log stays clean (no traceback, no leaked semaphore at shutdown)
        heavy = browser.new_page()
        heavy.goto(f"{server}/main?tab=floquet&N=1400&V=5.15&tol=1e-10")
        heavy.locator(".scene-floquet .scene-cancel button").wait_for(
            state="visible", timeout=120_000
        )
        heavy.close()
        rng = random.Random(5)
        t_end = time.monotonic() + 45
        moves = 0
        while time.monotonic() < t_end:
            pg = rng.choice(pages)
            pg.locator(".w-V .noUi-handle").first.focus()
            pg.keyboard.press(rng.choice(["ArrowLeft", "ArrowRight"]))
            moves += 1
            pg.wait_for_timeout(150)
        for k, pg in enumerate(pages):
            pg.wait_for_timeout(300)
            text, msg, q = settled(pg, 120)
            box = pg.locator(".in-V input").input_value()
            assert float(box) == float(q["V"]), (k, box, q["V"], text)
            assert widget_value(pg, "w-V") == float(q["V"]), (k, q["V"])  # and the slider
            check_consistent(pg, text, msg, q)
    finally:
        for pg in pages:
            pg.close()
    time.sleep(2)  # the server handles the ten closes
    probe.stop()
    times = sorted(probe.times)
    p95 = times[int(0.95 * (len(times) - 1))]
    print(
        f"[browser] ten sessions, {moves} slider moves: /liveness max {times[-1]:.3f} s, p95 "
        f"{p95:.3f} s, median {statistics.median(times):.3f} s over {len(times)} polls; "
        f"load average {os.getloadavg()}"
    )
    assert not any(foreign), foreign
    assert not app_tracebacks(), app_tracebacks()[-1][-2000:]
    strict = os.environ.get("FPU_STRICT_TIMING") == "1"
    lim_max, lim_p95 = (LIVENESS_MAX_S, LIVENESS_P95_S) if strict else (LOOSE_MAX_S, LOOSE_P95_S)
    assert times[-1] <= lim_max and p95 <= lim_p95, (times[-1], p95, strict)


def test_paper_tab_opens_three_figures(page):
    """The Paper tab: a click on a figure sets the state (law, mode, w₊, V, N, tab), the URL
    carries it and the scene that shows the figure renders exactly that state."""
    page.goto(f"{page.server}/main?a=-2&b=12&w_plus=0.5&V=4&{FAST}&mode=solitary&tab=paper")
    cases = [
        # label, tab, mode, V (the paper's parameters), what the scene must show
        ("pplane", "phase", "solitary", 2 * 65**0.5 / 3 - 0.001, "Time:"),
        ("superkink", "force", "superkink", 2 * 65**0.5 / 3, "Time:"),
        ("stabSW", "simulation", "solitary", 5.2174919476, "Run simulation"),
    ]
    # each figure's comparison row is filled (from fpu paper's cache, or the command to run)
    page.locator(".paper-cmp-pplane").get_by_text("fpu paper", exact=False).or_(
        page.locator(".paper-cmp-pplane").get_by_text("agree", exact=False)
    ).first.wait_for()
    page.screenshot(path="/tmp/fpu-paper-tab.png", full_page=False)
    for label, tab, mode, V, shows in cases:
        if query(page).get("tab") != "paper":
            open_tab(page, "Paper")
            wait_url(page, lambda q: q.get("tab") == "paper")
        page.locator(f".paper-open-{label} button").click()
        # the state changes in steps (tab, then law and mode, then w₊, N, V): wait for the last
        q = wait_url(
            page,
            lambda q, t=tab, m=mode, v=V: (
                q.get("tab") == t
                and q.get("mode") == m
                and q.get("a") == "-1.0"
                and abs(float(q.get("V", "nan")) - v) < 1e-9
            ),
        )
        assert q.get("tab") == tab and q.get("mode") == mode, (label, q)
        assert (float(q["a"]), float(q["b"]), int(q["N"])) == (-1.0, 10.0, 500), q
        assert abs(float(q["V"]) - V) < 1e-9, (label, q["V"])
        if shows == "Time:":
            text, msg, q = settled(page)
            assert stamp(q) in text and not msg, (label, text, msg)
        else:
            page.locator(f".scene-{tab} .scene-message").get_by_text(shows).wait_for()
        assert not app_tracebacks()


def test_an_invalid_url_value_is_reported_and_the_address_bar_rewritten(page):
    """?tab=nonsense: the message names the value, the state keeps its default tab, and the
    address bar shows the state's URL (a copied link reproduces what is on screen)."""
    page.goto(f"{page.server}/main?tab=nonsense&{FAST}")
    page.locator(".url-message").get_by_text("nonsense").wait_for()
    q = wait_url(page, lambda q: q.get("tab") == "force")
    assert q.get("tab") == "force", page.url
    assert "nonsense" not in page.url


# ----------------------------------------------------------------------- Floquet figures' layout
# Records, per canvas, the box (canvas px) of every text drawn since the canvas was last cleared
# whole (BokehJS clears a plot's canvas before each repaint): the tick labels as drawn.
CANVAS_TEXT_HOOK = """(() => {
  const logs = new WeakMap();
  window.__canvasTexts = (canvas) => logs.get(canvas) || [];
  const P = CanvasRenderingContext2D.prototype, fill = P.fillText, clear = P.clearRect;
  P.clearRect = function (x, y, w, h) {
    if (x <= 0 && y <= 0 && x + w >= this.canvas.width && y + h >= this.canvas.height) {
      logs.set(this.canvas, []);
    }
    return clear.apply(this, arguments);
  };
  P.fillText = function (text, x, y) {
    const m = this.measureText(text), t = this.getTransform();
    const pts = [[-m.actualBoundingBoxLeft, -m.actualBoundingBoxAscent],
                 [m.actualBoundingBoxRight, -m.actualBoundingBoxAscent],
                 [-m.actualBoundingBoxLeft, m.actualBoundingBoxDescent],
                 [m.actualBoundingBoxRight, m.actualBoundingBoxDescent]]
      .map(([u, v]) => [t.a * (x + u) + t.c * (y + v) + t.e, t.b * (x + u) + t.d * (y + v) + t.f]);
    const xs = pts.map(p => p[0]), ys = pts.map(p => p[1]);
    if (!logs.has(this.canvas)) logs.set(this.canvas, []);
    logs.get(this.canvas).push({text: String(text),
      box: [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)]});
    return fill.apply(this, arguments);
  };
})();"""

# The Floquet figures as BokehJS laid them out: per panel letter its element's page box, its
# frame (canvas px), the pixels per unit of x and of y, and the numeric x tick labels drawn
# under the frame (their boxes in CSS px).
JS_FLOQUET_FIGURES = """() => {
  const out = {}, seen = new Set();
  const walk = (v) => {
    if (!v || seen.has(v)) return;
    seen.add(v);
    const t = v.model && v.model.title && v.model.title.text;
    const letter = typeof t === "string" && /^\\(([a-d])\\)/.exec(t);
    if (letter && v.model.visible) {
      const f = v.frame.bbox, r = v.el.getBoundingClientRect(), dpr = window.devicePixelRatio;
      const texts = window.__canvasTexts(v.canvas_view.primary.canvas)
        .map(s => ({text: s.text, box: s.box.map(z => z / dpr)}));
      out[letter[1]] = {
        el: [r.left, r.top, r.right, r.bottom], frame: [f.x0, f.y0, f.x1, f.y1],
        px_per_x: Math.abs(v.frame.x_scale.compute(1) - v.frame.x_scale.compute(0)),
        px_per_y: Math.abs(v.frame.y_scale.compute(1) - v.frame.y_scale.compute(0)),
        xlabels: texts.filter(s => s.box[1] >= f.y1 - 1
          && /^[−-]?[0-9.]+(e[−+-]?[0-9]+)?$/.test(s.text)).sort((p, q) => p.box[0] - q.box[0]),
      };
    }
    for (const c of v.children()) walk(c);
  };
  for (const v of Bokeh.index) walk(v);
  return out;
}"""

#: window widths: wide, the test default (both fit side by side in its 800 px main column), and
#: two where (b) wraps below (a).  (Below ~1100 px, or 760 px with the sidebar closed, one
#: square figure is wider than the main column.)
WINDOW_WIDTHS = (1920, 1500, 1280, 1150)


def floquet_figures_at(page, width: int) -> dict:
    """JS_FLOQUET_FIGURES once the layout at this window width has settled (two equal reads)."""
    page.set_viewport_size({"width": width, "height": 1000})
    t_end = time.monotonic() + 20
    last = None
    while time.monotonic() < t_end:
        page.wait_for_timeout(300)
        now = page.evaluate(JS_FLOQUET_FIGURES)
        if now == last and now.get("a", {}).get("xlabels"):
            return now
        last = now
    raise AssertionError(f"Floquet figures did not settle at width {width}: {last}")


def open_floquet(page, query: str) -> None:
    page.add_init_script(CANVAS_TEXT_HOOK)
    page.goto(f"{page.server}/main?tab=floquet&{query}")
    settled(page, 240)


def test_floquet_unit_circle_is_a_circle_at_every_window_width(page):
    """Panels (a) and (b) draw the complex plane with as many pixels per unit of Re μ as of
    Im μ (the unit circle is round), their frames square, at every width; they never run into
    the status column (narrower than both, (b) goes below (a))."""
    open_floquet(page, f"V=4.5&{FAST}")
    for width in WINDOW_WIDTHS:
        figs = floquet_figures_at(page, width)
        for p in "ab":
            f = figs[p]
            x0, y0, x1, y1 = f["frame"]
            # equal x and y spans (set by the scene) in a square frame: within 0.5 %
            assert abs(f["px_per_x"] / f["px_per_y"] - 1) < 5e-3, (width, p, f)
            assert abs((x1 - x0) - (y1 - y0)) <= 1, (width, p, f["frame"])
            assert f["el"][2] <= page.evaluate("() => innerWidth"), (width, p, f["el"])
        a, b = figs["a"]["el"], figs["b"]["el"]
        assert b[0] >= a[2] - 1 or b[1] >= a[3] - 1, (width, a, b)  # beside or below
        side = status(page, "floquet").bounding_box()
        assert max(a[2], b[2]) <= side["x"] + 1, (width, a, b, side)
    assert not app_tracebacks()


def test_floquet_tick_labels_never_run_together(page):
    """The x tick labels of (a) and (b) as drawn on the canvas: at least two each, every one
    clear of its neighbour by more than a digit's width (8 px at the 11 px tick font).  At
    w₊ = 1, V = 4.5 the zoom (b) spans ~6e-6: labels of 7–8 digits ("0.969312")."""
    open_floquet(page, f"V=4.5&{FAST}")
    for width in WINDOW_WIDTHS:
        figs = floquet_figures_at(page, width)
        for p in "ab":
            labels = figs[p]["xlabels"]
            assert len(labels) >= 2, (width, p, labels)
            for left, right in zip(labels, labels[1:]):
                gap = right["box"][0] - left["box"][2]
                assert gap >= 8, (width, p, left["text"], right["text"], gap)
    assert not app_tracebacks()


def test_floquet_panels_are_in_the_order_a_b_c_d(page):
    """After a sweep all four panels show, top to bottom (a), (b), (c), (d) ((b) beside (a)
    or below it)."""
    open_floquet(page, FAST)
    run_floquet_sweep(page, 3)
    for width in (1500, 1150):
        figs = floquet_figures_at(page, width)
        assert set(figs) == set("abcd"), (width, sorted(figs))
        a, b, c, d = (figs[p]["el"] for p in "abcd")
        assert b[0] >= a[2] - 1 or b[1] >= a[3] - 1, (width, a, b)
        assert max(a[3], b[3]) <= c[1] + 1 and c[3] <= d[1] + 1, (width, a, b, c, d)
    assert not app_tracebacks()


# ---------------------------------------------------------------- marks under the sliders
def _track_and_mark(page, slider: str, mark: str) -> tuple[float, float, float, float, float]:
    """(track left, track width, slider start, slider end, the mark's x), from the page."""
    base = page.locator(f".w-{slider} .noUi-base").first.bounding_box()
    lo, hi = page.evaluate(
        """(cls) => { for (const d of Bokeh.documents) { for (const m of d.all_models) {
        if (m.css_classes && m.css_classes.includes(cls) && m.start !== undefined) {
        return [m.start, m.end]; } } } return null; }""",
        f"w-{slider}",
    )  # the slider model's range (the handle's aria values are rounded to 0.1)
    at = page.locator(f".{mark} .mark-at").first.bounding_box()
    return base["x"], base["width"], lo, hi, at["x"]


def _cubic_v_sk(w_plus: float, a: float = -1.0, b: float = 10.0) -> float:
    """The cubic's V_SK in closed form: w₊ + w₋ = 2w*, V² = (f(w₋) − f(w₊)) / (w₋ − w₊)."""
    f = lambda w: a * w**3 + b * w**2 + w  # noqa: E731
    w_minus = 2 * (-b / (3 * a)) - w_plus
    return ((f(w_minus) - f(w_plus)) / (w_minus - w_plus)) ** 0.5


def test_v_sk_and_w_star_are_marked_under_their_sliders_and_a_typed_V_stays_exact(page):
    """The V_SK mark sits at V_SK's place along the V slider's track (± 3 px) and moves when
    w₊ does; w* sits on the w₊ track; a V typed meanwhile stays exactly what was typed (the
    mark is its own pane: the slider never re-renders for it, so nothing echoes back)."""
    open_app(page, FAST + "&w_plus=1&V=5")
    for slider, mark, value in (("V", "mark-V", _cubic_v_sk(1.0)), ("wplus", "mark-wplus", 10 / 3)):
        x0, width, lo, hi, x = _track_and_mark(page, slider, mark)
        assert x == pytest.approx(x0 + width * (value - lo) / (hi - lo), abs=3.0), slider
    box = page.locator(".in-wplus input")
    box.fill("2")
    box.press("Enter")
    wait_url(page, lambda q: float(q.get("w_plus", "nan")) == 2.0)
    settled(page)
    t_end = time.monotonic() + 20
    want = _cubic_v_sk(2.0)
    while time.monotonic() < t_end:
        x0, width, lo, hi, x = _track_and_mark(page, "V", "mark-V")
        if abs(x - (x0 + width * (want - lo) / (hi - lo))) <= 3.0:
            break
        page.wait_for_timeout(100)
    assert x == pytest.approx(x0 + width * (want - lo) / (hi - lo), abs=3.0)
    assert f"V_SK = {want:.6g}" in page.locator(".mark-V .mark-label").first.inner_text()
    typed = "5.51234567"  # in (c₊, V_SK) = (5.385, 5.705) at w₊ = 2, off the slider's grid
    inp = page.locator(".in-V input")
    inp.fill(typed)
    inp.press("Enter")
    wait_url(page, lambda q: q.get("V") == typed)
    settled(page)
    page.wait_for_timeout(1500)  # an echo, if any, would arrive by now
    q = query(page)
    assert q["V"] == typed and page.locator(".in-V input").input_value() == typed, q
    assert not app_tracebacks()


# ----------------------------------------------------------- Copy as Python and value boxes
def test_copy_as_python_confirms_or_opens_the_code_where_there_is_no_clipboard(page):
    """Plain http on another host has no navigator.clipboard: "Copy as Python" then uses the
    legacy copy command and says "Copied ✓", or opens the code card and says to select the
    code — never nothing.  The code box is monospace and does not wrap; the exact-value boxes
    show 17 significant digits uncut."""
    page.add_init_script("Object.defineProperty(navigator, 'clipboard', {value: undefined});")
    open_app(page, FAST)
    btn = page.locator(".scene-force .scene-copy button")
    btn.click()
    t_end = time.monotonic() + 5
    label = btn.inner_text()
    while label == "Copy as Python" and time.monotonic() < t_end:
        page.wait_for_timeout(50)
        label = btn.inner_text()
    assert label in ("Copied ✓", "Select the code below"), label
    code = page.locator(".scene-force .scene-code textarea")
    if label.startswith("Select"):
        code.wait_for(state="visible", timeout=5000)
    style = code.evaluate(
        "(el) => { const s = getComputedStyle(el); return [s.fontFamily, s.whiteSpace]; }"
    )
    assert "monospace" in style[0] and style[1] == "pre", style
    for box in (".in-V input", ".in-wplus input"):
        cut = page.locator(box).evaluate(
            "(el) => { el.value = '-5.3748384988656987e-10'; "
            "return el.scrollWidth > el.clientWidth; }"
        )
        assert not cut, box


def test_hold_curves_and_export_the_scene(page):
    """Wave profiles: "Hold curve" keeps the profile at V = 5 while the V slider moves on; the
    held curve is drawn (the browser's copy of its source), the downloads hold the scene as
    drawn (an SVG with the held curve's path, a PNG, a notebook with the held call), and "Clear
    held" removes it."""
    page.goto(f"{page.server}/main?tab=profiles&{FAST}&V=5.0&mode=solitary")
    wait_rendered(page, "profiles", 180.0)
    before = status_text(page, "profiles")
    page.locator(".profiles-hold button").click()
    page.wait_for_function(
        "() => { for (const d of Bokeh.documents) for (const m of d.all_models)"
        " if (m.name === 'profile-held-0' && m.data && m.data.x.length > 0) return true;"
        " return false; }"
    )
    held = source(page, "profile-held-0")
    handle = page.locator(".w-V .noUi-handle").first
    handle.focus()
    page.keyboard.press("ArrowLeft")
    q = wait_url(page, lambda q: q.get("V") != "5.0")
    t_end = time.monotonic() + 120
    while stamp(q) not in (after := status_text(page, "profiles")) or "Time:" not in after:
        assert time.monotonic() < t_end, after
        page.wait_for_timeout(100)
    assert "V = 5," not in after and after != before  # the current wave moved on ...
    assert source(page, "profile-held-0") == held  # ... the held one stayed
    assert len(held["x"]) == 1601
    page.screenshot(path="/tmp/fpu-profiles-held.png", full_page=True)
    with page.expect_download() as dl:
        page.locator(".scene-profiles .scene-export-svg button").click()
    assert dl.value.suggested_filename == "profiles.svg"
    svg = Path(dl.value.path()).read_text()
    assert svg.lstrip().startswith("<?xml") and 'id="profile-held-0"' in svg
    with page.expect_download() as dl:
        page.locator(".scene-profiles .scene-export-png button").click()
    assert Path(dl.value.path()).read_bytes()[:4] == b"\x89PNG"
    with page.expect_download() as dl:
        page.locator(".scene-profiles .scene-export-notebook button").click()
    assert dl.value.suggested_filename == "profiles.ipynb"
    nb = Path(dl.value.path()).read_text()
    assert "held.append((qc.solitary(law, 1.0, 5.0)" in nb and '"nbformat": 4' in nb
    page.locator(".profiles-clear-held button").click()
    page.wait_for_function(
        "() => { for (const d of Bokeh.documents) for (const m of d.all_models)"
        " if (m.name === 'profile-held-0' && m.data) return m.data.x.length === 0;"
        " return false; }"
    )
    assert not app_tracebacks()


JS_DATA_TO_PAGE = """([title, x, y]) => {
  let out = null;
  const walk = (v) => {
    const m = v.model;
    if (out === null && m.title && m.title.text && m.title.text.startsWith(title) && v.frame) {
      const r = v.canvas_view.el.getBoundingClientRect();
      out = [r.left + v.frame.x_scale.compute(x), r.top + v.frame.y_scale.compute(y)];
    }
    for (const c of v.children()) walk(c);
  };
  for (const v of Bokeh.index) walk(v);
  return out;
}"""


def test_branch_view_click_opens_the_wave(page):
    """Diagrams (b): "Classify stability" draws the family's waves coloured by their Floquet
    class; a click on one makes it the current wave (the URL's V)."""
    page.goto(f"{page.server}/main?tab=diagram&N=96&tol=1e-08&V=5.0&mode=solitary&w_plus=1.0")
    wait_rendered(page, "diagram", 180.0)
    field = page.locator(".scene-diagram .bk-input-group", has_text="discrete points").locator(
        "input"
    )
    field.fill("2")
    field.press("Enter")
    inputs_reach_the_server(page)
    page.locator(".diagram-classify button").click()
    page.locator(".scene-diagram .scene-status").get_by_text("branch view").wait_for(
        timeout=400_000
    )
    points = {}
    for c in ("stable", "finite_size", "unstable", "undetermined"):
        s = source(page, f"diagram-branch-{c}")
        points |= {x: y for x, y in zip(s["x"], s["y"])}
    assert len(points) == 4, points
    V, E = sorted(points.items())[0]
    page.screenshot(path="/tmp/fpu-diagram-branch.png", full_page=True)
    # click the point: data → screen through the figure's frame (BokehJS's own mapping)
    box = page.evaluate(JS_DATA_TO_PAGE, ["(b) renormalized", V, E])
    assert box is not None
    page.mouse.click(box[0], box[1])
    q = wait_url(page, lambda q: abs(float(q.get("V", "nan")) - V) < 1e-9)
    assert float(q["V"]) == pytest.approx(V, abs=1e-9)
    assert not app_tracebacks()


def test_tracked_sites_on_the_simulation_scene(page):
    """Simulation, Riemann data with a tracked site (Fig. Riemann1 (c)): panel (c) shows the
    site's history and the wave computed at the measured V and w_B."""
    page.goto(f"{page.server}/main?tab=simulation&N=300&tol=1e-08")
    page.locator(".scene-simulation .scene-message").get_by_text("Run simulation").wait_for()
    field = page.locator(".scene-simulation .bk-input-group", has_text="tracked sites")
    field.locator("input").fill("280")
    field.locator("input").press("Enter")
    text = run_riemann(page, t_end="20", L="400")
    assert "wave at V = 4.6" in text, text
    site, tw = source(page, "sim-probe-0"), source(page, "sim-probe-wave-0")
    assert len(site["x"]) > 100 and len(tw["x"]) > 10
    assert abs(max(site["y"]) - max(tw["y"])) < 0.1  # the crests meet (4.5 high)
    page.screenshot(path="/tmp/fpu-simulation-tracked.png", full_page=True)
    assert not app_tracebacks()
