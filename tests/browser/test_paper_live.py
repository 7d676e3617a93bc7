"""The paper, live: the Paper tab, held curves, the scene export, branch view, tracked sites."""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest
from browser_harness import (
    FAST,
    app_tracebacks,
    cut_titles,
    inputs_reach_the_server,
    open_tab,
    query,
    run_riemann,
    settled,
    source,
    stamp,
    status,
    status_text,
    wait_rendered,
    wait_url,
)

pytestmark = pytest.mark.browser


def wait_source(page, name: str, pred, timeout_ms: float = 180_000) -> dict:
    """The browser's copy of source ``name`` once ``pred`` holds for it (bounded)."""
    t_end = time.monotonic() + timeout_ms / 1000
    while True:
        s = source(page, name)
        if s is not None and pred(s):
            return s
        assert time.monotonic() < t_end, (name, None if s is None else len(s["x"]))
        page.wait_for_timeout(100)


def sim_input(page, label: str) -> str:
    field = page.locator(".scene-simulation .bk-input-group", has_text=label).locator("input")
    return field.first.input_value()


def top_in_view(page, scene: str) -> bool:
    """Whether the scene's status (the top of its right column) is inside the window: the
    Paper list is long, and the button a person clicks sits far down it."""
    box = status(page, scene).bounding_box()
    return box is not None and 0 <= box["y"] < page.viewport_size["height"]


def test_paper_tab_opens_three_figures(page):
    """The Paper tab: a click on a figure sets the state (law, mode, w₊, V, N, tab, held
    curves, the Simulation scene's initial data), the URL carries it (``fig``, ``hold``) and the
    scene shows exactly that: the phase plane of Fig. pplane, the family of superkinks of Fig.
    TWcubic (current and five held, with their discrete points) and the Riemann run of Fig.
    Riemann1 with its tracked sites (its widgets set to the caption's values and the run
    started by the click)."""
    page.goto(f"{page.server}/main?a=-2&b=12&w_plus=0.5&V=4&{FAST}&mode=solitary&tab=paper")
    v_sk = 2 * 65**0.5 / 3
    cases = [
        # label, tab, mode, V (the paper's parameters)
        ("pplane", "phase", "solitary", v_sk - 0.001),
        ("TWcubic", "profiles", "superkink", 5.2),
        ("Riemann1", "simulation", "superkink", 5.720916787446649),
    ]
    # each figure's comparison row is filled (from fpu paper's cache, or the command to run)
    page.locator(".paper-cmp-pplane").get_by_text("fpu paper", exact=False).or_(
        page.locator(".paper-cmp-pplane").get_by_text("agree", exact=False)
    ).first.wait_for()
    page.screenshot(path="/tmp/fpu-paper-tab.png", full_page=False)
    for label, tab, mode, V in cases:
        if query(page).get("tab") != "paper":
            open_tab(page, "Paper")
            wait_url(page, lambda q: q.get("tab") == "paper")
        page.locator(f".paper-open-{label} button").click()
        # the state changes in steps (tab, then law and mode, then w₊, N, V, held, fig)
        q = wait_url(page, lambda q, lab=label: q.get("fig") == lab, timeout=60.0)
        assert q.get("tab") == tab and q.get("mode") == mode, (label, q)
        assert (float(q["a"]), float(q["b"]), int(q["N"])) == (-1.0, 10.0, 500), q
        assert abs(float(q["V"]) - V) < 1e-9, (label, q["V"])
        # the sidebar's exact V box shows the state's V
        box = page.locator(".in-V input").first
        assert abs(float(box.input_value()) - V) < 1e-9, box.input_value()
        if label == "TWcubic":
            # five held superkinks (sk@w₊) drawn beside the current one, with their points
            held = q["hold"].split(",")
            assert len(held) == 5 and all(h.startswith("sk@") for h in held), q["hold"]
            text = wait_rendered(page, "profiles", 300.0)
            assert stamp(q) in text, text
            for k in range(5):
                s = wait_source(page, f"profile-held-{k}", lambda s: len(s["x"]) == 1601)
                w_plus = float(held[k][3:])
                assert abs(min(s["y"]) - w_plus) < 1e-3  # the plateau ahead: w₊ of the entry
            assert len(source(page, "profile-held-5")["x"]) == 0
            page.screenshot(path="/tmp/fpu-paper-TWcubic.png", full_page=True)
            assert top_in_view(page, "profiles")  # the scene opens at its top, not scrolled
        elif label == "Riemann1":
            # the caption's run: Riemann data w^l = 4.6, w^r = 0, L = 3600, t = 300, sites
            # 100, 200, 3000 — in the widgets, and run at once (measured ~1-3 s)
            active = page.locator(".scene-simulation .bk-btn-group button.bk-active")
            assert active.inner_text().strip() == "Riemann"
            assert int(sim_input(page, "L (sites)")) == 3600
            assert float(sim_input(page, "t_end")) == 300.0
            assert float(sim_input(page, "w^l")) == 4.6 and float(sim_input(page, "w^r")) == 0
            assert sim_input(page, "tracked sites") == "100, 200, 3000"
            text = wait_rendered(page, "simulation", 300.0)
            assert "simulation of Riemann data to t = 300" in text, text
            pairs = re.findall(r"(-?\d+\.\d+) ± (\S+?),? ", text)  # "V ± error" of each wave
            tracked = [(float(v), float(e)) for v, e in pairs]
            for printed in (-5.7209, -5.6159, 4.6404):  # the caption's V, within the error bar
                v, e = min(tracked, key=lambda t, p=printed: abs(t[0] - p))
                assert abs(v - printed) <= e + 5e-5, (printed, tracked, text)
            for k in range(3):  # panels (c)-(e): the tracked site and the wave at its V, w_B
                wait_source(page, f"sim-probe-{k}", lambda s: len(s["x"]) > 50)
                wait_source(page, f"sim-probe-wave-{k}", lambda s: len(s["x"]) > 10)
            page.screenshot(path="/tmp/fpu-paper-Riemann1.png", full_page=True)
            # every title whole: (c)-(e) name the site, the wave, its V and w_B ± error
            assert not cut_titles(page), cut_titles(page)
            assert top_in_view(page, "simulation")  # the scene opens at its top, not scrolled
        else:
            assert "hold" not in q
            text, msg, q = settled(page)
            assert stamp(q) in text and not msg, (label, text, msg)
        assert not app_tracebacks()


