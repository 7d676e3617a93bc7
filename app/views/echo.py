"""Throw-away heavy scene (measures the files a new heavy scene touches; reverted)."""

from __future__ import annotations

import numpy as np

from .. import compute
from .bokeh_scene import BokehScene, Updates, add_line, new_figure
from .report import Info


class EchoScene(BokehScene):
    title = "Echo"

    def build(self):
        self.fig = new_figure("f(w) in a worker", "w", "f(w)")
        self.r = add_line(self.fig, "#1f77b4", 1.5)
        return self.fig

    def render(self, info: Info):
        req = compute.EchoRequest(n=int(self.state.N))
        c = compute.run(self.state.law(), req, stop=self.superseded)
        info.time("echo", c)
        up = Updates()
        w, f = c.value
        up.data(self.r[1], x=w, y=f)
        up.range(self.fig.x_range, float(w[0]), float(w[-1]))
        up.range(self.fig.y_range, float(np.min(f)), float(np.max(f)), pad=0.05)
        return up

    def python_code(self) -> str:
        return super().python_code() + "# echo\n"
