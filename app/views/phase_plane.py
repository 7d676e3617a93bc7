"""Scene 2 — QC phase plane (Fig. pplane).

Level sets of the exact first integral H(w, w′) of eq. TW_QC_gen3 (thin), the separatrix levels
through the saddles (thick), critical points marked by type (saddle ×, center ○) and the
current orbit highlighted: the homoclinic orbit of a tensile/compressive solitary wave, or the
kink (red) and antikink (green) heteroclinic pair at V = V_SK.  A click draws the orbit through
that point (pplane-style, from the closed-form first integral: fpucore.qc.phase.orbit_through);
the clicked points stay (their orbits follow w₊ and V) until "Clear orbits".  QC only.
"""

from __future__ import annotations

import contourpy
import numpy as np
import panel as pn
from bokeh.events import Tap

from .. import compute
from ..compute.cache import exact
from .bokeh_scene import BokehScene, Updates, add_legend, add_line, add_points, new_figure
from .formatting import as_csv, fmt_num, provenance
from .held import Held, HeldCurves
from .python_code import python_preamble
from .report import Info, SceneMessage
from .scene import Scene
from .untrusted import LiteralMarkdown

ORBIT_COLORS = {"kink": "#d62728", "antikink": "#2ca02c"}
MAX_CLICKED = 8  # orbits drawn through clicked points at once (the oldest goes first)
POINT_STYLES = (  # kind, marker, color
    ("saddle", "x", "black"),
    ("center", "circle", "#1f77b4"),
    ("degenerate", "diamond", "orange"),
)


def contour_lines(pp, levels) -> tuple[np.ndarray, np.ndarray]:
    """Level sets of the grid H(w, w′) as one NaN-separated polyline (x, y)."""
    if len(levels) == 0:
        return np.empty(0), np.empty(0)
    gen = contourpy.contour_generator(pp.w, pp.wp, pp.H, line_type="ChunkCombinedNan")
    parts = [pts for (chunk,) in gen.multi_lines(levels) for pts in chunk if pts is not None]
    if not parts:
        return np.empty(0), np.empty(0)
    nan = np.full((1, 2), np.nan)
    xy = np.concatenate([p for part in parts for p in (part, nan)][:-1])
    return xy[:, 0], xy[:, 1]