def test_a_link_with_held_curves_reproduces_them_after_reload(page):
    """``hold=`` in the URL: the page draws the held profiles (the closed forms at those V)
    and the same held orbits on the phase plane; Hold adds the current wave to the URL, a
    reload draws all three again, and Clear held removes them from the URL."""
    page.goto(f"{page.server}/main?tab=profiles&{FAST}&V=5.0&mode=solitary&hold=4.6,5.37")
    wait_rendered(page, "profiles", 180.0)
    first = [wait_source(page, f"profile-held-{k}", lambda s: len(s["x"]) == 1601)
             for k in range(2)]  # fmt: skip
    # the QC solitary wave's crest w(0) = w₊ + amplitude, its tails at w₊ = 1
    assert all(abs(s["y"][0] - 1.0) < 1e-3 and abs(s["y"][-1] - 1.0) < 1e-3 for s in first)
    assert len(source(page, "profile-held-2")["x"]) == 0
    page.locator(".profiles-hold button").click()
    q = wait_url(page, lambda q: q.get("hold") == "4.6,5.37,5.0")
    assert q.get("hold") == "4.6,5.37,5.0", q
    wait_source(page, "profile-held-2", lambda s: len(s["x"]) == 1601)
    page.reload()
    wait_rendered(page, "profiles", 180.0)
    assert query(page).get("hold") == "4.6,5.37,5.0"
    again = [wait_source(page, f"profile-held-{k}", lambda s: len(s["x"]) == 1601)
             for k in range(3)]  # fmt: skip
    assert again[:2] == first  # the same curves, recomputed from the link
    open_tab(page, "Phase plane")
    wait_rendered(page, "phase", 120.0)
    for k in range(3):
        wait_source(page, f"phase-held-{k}", lambda s: len(s["x"]) > 10)
    page.screenshot(path="/tmp/fpu-phase-held-from-url.png", full_page=True)
    page.locator(".phase-clear-held button").click()
    q = wait_url(page, lambda q: "hold" not in q)
    assert "hold" not in q, q
    wait_source(page, "phase-held-0", lambda s: len(s["x"]) == 0)
    assert not app_tracebacks()


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


def classify_and_click_first(
    page, query: str, status: str, prefix: str, title: str
) -> tuple[float, dict]:
    """Open Diagrams at ``query`` with 2 discrete points per interval, press "Classify
    stability", wait (bounded) for the status line ``status``, read the 4 classified points of
    the sources ``prefix-<class>`` and click the one of smallest V on the panel titled
    ``title`` (data → screen through BokehJS's own frame mapping).  (that V, {V: y})."""
    page.goto(f"{page.server}/main?{query}")
    wait_rendered(page, "diagram", 180.0)
    field = page.locator(".scene-diagram .bk-input-group", has_text="discrete points").locator(
        "input"
    )
    field.fill("2")
    field.press("Enter")
    inputs_reach_the_server(page)
    page.locator(".diagram-classify button").click()
    page.locator(".scene-diagram .scene-status").get_by_text(status).wait_for(timeout=400_000)
    points = {}
    for c in ("stable", "finite_size", "unstable", "undetermined"):
        s = source(page, f"{prefix}-{c}")
        points |= {x: y for x, y in zip(s["x"], s["y"])}
    assert len(points) == 4, points
    page.screenshot(path=f"/tmp/fpu-{prefix}.png", full_page=True)
    V, y = sorted(points.items())[0]
    box = page.evaluate(JS_DATA_TO_PAGE, [title, V, y])
    assert box is not None
    page.mouse.click(box[0], box[1])
    return V, points


