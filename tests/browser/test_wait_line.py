"""The wait a user sees is the wait they had: after a slider key press, the scene's "Your wait"
line gives the time from the press to the drawn result as the page measured it, split into
the server's part (with the last render's share) and the rest — bounded here by the time the
test itself saw pass between its key press and the new status, and never less than the
server's share."""

from __future__ import annotations

import re
import time

import pytest
from browser_harness import app_tracebacks, settled, status_text, wait_status_change

pytestmark = pytest.mark.browser

SECONDS = r"([0-9.]+) (ms|s)"


def seconds(value: str, unit: str) -> float:
    return float(value) / (1000.0 if unit == "ms" else 1.0)


def wait_line(page, scene: str) -> str:
    return " ".join(page.locator(f".scene-{scene} .scene-wait p").all_inner_texts())


@pytest.mark.parametrize("scene", ["force", "profiles"])
def test_the_wait_line_is_the_pages_click_to_drawn_time(page, scene):
    page.goto(f"{page.server}/main?tab={scene}&V=5.05&N=200")
    settled(page)
    handle = page.locator(".w-V .noUi-handle").first
    handle.focus()
    for key in ("ArrowRight", "ArrowLeft"):
        before = status_text(page, scene)
        t0 = time.monotonic()
        page.keyboard.press(key)
        wait_status_change(page, scene, before)
        seen_s = time.monotonic() - t0
        t_end = time.monotonic() + 30
        line = ""
        while time.monotonic() < t_end:
            line = wait_line(page, scene)
            if "click → drawn" in line and line != getattr(page, "_last_wait", ""):
                break
            page.wait_for_timeout(50)
        page._last_wait = line
        m = re.search(r"Your wait: " + SECONDS + " click → drawn", line)
        assert m, line
        wait_s = seconds(*m.groups())
        parts = dict(
            (name, seconds(v, u))
            for name, v, u in re.findall(r"(server|the last render|the rest) " + SECONDS, line)
        )
        assert set(parts) == {"server", "the last render", "the rest"}, line
        # the page's measure sits inside what the test saw (+ its polling and a frame)
        assert wait_s <= seen_s + 0.5, (wait_s, seen_s, line)
        assert parts["the last render"] <= parts["server"] + 0.001, line
        assert wait_s >= parts["server"] - 0.01, line  # the server's part is inside the wait
        assert abs(parts["server"] + parts["the rest"] - wait_s) <= 0.02, line  # rounding
    print(f"[browser] {scene}: {line}")
    assert not app_tracebacks()
