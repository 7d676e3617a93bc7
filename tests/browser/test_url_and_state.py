"""The URL and the state: bad values named and the rest kept, the seeded 40-step state walk,
typed values and typed laws.
"""

from __future__ import annotations

import os
import random
import time

import pytest
from browser_harness import (
    FAST,
    SCENES,
    TAB_TITLES,
    TIMEOUT_MS,
    app_tracebacks,
    check_consistent,
    message_text,
    open_app,
    open_law_box,
    open_tab,
    press_on_slider,
    query,
    run_riemann,
    settled,
    stamp,
    type_into,
    url_message,
    wait_rendered,
    wait_status_change,
    wait_url,
    widget_value,
)

pytestmark = pytest.mark.browser
WALK_STEPS = 40  # of seed 13 (about 20 s on an idle machine, 10-15 min at load 20)
#: a sidebar slider's class suffix (.w-…) → its URL name
SLIDER_URL_NAMES = {"wplus": "w_plus"}
#: how long a user action may take to reach the URL (settled's patience for the render)
REACH_S = 90.0


def expect(page, pred, what: str, step: int) -> dict:
    """Wait (bounded) until the URL shows what the step's action set — the state the step must
    then find rendered; fail naming it if it never comes (a lost event, not a slow one)."""
    q = wait_url(page, pred, REACH_S)
    assert pred(q), f"step {step}: {what} did not reach the URL in {REACH_S} s: {q}"
    return q


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


# FPU_WALK_REPEAT=20: the same walk 20 times against one server (the load check of the walk)
@pytest.mark.parametrize("repeat", range(int(os.environ.get("FPU_WALK_REPEAT", "1"))))
def test_state_walk(page, repeat):
    """A seeded, bounded random walk through what users do — slider moves, mode switches, tab
    changes, invalid values typed or in the URL, and recoveries — checking after every step
    that the active scene renders the URL's state (none is dead), that the plot's data sources
    match the status text, and that the server log has no traceback."""
    rng = random.Random(13)
    base = "a=-1&b=10&w_plus=1&V=5&N=80&tol=1e-08&mode=solitary"
    page.goto(f"{page.server}/main?{base}&tab=force")
    settled(page, 120)
    # A fixed number of steps: the same seeded walk on every machine.  (It was bounded by 150 s
    # with at least 20 steps: at load 20 on the 2 cores only 7 steps fitted, and which states
    # were visited depended on the machine's speed.)  Each step waits (bounded) for its state.
    steps, kinds = 0, {}
    history: list[str] = []
    while steps < WALK_STEPS:
        r = rng.random()
        if r < 0.45:
            kind = "slider"
            name = rng.choice(["a", "b", "wplus", "V", "V", "N"])
            url_name = SLIDER_URL_NAMES.get(name, name)
            page.locator(f".w-{name} .noUi-handle").first.focus()
            value = widget_value(page, f"w-{name}")
            for _ in range(rng.randint(1, 3)):
                page.keyboard.press(rng.choice(["ArrowLeft", "ArrowRight"]))
                # each press that moves the slider is its own event to the server: the step
                # ends once the URL shows the value of each press in turn.  (Waiting for the
                # first change of the URL ended at the first press, and the check compared a
                # plot drawn for the later ones with it; waiting for the last value ended early
                # when a press went back — Right, Right, Left: the first press's value is the
                # last's — and the step settled on the second press's state.)
                before, value = value, widget_value(page, f"w-{name}")
                if value != before:  # else at the slider's end: nothing was sent
                    expect(page, lambda q, n=url_name, v=value: float(q.get(n, "nan")) == v,
                           f"{url_name}={value!r}", steps)  # fmt: skip
        elif r < 0.6:
            kind = "tab"
            key = rng.choice(["force", "phase", "profiles", "diagram", "floquet", "simulation"])
            open_tab(page, TAB_TITLES[key])
            expect(page, lambda q, k=key: q.get("tab") == k, f"tab={key}", steps)
        elif r < 0.7:
            kind = "mode"
            mode = rng.choice(["superkink", "solitary"])
            page.locator(".w-mode button", has_text=mode).click()
            expect(page, lambda q, m=mode: q.get("mode") == m, f"mode={mode}", steps)
        elif r < 0.75:
            # typed into the exact box: V_SK itself (invalid in solitary mode), out of range,
            # or a valid V — the slider must show it without echoing another value back
            kind = "typed V"
            V = rng.choice(["5.374838498865699", "9", "4.1", "5.2", "5.45"])
            inp = page.locator(".in-V input")
            inp.fill(V)
            inp.press("Enter")
            # (at load 20 the typed value took longer than 20 s to reach the URL, and the
            # check below then compared the previous state: step 18 of seed 13)
            expect(page, lambda q, v=V: q.get("V") in (v, repr(float(v))), f"V={V}", steps)
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
    assert len(kinds) >= 4


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
    open_law_box(page)
    law = "w + 10*w**2 - w**3"
    type_into(page, "in-law", law, "law", law)
    moved = press_on_slider(page, "w-c2", "End")["law"]
    assert moved != law
    type_into(page, "in-law", law, "law", law)
    q = press_on_slider(page, "w-c2", "End")
    assert q["law"] == moved, (moved, q)
    assert page.locator(".in-law input").input_value() == moved
    assert not app_tracebacks()


# ------------------------------------------------------------------------------ a typed law
QUARTIC = "w + 10*w**2 - w**3 - 0.01*w**4"


def test_typed_law_reaches_every_scene_and_the_url(page):
    """Choose "expression", type the quartic, and every scene renders for it — its
    status has "Time:" and the law in its parameters line, the URL carries law=…, a coefficient
    slider rewrites the law, and the server log has no traceback."""
    open_app(page, FAST)
    box = open_law_box(page)
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


def test_an_invalid_url_value_is_reported_and_the_address_bar_rewritten(page):
    """?tab=nonsense: the message names the value, the state keeps its default tab, and the
    address bar shows the state's URL (a copied link reproduces what is on screen)."""
    page.goto(f"{page.server}/main?tab=nonsense&{FAST}")
    page.locator(".url-message").get_by_text("nonsense").wait_for()
    q = wait_url(page, lambda q: q.get("tab") == "force")
    assert q.get("tab") == "force", page.url
    assert "nonsense" not in page.url