def test_branch_view_click_opens_the_wave(page):
    """Diagrams (b): "Classify stability" draws the family's waves coloured by their Floquet
    class; a click on one makes it the current wave (the URL's V)."""
    V, _ = classify_and_click_first(
        page,
        "tab=diagram&N=96&tol=1e-08&V=5.0&mode=solitary&w_plus=1.0",
        "branch view",
        "diagram-branch",
        "(b) renormalized",
    )
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


def test_superkink_branch_view_click_opens_the_superkink(page):
    """Diagrams (d), superkink mode: "Classify stability" sweeps the superkink family (Fig.
    floquet_SK) and draws each superkink by its Floquet class; a click on one sets V and w₊
    (V = V_SK(w₊)) in the URL."""
    w0 = 0.6327161199294542  # V_SK = 5.2
    V, points = classify_and_click_first(
        page,
        f"tab=diagram&N=64&tol=1e-08&V=5.2&mode=superkink&w_plus={w0}",
        "superkink branch view",
        "diagram-sk-branch",
        "(d) superkinks",
    )
    assert all(4.78423 < v < 5.85947 for v in points)  # the paper's superkink interval
    q = wait_url(page, lambda q: abs(float(q.get("V", "nan")) - V) < 1e-9)
    assert q["mode"] == "superkink"
    w = float(q["w_plus"])  # V = V_SK(w₊) (eq. cubic_cond2, a = −1, b = 10)
    assert (1 + 100 / 3 - (w - 10 / 3) ** 2) ** 0.5 == pytest.approx(V, abs=1e-9)
    assert not app_tracebacks()


def test_paper_tab_shows_every_thumbnail_embedded(page):
    """The Paper tab: one thumbnail per figure, its bytes in the page (a data: URL, no request
    to the server's files or to another host)."""
    page.goto(f"{page.server}/main?tab=paper")
    imgs = page.locator(".paper-thumb img")
    imgs.nth(16).wait_for(timeout=60_000)
    assert imgs.count() == 17
    srcs = [imgs.nth(k).get_attribute("src") for k in range(17)]
    assert all(s.startswith("data:image/png;base64,") for s in srcs)
    widths = {imgs.nth(k).evaluate("e => e.getBoundingClientRect().width") for k in range(17)}
    assert widths == {200}, widths
    assert not app_tracebacks()


#: what a simulation status says it shows → the run kind its parameter line must name
RUN_WORDS = {
    "Riemann data": "run: riemann",
    "(TW-seeded)": "run: seeded",
    "a Gaussian bump": "run: gaussian",
}


def test_figure_after_figure_never_shows_a_result_under_another_stamp(page):
    """Paper → Riemann1, stabSW, SWdyn, stabSK, Riemann1 without waiting between them more than
    the click takes: every status the page shows on the way — sampled every 50 ms — has a
    parameter line that names the run it describes (a Riemann run's velocities never stand
    under a seeded run's parameters), and the last one is the last figure's."""
    page.goto(f"{page.server}/main?tab=paper&{FAST}")
    seen: list[str] = []
    for label in ("Riemann1", "stabSW", "SWdyn", "stabSK", "Riemann1"):
        if query(page).get("tab") != "paper":
            open_tab(page, "Paper")
            wait_url(page, lambda q: q.get("tab") == "paper")
        page.locator(f".paper-open-{label} button").click()
        wait_url(page, lambda q, lab=label: q.get("fig") == lab, timeout=60.0)
        t_end = time.monotonic() + (300.0 if label == "Riemann1" else 5.0)
        while time.monotonic() < t_end:  # the next click comes while this one may still run
            seen.append(status_text(page, "simulation"))
            if label == "Riemann1" and "Riemann data" in seen[-1] and "Time:" in seen[-1]:
                break
            page.wait_for_timeout(50)
    text = wait_rendered(page, "simulation", 300.0)
    assert "Riemann data" in text and "run: riemann" in text, text
    checked = 0
    for s in seen:
        if "Parameters:" not in s:
            continue
        stamp_line = s.rsplit("Parameters:", 1)[1]
        for words, run in RUN_WORDS.items():
            if words in s.rsplit("Parameters:", 1)[0]:
                assert run in stamp_line, (words, s)
                checked += 1
    assert checked >= 3, seen[-5:]
    assert not app_tracebacks()
