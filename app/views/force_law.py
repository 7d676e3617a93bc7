"""Scene 1 — the force law (Fig. superkink).

f(w) (red), the superkink's Rayleigh line of slope V_SK² through (w₊, f(w₊)) and (w₋, f(w₋))
with the two equal areas it cuts from f shaded (eq. zero_G), w* and the convex interval (α, β).
In solitary mode also the current Rayleigh line of slope V², and the sonic lines of slopes c₊²
(blue, tangent at w₊) and c₋² (green, tangent at w₋ˢ).  QC only: no discrete solve.
"""

from __future__ import annotations

import holoviews as hv
import numpy as np

from fpucore import qc

from .. import compute
from .base import Info, Scene, SceneMessage, as_csv, fmt_num


class ForceLawScene(Scene):
    key = "force"
    title = "Force law"
    cheap = True

    def render(self, info: Info):
        s = self.state
        lw = s.law()
        alpha, ws, beta = lw.alpha, lw.w_star, lw.beta
        try:
            sk_c = compute.qc_wave(s.a, s.b, "superkink", s.w_plus, s.V)
        except compute.ParameterError as exc:
            raise SceneMessage(str(exc)) from None
        sk = sk_c.value
        info.time("QC superkink", sk_c)
        info.error("Rayleigh residual", sk.rayleigh_residual)
        info.error("equal-area residual |G|", sk.driving_force)

        span = beta - alpha
        w = np.linspace(alpha - 0.06 * span, beta + 0.06 * span, 801)
        fw = lw.f(w)
        wp, wm = sk.w_plus, sk.w_minus
        fp = float(lw.f(wp))
        items = [hv.Curve((w, fw), "w", "f(w)", label="f(w)").opts(color="#d62728", line_width=2.5)]

        # equal areas between f and the superkink Rayleigh line, on each side of w*
        R = lambda x, V: fp + V * V * (x - wp)  # noqa: E731
        for lo, hi, color in (
            (min(wp, ws), max(wp, ws), "#9ecae1"),
            (min(wm, ws), max(wm, ws), "#fdae6b"),
        ):
            x = np.linspace(lo, hi, 200)
            items.append(
                hv.Area((x, lw.f(x), R(x, sk.V)), "w", ["f(w)", "R"]).opts(
                    color=color, alpha=0.6, line_alpha=0
                )
            )
        x = np.linspace(min(wp, wm), max(wp, wm), 2)
        items.append(
            hv.Curve((x, R(x, sk.V)), "w", "f(w)", label="Rayleigh line (V_SK)").opts(
                color="black", line_width=2
            )
        )
        pts = {"w": [wp, wm], "f": [fp, float(lw.f(wm))], "label": ["w₊", "w₋"]}
        shown = (
            f"superkink construction for w₊ = {fmt_num(wp)}: w₋ = {fmt_num(wm)}, "
            f"V_SK = {fmt_num(sk.V)}"
        )

        if s.mode == "solitary":
            cp, vsk, cm = qc.sound_speeds(lw, wp)
            wms = qc.w_minus_sonic(lw, wp)
            xl = np.linspace(w[0], w[-1], 2)
            for V, color, lab in (
                (cp, "#1f77b4", "sonic line c₊"),
                (cm, "#2ca02c", "sonic line c₋"),
            ):
                items.append(
                    hv.Curve((xl, R(xl, V)), "w", "f(w)", label=lab).opts(
                        color=color, line_width=1.5
                    )
                )
            pts["w"].append(wms)
            pts["f"].append(float(lw.f(wms)))
            pts["label"].append("w₋ˢ")
            problem = s.problem()
            if problem is None:
                items.append(
                    hv.Curve((xl, R(xl, s.V)), "w", "f(w)", label="Rayleigh line (current V)").opts(
                        color="#9467bd", line_dash="dashed", line_width=2
                    )
                )
                roots = qc.rayleigh_roots(lw, wp, s.V)
                for r in roots:
                    if np.isfinite(r):
                        pts["w"].append(r)
                        pts["f"].append(float(lw.f(r)))
                        pts["label"].append("root")
                shown += f"; current V = {fmt_num(s.V)} in " + (
                    "(c₊, V_SK)" if s.V < vsk else "(V_SK, c₋)"
                )
            else:
                info.warning = f"current V not drawn: {problem}"

        items.append(
            hv.Scatter(pts, "w", ["f", "label"]).opts(color="black", size=8, tools=["hover"])
        )
        ymin, ymax = float(np.min(fw)), float(np.max(fw))
        pad = 0.08 * (ymax - ymin)
        for x0, lab in ((ws, "w*"), (alpha, "α"), (beta, "β")):
            items.append(hv.VLine(x0).opts(color="gray", line_dash="dotted"))
            items.append(hv.Text(x0, ymax + 0.5 * pad, lab).opts(text_color="gray"))
        info.shown = shown
        self._data = {"w": w, "f": fw, "R_SK": R(w, sk.V)}
        self._header = shown
        return hv.Overlay(items).opts(
            responsive=True,
            min_height=self.plot_height - 20,
            legend_position="top_left",
            ylim=(ymin - pad, ymax + pad),
            title="Force law and Rayleigh line (Fig. superkink)",
            show_grid=True,
        )

    def download_data(self):
        if not getattr(self, "_data", None):
            raise SceneMessage("nothing shown yet")
        return "force_law.csv", as_csv(self._data, self._header)
