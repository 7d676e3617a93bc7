"""Every scene in the page: renders, follows its sliders and clicks, reports bad settings,
downloads, slider marks, Copy as Python.
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest
from browser_harness import (
    FAST,
    SCENES,
    TIMEOUT_MS,
    app_tracebacks,
    inputs_reach_the_server,
    open_app,
    open_tab,
    query,
    run_riemann,
    settled,
    status_text,
    wait_rendered,
    wait_status_change,
    wait_url,
)

pytestmark = pytest.mark.browser


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
