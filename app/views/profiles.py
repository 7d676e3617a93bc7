"""Scene 3 — strain profiles (Figs. TWcubic, SWs_cubic, SWs_cubic_DvsQC).

The QC profile w(ξ) (solid, closed form eqs. SKsoln_cubic / SWsoln_cubic) with the discrete
traveling wave w_n(0) (circles, fixed point of eq. nonlin_map at N sites, tolerance tol)
overlaid.  Near V_SK a solitary wave is a kink–antikink bundle: the superkink fronts are drawn
(dashed) at the two boundary layers.  The QC curve is shown at once; the discrete solve follows.
"""

from __future__ import annotations

import holoviews as hv
import numpy as np
import panel as pn

from .. import compute
from .base import Info, Scene, SceneMessage, as_csv, fmt_num


class ProfilesScene(Scene):
    key = "profiles"
    title = "Profiles"

    def controls(self):
        self.show_discrete = pn.widgets.Checkbox(label="discrete wave (N, tol)", value=True)
        self.show_fronts = pn.widgets.Checkbox(label="kink/antikink fronts near V_SK", value=True)
        return [self.show_discrete, self.show_fronts]

    def _extra_watch(self):
        for w in (self.show_discrete, self.show_fronts):
            w.param.watch(lambda e: self.request(), "value")

    def _qc_overlay(self, info: Info):
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
        items = [hv.Curve((xi, wq), "ξ", "w", label="QC").opts(color="#1f77b4", line_width=2.5)]
        self._cols = {"xi": xi, "w_qc": wq}
        fronts = []
        if s.mode == "solitary" and self.show_fronts.value:
            fronts = self._fronts(qcw, xi, info)
        # fixed structure (empty placeholders), so updates stay in place
        items += fronts or [self._front_curve([], []), self._front_curve([], [])]
        return items, what, half

    @staticmethod
    def _front_curve(x, y):
        return hv.Curve((x, y), "ξ", "w", label="kink / antikink fronts").opts(
            color="#d62728", line_dash="dashed", line_width=1.5
        )

    @staticmethod
    def _dots(x, y):
        return hv.Scatter((x, y), "ξ", "w", label="discrete").opts(
            marker="circle", size=6, fill_color="white", line_color="black", color="black"
        )

    def _fronts(self, sw, xi, info: Info):
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
        return [self._front_curve(xi, kr), self._front_curve(xi, kl)]

    def _finish(self, items, title):
        return hv.Overlay(items).opts(
            responsive=True,
            min_height=self.plot_height - 20,
            legend_position="top_right",
            title=title,
            show_grid=True,
        )

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        items, what, half = self._qc_overlay(info)
        info.shown = what
        title = "Strain profile: QC (line) and discrete (circles)"
        self._discrete = None
        if not self.show_discrete.value:
            info.notes.append("discrete wave off: QC only")
            return self._finish(items + [self._dots([], [])], title)
        self.show_intermediate(self._finish(items + [self._dots([], [])], title), info)
        try:
            c = compute.discrete_wave(s.a, s.b, s.mode, s.w_plus, s.V, s.N, s.tol)
        except compute.NotAvailable as exc:
            info.notes.append(f"discrete wave not available: {exc}")
            return self._finish(items + [self._dots([], [])], title)
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
        items.append(self._dots(r.n[sel], r.w[sel]))
        info.shown = what + f"; discrete amplitude {fmt_num(r.amplitude)}"
        return self._finish(items, title)

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
