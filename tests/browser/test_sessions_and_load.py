"""Several sessions and load: no cross-talk, a heavy job or a pathological law never blocks another
session or the server.
"""

from __future__ import annotations

import os
import random
import statistics
import time
import urllib.parse
import urllib.request

import pytest
from browser_harness import (
    FAST,
    TIMEOUT_MS,
    LivenessProbe,
    app_tracebacks,
    check_consistent,
    law_box_refusal,
    liveness_s,
    open_law_box,
    record_foreign_requests,
    server_rss_mb,
    settled,
    status_text,
    url_message,
    wait_status_change,
    wait_url,
    widget_value,
)

pytestmark = pytest.mark.browser


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
        live = [liveness_s(server) for _ in range(3)]
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


# ----------------------------------------------------------------------------- laws off the loop
DOS_LAWS = ["(w+1)**100000", "w*9**9**9"]


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
        box = open_law_box(a)
        box.fill(DOS_LAWS[1])
        box.press("Enter")
        before = status_text(b, "force")
        b.locator(".w-V .noUi-handle").first.focus()
        t = time.monotonic()
        b.keyboard.press("ArrowRight")
        wait_status_change(b, "force", before)
        renders.append(time.monotonic() - t)
        # a typed law that is refused never enters the state: the law editor names the refusal
        refusal = law_box_refusal(a, timeout=30.0)
        assert "law refused" in refusal, refusal
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
