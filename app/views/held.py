"""Held curves: "Hold" keeps the curve on screen (its data, from the last render — nothing is
recomputed) while the sliders move on, so several V overlay as in the paper's families of
profiles (Figs. cubic (b), SWs_cubic, TWcubic, SWs_cubic_DvsQC) and of phase-plane orbits;
"Clear held" removes them.

The renderers (MAX_HELD lines and point sets, one colour each) are built once with the figure;
a render only fills or hides them.  Each held curve keeps the fpucore call that computes it, so
"Copy as Python", the notebook, the data download and the exported figure hold it too.
Held curves live in the session (not in the URL: a link reproduces the current curve only).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import panel as pn

from .bokeh_scene import Updates, add_line, add_points

MAX_HELD = 6  # curves held at once (the oldest goes first)
HELD_COLORS = ("#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf")


@dataclass(frozen=True)
class Held:
    """One held curve: its legend label, its line (x, y; NaN-separated pieces allowed), its
    points (possibly empty) and the Python line that computes it: ``held.append(…)`` with
    ``{law}`` where the law goes (``law_src``: the law's constructor when it was held)."""

    label: str
    x: np.ndarray
    y: np.ndarray
    px: np.ndarray
    py: np.ndarray
    code: str
    law_src: str


class HeldCurves:
    """The Hold / Clear held buttons and the held curves' renderers on one figure."""

    def __init__(self, on_change, css: str):
        self.items: list[Held] = []
        self.hold_btn = pn.widgets.Button(label="Hold curve", css_classes=[f"{css}-hold"])
        self.clear_btn = pn.widgets.Button(label="Clear held", css_classes=[f"{css}-clear-held"])
        self._hold = None  # the scene's function returning the Held of what is shown
        self._on_change = on_change
        self.hold_btn.on_click(lambda _: self.hold())
        self.clear_btn.on_click(lambda _: self.clear())

    def widgets(self) -> list:
        return [pn.Row(self.hold_btn, self.clear_btn)]

    def build(self, fig, name: str, current_item_renderers=None) -> list:
        """The renderers on ``fig`` (sources named ``{name}-{k}``, read by the tests); returns
        the legend entries (label, renderers) to add."""
        self.lines, self.points = [], []
        for k, color in enumerate(HELD_COLORS[:MAX_HELD]):
            line = add_line(fig, color, 1.8, "dashed")
            line[1].name = f"{name}-{k}"
            pts = add_points(fig, "circle", 5, color=color)
            self.lines.append(line)
            self.points.append(pts)
        return [(f"held {k}", [self.lines[k][0], self.points[k][0]]) for k in range(MAX_HELD)]

    def set_source(self, make_held) -> None:
        """``make_held()`` → the Held of the curve now shown (None if nothing is shown)."""
        self._hold = make_held

    def hold(self) -> bool:
        h = self._hold() if self._hold is not None else None
        if h is None:
            return False
        self.items = [*(i for i in self.items if i.label != h.label), h][-MAX_HELD:]
        self._on_change()
        return True

    def clear(self) -> None:
        self.items = []
        self._on_change()

    def update(self, up: Updates, legend_items) -> list[np.ndarray]:
        """Fill the renderers (and name the legend entries); returns the held y arrays (for the
        axis ranges)."""
        ys = []
        for k in range(MAX_HELD):
            (rl, sl), (rp, sp), item = self.lines[k], self.points[k], legend_items[k]
            if k < len(self.items):
                h = self.items[k]
                up.data(sl, ("held", h.label), x=h.x, y=h.y)
                up.data(sp, ("held", h.label), x=h.px, y=h.py)
                up.set(item, label={"value": f"held: {h.label}"})
                ys += [h.y, h.py]
            else:
                up.data(sl, ("held", None), x=np.empty(0), y=np.empty(0))
                up.data(sp, ("held", None), x=np.empty(0), y=np.empty(0))
            shown = k < len(self.items)
            up.show(rl, item, shown)
            up.show(rp, None, shown and k < len(self.items) and len(self.items[k].px) > 0)
        return ys

    def code(self, law_src: str) -> str:
        """The held curves' fpucore calls (``held`` is the list of their results); a curve held
        under the current law (constructor ``law_src``) uses ``law``, another its own law."""
        if not self.items:
            return ""
        out = "# held curves (Hold), oldest first\nheld = []\n"
        for h in self.items:
            out += h.code.format(law="law" if h.law_src == law_src else h.law_src) + "\n"
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """The held curves as CSV columns."""
        cols = {}
        for h in self.items:
            cols[f"held {h.label} x"] = h.x
            cols[f"held {h.label} y"] = h.y
            if len(h.px):
                cols[f"held {h.label} points x"] = h.px
                cols[f"held {h.label} points y"] = h.py
        return cols