class PhasePlaneScene(BokehScene):
    title = "Phase plane"
    caption = (
        "_Level sets of the first integral of the quasicontinuum traveling-wave equation, "
        "with the current orbit highlighted. Paper: Fig. 2 (pplane)._"
    )
    cheap = True
    depends = (*Scene.depends, "held")

    def build(self):
        fig = new_figure(
            "Phase plane (w, w′) of the quasicontinuum traveling waves",
            "w",
            "w′",
            sizing_mode="stretch_width",
            height=self.plot_height,
        )
        self.fig = fig
        fig.x_range.name, fig.y_range.name = "phase-x", "phase-y"  # read by the browser tests
        self.r_thin = add_line(fig, "#aaaaaa", 0.8)
        self.r_sep = add_line(fig, "#444444", 1.6)
        self.r_orbits = [add_line(fig, "#e377c2", 3.5) for _ in range(2)]
        self.r_clicked = add_line(fig, "#ff7f0e", 2.0, "dashed")
        self.r_clicked[1].name = "phase-clicked-orbits"  # read by the tests
        self.r_seeds = add_points(fig, "circle", 7, color="#ff7f0e")
        fig.on_event(Tap, lambda ev: self.click(ev.x, ev.y))
        self.r_points = [
            add_points(fig, marker, 14, color=color, line_width=3)
            for _, marker, color in POINT_STYLES
        ]
        held = self.held.build(fig, "phase-held")
        items = add_legend(
            fig,
            "right",
            [("orbit", [r]) for r, _ in self.r_orbits]
            + [(kind, [r]) for (kind, _, _), (r, _) in zip(POINT_STYLES, self.r_points)]
            + [("orbit through a click", [self.r_clicked[0], self.r_seeds[0]])]
            + held,
        )
        n = 2 + len(POINT_STYLES)
        self.orbit_items, self.point_items = items[:2], items[2:n]
        self.clicked_item, self.held_items = items[n], items[n + 1 :]
        return fig

    def controls(self):
        self.clear_btn = pn.widgets.Button(label="Clear orbits", css_classes=["phase-clear"])
        self.held = HeldCurves(self.state, self.request, "phase")
        self.held.set_source(self._orbit_shown)
        return [
            LiteralMarkdown("_Click in the plane: the orbit through that point._"),
            self.clear_btn,
            LiteralMarkdown("_Hold keeps the current orbit on the plot while V and w₊ move._"),
            *self.held.widgets(),
        ]

    def _orbit_shown(self) -> bool:
        """Whether the current wave's orbit is on screen (what Hold holds)."""
        pp = getattr(self, "_pp", None)
        return self.last_info is not None and pp is not None and bool(pp.orbits)

    def _held_curve(self, wave) -> Held:
        """A held wave's orbit(s) (the superkink's pair) from its own phase plane (cached)."""
        lw = self.state.law()
        V = compute.run(lw, compute.QCWaveRequest(wave.mode, wave.w_plus, wave.V)).value.V
        pp = compute.run(lw, compute.PhasePlaneRequest(wave.w_plus, V)).value
        xs, ys = [], []
        for o in pp.orbits:
            xs += [o.w, [np.nan]]
            ys += [o.wp, [np.nan]]
        wp = float(wave.w_plus)
        code = f"held.append(phase.phase_plane(law, {wp!r}, {float(V)!r}, n_grid=241))"
        none = np.empty(0)
        if not xs:
            return Held(wave.label(V), none, none, none, none, code)
        x, y = np.concatenate(xs[:-1]), np.concatenate(ys[:-1])
        return Held(wave.label(V), x, y, none, none, code)

    def __init__(self, state):
        super().__init__(state)
        self.clicks: list[tuple[float, float]] = []
        self.clear_btn.on_click(self._on_clear)

    def _on_clear(self, _) -> None:
        self.clicks = []
        self.request()

    def click(self, w0, wp0) -> bool:
        """Add the orbit through (w0, w0′) (a click); False for a point off the plot."""
        if w0 is None or wp0 is None:
            return False
        self.clicks = [*self.clicks, (float(w0), float(wp0))][-MAX_CLICKED:]
        self.request()
        return True

    def _clicked_orbits(self, pp, lw, info: Info) -> tuple[np.ndarray, np.ndarray, list]:
        """The orbits through the clicked points inside this portrait's window, as one
        NaN-separated polyline, and the points used."""
        s = self.state
        xs, ys, seeds, worst, cost = [], [], [], 0.0, 0.0
        for w0, wp0 in self.clicks:
            if not (pp.w[0] <= w0 <= pp.w[-1] and pp.wp[0] <= wp0 <= pp.wp[-1]):
                continue  # the window moved with w₊ or V: this point is off the plot now
            c = compute.run(
                lw, compute.PhaseOrbitRequest(s.w_plus, s.V, w0, wp0, (pp.w[0], pp.w[-1]))
            )
            o = c.value
            xs += [o.w, [np.nan]]
            ys += [o.wp, [np.nan]]
            seeds.append((w0, wp0))
            worst, cost = max(worst, o.residual), cost + c.elapsed_s
        if seeds:
            info.time(f"{len(seeds)} clicked orbit(s)", cost)
            info.error("H on clicked orbits", worst)
        if not xs:
            return np.empty(0), np.empty(0), seeds
        return np.concatenate(xs[:-1]), np.concatenate(ys[:-1]), seeds

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        lw = s.law()
        c = compute.run(lw, compute.PhasePlaneRequest(s.w_plus, s.V))
        pp = c.value
        info.time("phase plane (QC)", c)
        info.error("H on orbit / H range", pp.orbit_residual)
        if not np.all(np.isfinite(pp.H)):
            raise SceneMessage("the first integral is not finite on this grid")
        up = Updates()
        key = (compute.laws.law_key(lw), exact(s.w_plus), exact(s.V))

        qs = np.quantile(pp.H, np.linspace(0.02, 0.6, 12))
        levels = sorted(set(np.round(np.concatenate([qs, pp.separatrix_levels]), 14)))
        x, y = contour_lines(pp, levels)
        up.data(self.r_thin[1], key, x=x, y=y)
        x, y = contour_lines(pp, sorted(pp.separatrix_levels))
        up.data(self.r_sep[1], key, x=x, y=y)
        for k, ((r, src), item) in enumerate(zip(self.r_orbits, self.orbit_items)):
            if k < len(pp.orbits):
                o = pp.orbits[k]
                up.data(src, key, x=o.w, y=o.wp)
                up.set(r.glyph, line_color=ORBIT_COLORS.get(o.name, "#e377c2"))
                up.set(item, label={"value": o.name})
            up.show(r, item, k < len(pp.orbits))
        # only the critical points inside the plotted window are drawn, and only those listed
        shown = [cp for cp in pp.critical_points if pp.w[0] <= cp.w <= pp.w[-1]]
        for (kind, _, _), (r, src), item in zip(POINT_STYLES, self.r_points, self.point_items):
            ws = np.array([cp.w for cp in shown if cp.kind == kind], float)
            up.data(src, key, x=ws, y=np.zeros(len(ws)))
            up.show(r, item, len(ws) > 0)
        x, y, seeds = self._clicked_orbits(pp, lw, info)
        up.data(self.r_clicked[1], x=x, y=y)
        up.data(self.r_seeds[1], x=[p[0] for p in seeds], y=[p[1] for p in seeds])
        up.show(self.r_clicked[0], self.clicked_item, bool(seeds))
        up.show(self.r_seeds[0], None, bool(seeds))
        self.held.compute(self._held_curve, info)
        self.held.update(up, self.held_items)
        up.range(self.fig.x_range, pp.w[0], pp.w[-1])
        up.range(self.fig.y_range, pp.wp[0], pp.wp[-1])

        names = ", ".join(f"{cp.kind} at w = {fmt_num(cp.w, 5)}" for cp in shown)
        orbit = {"superkink": "kink/antikink heteroclinic pair", "none": "no orbit"}.get(
            pp.regime, f"{pp.regime} solitary wave (homoclinic)"
        )
        info.shown = f"{orbit} at w₊ = {fmt_num(s.w_plus)}, V = {fmt_num(s.V)}; {names}"
        self._pp = pp
        return up

    def download_data(self):
        pp = getattr(self, "_pp", None)
        if pp is None or not pp.orbits:
            raise SceneMessage("no orbit shown")
        cols = {}
        for o in pp.orbits:
            cols[f"{o.name} w"] = o.w
            cols[f"{o.name} w'"] = o.wp
        cols |= self.held.columns()
        hdr = provenance(self.state, f"phase-plane orbits ({pp.regime})")
        return "phase_orbits.csv", as_csv(cols, hdr + "\n" + self.python_code())

    def notebook_plot(self) -> str:
        return (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            "fig, ax = plt.subplots(figsize=(8, 5))\n"
            "levels = np.unique(np.r_[np.quantile(pp.H, np.linspace(0.02, 0.6, 12)), "
            "pp.separatrix_levels])\n"
            "ax.contour(pp.w, pp.wp, pp.H, levels=levels, colors='gray', linewidths=0.8)\n"
            "for orbit in pp.orbits:\n"
            "    ax.plot(orbit.w, orbit.wp, lw=3, label=orbit.name)\n"
            "for c in pp.critical_points:\n"
            "    ax.plot(c.w, 0.0, 'x' if c.kind == 'saddle' else 'o', color='k')\n"
            + (
                "for k, hp in enumerate(held):\n"
                "    for orbit in hp.orbits:\n"
                "        ax.plot(orbit.w, orbit.wp, '--', label=f'held {k}: V = {hp.V:.6g}')\n"
                if self.held.items
                else ""
            )
            + "ax.set(xlabel='w', ylabel=\"w'\", title='phase plane (QC)')\n"
            "ax.legend()\n"
        )

    def python_code(self) -> str:
        s = self.state
        wv = f"{float(s.w_plus)!r}, {float(s.V)!r}"
        code = python_preamble(s) + (
            "from fpucore.qc import phase\n"
            f"pp = {compute.PhasePlaneRequest(s.w_plus, s.V).call().code()}\n"
            "print(pp.regime, [(c.kind, c.w) for c in pp.critical_points])\n"
        )
        for w0, wp0 in self.clicks:  # the orbits through the clicked points
            code += f"o = phase.orbit_through(law, {wv}, {w0!r}, {wp0!r}, (pp.w[0], pp.w[-1]))\n"
        return code + self.held.code()
