"""The browser-test harness (imported by tests/browser/conftest.py and the browser tests).

The Chromium binary and flags, the serve command (the Makefile's: fpu serve), the server log's
traceback check, and the page helpers: open the app, wait (bounded, never sleeps) for a scene's
render or a URL change, read a scene's status, message and data sources, type into widgets.
Run the browser tests: `.venv/bin/python -m pytest tests/browser -q -s`.
"""

from __future__ import annotations

import socket
import sys
import threading
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

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
# The Makefile's `serve` target and the Dockerfile's CMD (checked in test_harness.py), run with
# this interpreter: fpu serve = panel serve app/main.py … --setup app/warm.py --warm
SERVE_COMMAND = [sys.executable, "-m", "fpucore", "serve"]
TIMEOUT_MS = 60_000
# a small chain keeps the discrete scenes quick in CI; everything else at the defaults
FAST = "N=120&tol=1e-08"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


#: the running server's log file (read by the tests that check it after every step)
SERVER_LOG: dict[str, str] = {}


_REPORTED = {"count": 0}


def app_tracebacks() -> list[str]:
    """Tracebacks of the app in the server log not yet reported by an earlier call (client
    disconnects excluded): each fails the first test that looks after it was logged, not every
    later one (the server fixture still fails the session on any)."""
    text = Path(SERVER_LOG["path"]).read_text(errors="replace")
    found = [tb for tb in tracebacks(text) if not client_disconnect(tb)]
    new = found[_REPORTED["count"] :]
    _REPORTED["count"] = len(found)
    return new


# A page closed or navigated away while the server still writes to its websocket makes tornado
# log one of these: the client went away, nothing failed in the app.
DISCONNECTS = ("tornado.websocket.WebSocketClosedError", "tornado.iostream.StreamClosedError")


def tracebacks(log_text: str) -> list[str]:
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


def client_disconnect(tb: str) -> bool:
    # (Bokeh's "assert self._session is not None" at a browser's close is no longer excused:
    # app/server_guards.py handles it)
    return tb.strip().splitlines()[-1].startswith(DISCONNECTS)


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


# ------------------------------------------------------------ scene robustness in the page
TAB_TITLES = {key: title for title, key in SCENES} | {"simulation": "Simulation"}

JS_SOURCE = """(name) => { for (const d of Bokeh.documents) { for (const m of d.all_models) {
  if (m.name === name && m.data) { return {x: Array.from(m.data.x), y: Array.from(m.data.y)}; }
} } return null; }"""


JS_TITLES = """() => {
  const ctx = document.createElement("canvas").getContext("2d"); const out = [];
  for (const d of Bokeh.documents) { for (const m of d.all_models) {
    if (!m.title || typeof m.title.text !== "string" || !m.title.text || !m.visible) continue;
    const t = m.title, w = m.outer_width ?? m.inner_width ?? m.width;
    if (!w) continue;
    ctx.font = `${t.text_font_style} ${t.text_font_size} ${t.text_font}`;
    const widest = Math.max(...t.text.split("\\n").map((s) => ctx.measureText(s).width));
    out.push({text: t.text, text_px: widest, plot_px: w});
  } } return out; }"""


def cut_titles(page) -> list[dict]:
    """The visible figures whose title is wider than the figure (BokehJS draws a title on the
    canvas and cuts what does not fit): each title's widest line measured with its own font."""
    return [t for t in page.evaluate(JS_TITLES) if t["text_px"] > t["plot_px"]]


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


def check_consistent(page, text: str, msg: str, q: dict, wait_s: float = 30.0) -> None:
    """What the plot's data sources hold matches the status text — within ``wait_s``: status
    and data reach the browser in separate messages (the data patch of a render is queued on
    the server's event loop before its status text, and the browser applies patches in order),
    so the data may trail by a few ms on an idle machine — and by seconds when both the server
    and Chromium share 2 busy cores (load 15–20 while the suite runs beside other jobs).  The
    bound is a patience like `settled`'s for the status, not a fixed 5 s: a point that stays
    behind its URL still fails, one that is merely late does not (the delay is printed)."""
    t0 = time.monotonic()
    while True:
        try:
            check_consistent_now(page, text, msg, q)
        except AssertionError:
            if time.monotonic() > t0 + wait_s:
                raise
            page.wait_for_timeout(100)
            continue
        late = time.monotonic() - t0
        if late > 1.0:
            print(f"[browser] {q.get('tab')}: plot data trailed the status text by {late:.1f} s")
        return


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


def liveness_s(server: str) -> float:
    t = time.monotonic()
    with urllib.request.urlopen(server + "/liveness", timeout=30) as r:
        assert r.status == 200
    return time.monotonic() - t


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
            self.times.append(liveness_s(self.server))
            self.rss.append(server_rss_mb())
            self.halt.wait(0.1)

    def stop(self) -> LivenessProbe:
        self.halt.set()
        self.join(30)
        return self


def open_law_box(page):
    """Choose "expression" and return the law box once the server has filled it with the
    current law.  Typing before that races the server's fill: on a loaded machine the fill
    arrived between Playwright's clear and its insert, and the two texts ran together."""
    page.locator(".w-law-kind button", has_text="expression").click()
    box = page.locator(".in-law input")
    box.wait_for()
    t_end = time.monotonic() + TIMEOUT_MS / 1000
    while not box.input_value() and time.monotonic() < t_end:
        page.wait_for_timeout(50)
    assert box.input_value(), "the law box was never filled with the current law"
    return box


def law_box_refusal(page, previous: str = "", timeout: float = 60.0) -> str:
    """After a law typed into the law box: wait (bounded) for the editor's refusal (the previous
    law stays in the state); its text, read inside the Alert's shadow root ("" if none came).
    ``previous``: the refusal shown before the text was typed, waited out for up to 15 s (two
    texts may be refused with the same words)."""
    t0 = time.monotonic()
    text = ""
    while time.monotonic() < t0 + timeout:
        text = " ".join(" ".join(page.locator(".law-refusal p").all_inner_texts()).split())
        if "law refused" in text and (text != previous or time.monotonic() > t0 + 15):
            return text
        page.wait_for_timeout(100)
    return text
