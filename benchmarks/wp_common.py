"""Shared pieces of the work–precision report: timing, rows, Markdown table, HoloViews plot.

Every study returns a list of :class:`Row` measured in one run on this machine; the driver
(:mod:`benchmarks.work_precision`) writes them to ``docs/work_precision.md`` (tables) and
``docs/work_precision.html`` (log–log plots).  Nothing here is typed in by hand.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass


@dataclass
class Row:
    route: str  # "period map", "traveling wave", "Floquet", "simulation"
    method: str  # curve label, e.g. "fpucore DOP853 (fixed m)" or "scipy solve_ivp DOP853"
    setting: str  # what was varied, e.g. "m=8" or "rtol=1e-10"
    error: float  # error against the high-accuracy reference (the route's stated metric)
    seconds: float  # best-of-repeats wall time, warm JIT
    note: str = ""


@dataclass
class Floor:
    route: str
    what: str
    seconds: float


def best_time(fn: Callable[[], object], repeat: int = 3, min_time: float = 0.05) -> float:
    """Best of ``repeat`` timings; each timing loops fn until ``min_time`` has elapsed."""
    best = float("inf")
    for _ in range(repeat):
        n, t0 = 0, time.perf_counter()
        while True:
            fn()
            n += 1
            dt = time.perf_counter() - t0
            if dt >= min_time or n >= 1000:
                break
        best = min(best, dt / n)
    return best


def markdown(rows: list[Row], floors: list[Floor]) -> str:
    out = []
    for route in dict.fromkeys(r.route for r in rows):
        out.append(f"### {route}\n")
        fl = [f for f in floors if f.route == route]
        for f in fl:
            out.append(f"Floor — {f.what}: **{f.seconds * 1e3:.3g} ms**\n")
        out.append("| method | setting | error | time [ms] | × floor | note |")
        out.append("|---|---|---|---|---|---|")
        base = fl[0].seconds if fl else float("nan")
        for r in (r for r in rows if r.route == route):
            ratio = f"{r.seconds / base:.3g}" if fl else "—"
            out.append(
                f"| {r.method} | {r.setting} | {r.error:.2e} | {r.seconds * 1e3:.3g} | "
                f"{ratio} | {r.note} |"
            )
        out.append("")
    return "\n".join(out)


def plot_html(rows: list[Row], path: str) -> None:
    """Log–log error vs time, one panel per route, one curve per method (HoloViews/Bokeh)."""
    import holoviews as hv

    hv.extension("bokeh")
    panels = []
    for route in dict.fromkeys(r.route for r in rows):
        curves = []
        for method in dict.fromkeys(r.method for r in rows if r.route == route):
            pts = [
                (r.seconds, max(r.error, 1e-17))
                for r in rows
                if (r.route, r.method) == (route, method)
            ]
            pts.sort()
            curves.append(
                hv.Curve(pts, "time [s]", "error", label=method)
                * hv.Scatter(pts, "time [s]", "error", label=method).opts(size=6)
            )
        panels.append(
            hv.Overlay(curves).opts(
                title=route,
                logx=True,
                logy=True,
                width=560,
                height=400,
                legend_position="top_right",
                padding=0.15,
            )
        )
    # inline resources: the report opens offline (no CDN on the machines that generate it)
    layout = hv.Layout(panels).cols(2).opts(shared_axes=False)
    hv.save(layout, path, backend="bokeh", resources="inline")
