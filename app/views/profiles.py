"""Scene 3 — strain profiles (Figs. TWcubic, SWs_cubic, SWs_cubic_DvsQC).

The QC profile w(ξ) (solid, closed form eqs. SKsoln_cubic / SWsoln_cubic) with the discrete
traveling wave w_n(0) (circles, fixed point of eq. nonlin_map at N sites, tolerance tol)
overlaid.  Near V_SK a solitary wave is a kink–antikink bundle: the superkink fronts are drawn
(dashed) at the two boundary layers.  The QC curve is shown at once; the discrete solve follows.
"""

from __future__ import annotations

import numpy as np
import panel as pn

from .. import compute
from ..compute import rnd
from .base import Info, SceneMessage, as_csv, fmt_num
from .bokeh_scene import (
    BokehScene,
    Updates,
    add_legend,
    add_line,
    add_points,
    finite_extent,
    new_figure,
)


class ProfilesScene(BokehScene):
    key = "profiles"
    title = "Profiles"

    def controls(self):
        self.show_discrete = pn.widgets.Checkbox(label="discrete wave (N, tol)", value=True)
        self.show_fronts = pn.widgets.Checkbox(label="kink/antikink fronts near V_SK", value=True)
        return [self.show_discrete, self.show_fronts]

    def _extra_watch(self):
        for w in (self.show_discrete, self.show_fronts):
            w.param.watch(lambda e: self.request(), "value")

    def build(self):
        fig = new_figure(
            "Strain profile: QC (line) and discrete (circles)",
            "ξ",
            "w",
            sizing_mode="stretch_width",
            height=self.plot_height,
        )
        self.fig = fig
        self.r_qc = add_line(fig, "#1f77b4", 2.5)
        self.r_fronts = [add_line(fig, "#d62728", 1.5, "dashed") for _ in range(2)]
        self.r_dots = add_points(
            fig, "circle", 6, fill_color="white", line_color="black", line_width=1
        )
        self.legend = add_legend(
            fig,
            "top_right",
            [
                ("QC", [self.r_qc[0]]),
                ("kink / antikink fronts", [r for r, _ in self.r_fronts]),
                ("discrete", [self.r_dots[0]]),
            ],
        )
        return fig

    def _qc_part(self, info: Info, up: Updates):
        s = self.state
        c = compute.qc_wave(s.a, s.b, s.mode, s.w_plus, s.V)
        qcw = c.value
        info.time("QC closed form", c)
        if s.mode == "superkink":
            info.error("QC Rayleigh residual", qcw.rayleigh_residual)
            half = max(8.0 * qcw.width, 25.0)
            what = (
                f"superkink V = {fmt_num(qcw.V)}, w₊ = {fmt_num(qcw.w_plus)}, "
                f"w₋ = {fmt_num(qcw.w_minus)}"
            )
        else:
            info.error("QC first-integral residual", qcw.first_integral_residual)
            half = max(14.0 * qcw.width, 25.0)
            what = (
                f"{qcw.kind} solitary wave V = {fmt_num(qcw.V)}, w_B = {fmt_num(qcw.w_B)}, "
                f"amplitude {fmt_num(qcw.amplitude)}"
            )
        half = min(half, 0.5 * self.state.N) if self.show_discrete.value else half
        xi = np.linspace(-half, half, 1601)
        wq = qcw.profile(xi)
        key = (s.mode, rnd(s.a), rnd(s.b), rnd(s.w_plus), rnd(s.V), rnd(half))
        up.data(self.r_qc[1], key, x=xi, y=wq)
        self._cols = {"xi": xi, "w_qc": wq}
        fronts = []
        if s.mode == "solitary" and self.show_fronts.value:
            fronts = self._fronts(qcw, xi, info)
        for k, (_, src) in enumerate(self.r_fronts):
            y = fronts[k] if fronts else np.empty(0)
            up.data(src, key + (bool(fronts),), x=xi if fronts else np.empty(0), y=y)
        up.show(self.r_fronts[0][0], self.legend[1], bool(fronts))
        up.show(self.r_fronts[1][0], None, bool(fronts))
        return what, half, xi, [wq, *fronts]

    def _fronts(self, sw, xi, info: Info) -> list[np.ndarray]:
        """Kink and antikink (QC superkinks of the same w₊) placed at the bundle's layers,
        shown when the solitary wave has a plateau (amplitude within 5% of |w₋ − w₊|)."""
        s = self.state
        sk = compute.qc_wave(s.a, s.b, "superkink", s.w_plus, s.V).value
        if abs(sw.amplitude - sk.amplitude) > 0.05 * sk.amplitude:
            return []
        w = sw.profile(xi)
        right = xi > 0
        mid = 0.5 * (sw.w_B + sw.w_M)
        k = np.flatnonzero(np.diff(np.sign(w[right] - mid)))
        if k.size == 0:
            return []
        x0 = float(xi[right][k[0]])
        sigma = 1.0 if sw.interval == "below" else -1.0  # right front ends at the background
        kr = sk.profile(sigma * (xi - x0))
        kl = sk.profile(sigma * (-xi - x0))
        info.notes.append(f"kink–antikink bundle: fronts at ξ = ±{x0:.4g}")
        self._cols.update(front_right=kr, front_left=kl)
        return [kr, kl]

    def _frame(self, up: Updates, half: float, ys: list, n=None, w=None) -> Updates:
        """Discrete dots (none if n is None) and the axis ranges."""
        if n is None:
            n = w = np.empty(0)
        up.data(self.r_dots[1], x=n, y=w)
        up.show(self.r_dots[0], self.legend[2], len(n) > 0)
        up.range(self.fig.x_range, -half, half)
        up.range(self.fig.y_range, *finite_extent(*ys, w), pad=0.06)
        return up

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        up = Updates()
        what, half, xi, ys = self._qc_part(info, up)
        info.shown = what
        self._discrete = None
        if not self.show_discrete.value:
            info.notes.append("discrete wave off: QC only")
            return self._frame(up, half, ys)
        if not compute.discrete_wave_cached(s.a, s.b, s.mode, s.w_plus, s.V, s.N, s.tol):
            # the QC curve now, the dots when the solve is done
            self.show_intermediate(self._frame(up, half, ys), info)
            up = Updates()
        c = compute.discrete_wave(s.a, s.b, s.mode, s.w_plus, s.V, s.N, s.tol)
        r = c.value
        self._discrete = r
        info.time(f"discrete N={r.N}", c)
        info.error("residual", r.residual)
        info.error("dropped eq.", r.dropped_residual)
        info.error("tail", getattr(r, "tail_error", float("nan")))
        info.error("max |discrete − QC|", getattr(r, "qc_max_deviation", float("nan")))
        if not r.converged:
            info.notes.append(f"discrete solve did not converge: {r.message}")
        sel = np.abs(r.n) <= half
        info.shown = what + f"; discrete amplitude {fmt_num(r.amplitude)}"
        return self._frame(up, half, ys, r.n[sel].astype(float), r.w[sel])

    def download_data(self):
        r = getattr(self, "_discrete", None)
        if r is not None:
            hdr = (
                f"discrete {r.kind} wave V={r.V!r} N={r.N} residual={r.residual:.3e} "
                f"(w_n(0), wdot_n(0); fixed ends w_left={r.w_left!r}, w_right={r.w_right!r})"
            )
            return "profile_discrete.csv", as_csv({"n": r.n, "w": r.w, "wdot": r.wdot}, hdr)
        if getattr(self, "_cols", None):
            return "profile_qc.csv", as_csv(self._cols, "QC profile")
        raise SceneMessage("nothing shown yet")
