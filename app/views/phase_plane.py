"""Scene 2 — QC phase plane (Fig. pplane).

Level sets of the exact first integral H(w, w′) of eq. TW_QC_gen3 (thin), the separatrix levels
through the saddles (thick), critical points marked by type (saddle ×, center ○) and the
current orbit highlighted: the homoclinic orbit of a tensile/compressive solitary wave, or the
kink (red) and antikink (green) heteroclinic pair at V = V_SK.  QC only.
"""

from __future__ import annotations

import holoviews as hv
import numpy as np

from .. import compute
from .base import Info, Scene, SceneMessage, as_csv, fmt_num

ORBIT_COLORS = {"kink": "#d62728", "antikink": "#2ca02c"}


class PhasePlaneScene(Scene):
    key = "phase"
    title = "Phase plane"
    cheap = True

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        c = compute.phase_plane(s.a, s.b, s.w_plus, s.V)
        pp = c.value
        info.time("phase plane (QC)", c)
        info.error("H on orbit / H range", pp.orbit_residual)
        if not np.all(np.isfinite(pp.H)):
            raise SceneMessage("the first integral is not finite on this grid")

        img = hv.Image((pp.w, pp.wp, pp.H), ["w", "w′"], "H")
        qs = np.quantile(pp.H, np.linspace(0.02, 0.6, 12))
        levels = sorted(set(np.round(np.concatenate([qs, pp.separatrix_levels]), 14)))
        thin = hv.operation.contours(img, levels=levels, filled=False).opts(
            color="#aaaaaa", line_width=0.8
        )
        items = [thin]
        if pp.separatrix_levels:
            sep = hv.operation.contours(img, levels=sorted(pp.separatrix_levels), filled=False)
            items.append(sep.opts(color="#444444", line_width=1.6))
        for o in pp.orbits:
            color = ORBIT_COLORS.get(o.name, "#e377c2")
            items.append(
                hv.Curve((o.w, o.wp), "w", "w′", label=o.name).opts(color=color, line_width=3.5)
            )
        for kind, marker, color in (
            ("saddle", "x", "black"),
            ("center", "circle", "#1f77b4"),
            ("degenerate", "diamond", "orange"),
        ):
            ws = [cp.w for cp in pp.critical_points if cp.kind == kind]
            if ws:
                items.append(
                    hv.Scatter((ws, np.zeros(len(ws))), "w", "w′", label=kind).opts(
                        marker=marker, size=14, color=color, line_width=3
                    )
                )
        names = ", ".join(f"{cp.kind} at w = {fmt_num(cp.w, 5)}" for cp in pp.critical_points)
        orbit = {"superkink": "kink/antikink heteroclinic pair", "none": "no orbit"}.get(
            pp.regime, f"{pp.regime} solitary wave (homoclinic)"
        )
        info.shown = f"{orbit} at w₊ = {fmt_num(s.w_plus)}, V = {fmt_num(s.V)}; {names}"
        self._pp = pp
        return hv.Overlay(items).opts(
            responsive=True,
            min_height=self.plot_height - 20,
            legend_position="top_right",
            title="Phase plane of eq. TW_QC_gen2 (Fig. pplane)",
            show_grid=True,
        )

    def download_data(self):
        pp = getattr(self, "_pp", None)
        if pp is None or not pp.orbits:
            raise SceneMessage("no orbit shown")
        cols = {}
        for o in pp.orbits:
            cols[f"{o.name} w"] = o.w
            cols[f"{o.name} w'"] = o.wp
        hdr = f"phase-plane orbits, w_plus={pp.w_plus!r}, V={pp.V!r}, regime={pp.regime}"
        return "phase_orbits.csv", as_csv(cols, hdr)
