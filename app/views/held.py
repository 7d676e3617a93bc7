"""Held curves: "Hold" keeps the current wave on screen while the sliders move on, so several V
overlay as in the paper's families of profiles (Figs. cubic (b), SWs_cubic, TWcubic,
SWs_cubic_DvsQC) and of phase-plane orbits; "Clear held" removes them.

The state owns the held waves (ExplorerState.held: (mode, w₊, V), up to MAX_HELD, in the URL's
``hold``); each scene that draws them recomputes their curves through app.compute (cached: a
wave held from the screen is the very one just computed) under the current law, N and tol, so a
link reproduces them.  Both Wave profiles and Phase plane draw the same held waves.

The renderers (MAX_HELD lines and point sets, one colour each) are built once with the figure;
a render only fills or hides them.  Each held curve keeps the fpucore call that computes it, so
"Copy as Python", the notebook, the data download and the exported figure hold it too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import panel as pn

from fpucore.errors import ParameterError

from ..state import MAX_HELD
from .bokeh_scene import Updates, add_line, add_points
from .report import Info
from .untrusted import md_literal

HELD_COLORS = ("#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf")


@dataclass(frozen=True)
class Held:
    """One held curve as drawn: its legend label, its line (x, y; NaN-separated pieces
    allowed), its points (possibly empty) and the Python line that computes it
    (``held.append(…)``, with the current ``law``)."""

    label: str
    x: np.ndarray
    y: np.ndarray
    px: np.ndarray
    py: np.ndarray
    code: str


class HeldCurves:
    """The Hold / Clear held buttons and the held curves' renderers on one figure."""

    def __init__(self, state, on_change, css: str):
        self.state = state
        self.items: list[Held] = []  # the held curves of the last render, oldest first
        self.hold_btn = pn.widgets.Button(label="Hold curve", css_classes=[f"{css}-hold"])
        self.clear_btn = pn.widgets.Button(label="Clear held", css_classes=[f"{css}-clear-held"])
        self._shown = None  # the scene's function: is a curve of the current wave on screen?
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

    def set_source(self, shown) -> None:
        """``shown()`` → whether the current wave's curve is on screen (Hold holds only that)."""
        self._shown = shown

    def hold(self) -> bool:
        """Hold the wave on screen (the state's current wave): the state's held list, and so
        the URL, gets it; the scenes that draw it re-render."""
        wave = self.state.current_wave() if self._shown is None or self._shown() else None
        if wave is None:
            return False
        self.state.hold(wave)
        self._on_change()
        return True

    def clear(self) -> None:
        self.state.held = []
        self._on_change()

    def compute(self, curve_of, info: Info) -> list[Held]:
        """The state's held waves as curves: ``curve_of(wave)`` → Held (raises ParameterError
        for a wave that is no wave of the current law: named in the notes, not drawn)."""
        items = []
        for wave in list(self.state.held):
            try:
                items.append(curve_of(wave))
            except ParameterError as exc:
                info.notes.append(f"held {wave.label()}: not drawn, {md_literal(exc)}")
        self.items = items
        return items

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

    def code(self) -> str:
        """The held curves' fpucore calls (``held`` is the list of their results)."""
        if not self.items:
            return ""
        out = "# held curves (Hold), oldest first\nheld = []\n"
        return out + "".join(h.code + "\n" for h in self.items)

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
