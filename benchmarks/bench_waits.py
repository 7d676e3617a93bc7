"""The user's waits in the served explorer, as the page measures them ("Your wait" under a
scene's status: click → drawn, with its queued / computed / transfer-and-draw parts), on a quiet
machine and beside busy processes.

Run: ``.venv/bin/python -m benchmarks.bench_waits [--hogs 2] [--rounds 2]``.  ``--hogs K``
starts K processes that spin a core each for the whole run (the "loaded" figures).  Waits
timed: a Paper-tab click on each simulation figure (the click starts the run) and a V-slider
key press on the force-law and Profiles scenes.  Each row also gives the time this script saw
from its click to the new status (an outside check on the page's own figure).
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import re
import statistics
import time

from benchmarks.served import served_app

FIGURES = ("stabSK", "stabSW", "SWdyn", "Riemann1")


def spin() -> None:  # a busy process
    while True:
        pass


def status(pg, scene: str) -> str:
    return " ".join(pg.locator(f".scene-{scene} .scene-status p").all_inner_texts())


def wait_line(pg, scene: str, before: str, t_end: float) -> str:
    while time.monotonic() < t_end:
        line = " ".join(pg.locator(f".scene-{scene} .scene-wait p").all_inner_texts())
        if "click → drawn" in line and line != before:
            return line
        pg.wait_for_timeout(20)
    return "(no wait line)"


def timed(pg, scene: str, act) -> tuple[float, str]:
    """(seconds this script saw from the action to the scene's new completed status, the
    page's wait line)."""
    before = status(pg, scene)
    line0 = " ".join(pg.locator(f".scene-{scene} .scene-wait p").all_inner_texts())
    t = time.monotonic()
    act()
    t_end = t + 300
    while time.monotonic() < t_end:
        now = status(pg, scene)
        if now != before and "Time:" in now and "computing the rest" not in now:
            break
        pg.wait_for_timeout(20)
    seen = time.monotonic() - t
    return seen, wait_line(pg, scene, line0, time.monotonic() + 10)


def page_wait(line: str) -> str:
    m = re.search(r"Your wait: (.*)", line)
    return m.group(1) if m else line


def run(url: str, rounds: int) -> None:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(
            executable_path="/usr/bin/chromium",
            args=["--headless=new", "--no-sandbox", "--disable-gpu"],
        )
        pg = b.new_page(viewport={"width": 1500, "height": 1000})
        rows: list[tuple[str, float, str]] = []
        for _ in range(rounds):
            for label in FIGURES:
                pg.goto(url + "/main?tab=paper")
                pg.locator(f".paper-open-{label} button").wait_for(timeout=120_000)
                btn = pg.locator(f".paper-open-{label} button")
                seen, line = timed(pg, "simulation", btn.click)
                rows.append((f"Paper → {label}", seen, line))
            for scene in ("force", "profiles"):
                pg.goto(url + f"/main?tab={scene}&V=5.05&N=500")
                pg.locator(f".scene-{scene} .scene-status p", has_text="Time:").first.wait_for(
                    timeout=120_000
                )
                handle = pg.locator(".w-V .noUi-handle").first
                handle.focus()
                seen, line = timed(pg, scene, lambda: pg.keyboard.press("ArrowRight"))
                rows.append((f"V slider, {scene}", seen, line))
        b.close()
    print(f"{'action':24s} {'seen by the script':>18s}   the page's wait line")
    for name, seen, line in rows:
        print(f"{name:24s} {seen:16.2f} s   {page_wait(line)}")
    by: dict[str, list[float]] = {}
    for name, seen, _ in rows:
        by.setdefault(name, []).append(seen)
    print("medians:", ", ".join(f"{k} {statistics.median(v):.2f} s" for k, v in by.items()))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hogs", type=int, default=0, help="busy processes beside the server")
    ap.add_argument("--rounds", type=int, default=1, help="repetitions of every action")
    args = ap.parse_args(argv)
    hogs = [mp.Process(target=spin, daemon=True) for _ in range(args.hogs)]
    with served_app() as url:
        for h in hogs:
            h.start()
        try:
            print(f"{args.hogs} busy process(es) beside the server; load {os.getloadavg()[0]:.1f}")
            run(url, args.rounds)
        finally:
            for h in hogs:
                h.terminate()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
