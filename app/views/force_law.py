"""Scene 1 — the force law (Fig. superkink).

f(w) (red), the superkink's Rayleigh line of slope V_SK² through (w₊, f(w₊)) and (w₋, f(w₋))
with the two equal areas it cuts from f shaded (eq. zero_G), w* and the convex interval (α, β).
In solitary mode also the current Rayleigh line of slope V², and the sonic lines of slopes c₊²
(blue, tangent at w₊) and c₋² (green, tangent at w₋ˢ).  A smooth law (fpucore SmoothLaw) is
drawn only on its represented interval, shaded, whose measured representation error of f, f′,
f″ the status line gives.  QC only: no discrete solve.
"""

from __future__ import annotations

import numpy as np
from bokeh.models import BoxAnnotation, HoverTool, LabelSet

from fpucore import qc
from fpucore.law.smooth import SmoothLaw

from .. import compute
from ..compute.cache import exact
from .bokeh_scene import (
    BokehScene,
    Updates,
    add_band,
    add_label,
    add_legend,
    add_line,
    add_points,
    add_vline,
    new_figure,
)
from .formatting import as_csv, fmt_num, provenance
from .python_code import python_preamble
from .report import Info, SceneMessage


class ForceLawScene(BokehScene):
    title = "Force law"
    caption = (
        "_The force law f(w) with the superkink's Rayleigh line cutting two equal areas "
        "(shaded) and, for solitary waves, the sonic lines and the current Rayleigh line. "
        "Paper: Fig. 1 (superkink)._"
    )
    cheap = True

    def build(self):
        fig = new_figure(
            "Force law f(w) and the Rayleigh lines",
            "w",
            "f(w)",
            sizing_mode="stretch_width",
            height=self.plot_height,
        )
        self.fig = fig
        self.r_areas = [add_band(fig, c) for c in ("#9ecae1", "#fdae6b")]
        self.r_f = add_line(fig, "#d62728", 2.5)
        self.r_sk = add_line(fig, "black", 2)
        self.r_cp = add_line(fig, "#1f77b4", 1.5)
        self.r_cm = add_line(fig, "#2ca02c", 1.5)
        self.r_V = add_line(fig, "#9467bd", 2, "dashed")
        self.r_pts = add_points(fig, "circle", 8, color="black")
        self.r_pts[1].data["label"] = np.empty(0, dtype=object)
        self.r_pts[1].data["what"] = np.empty(0, dtype=object)
        self.r_pts[1].name = "force-special-points"  # read by the tests
        self.r_V[1].name = "force-rayleigh-V"  # read by the browser tests
        self.r_f[1].name = "force-curve"
        # each special point named beside it; hovering gives its role and exact coordinates
        fig.add_layout(
            LabelSet(
                x="x",
                y="y",
                text="label",
                source=self.r_pts[1],
                x_offset=6,
                y_offset=-16,
                text_font_size="10pt",
            )
        )
        fig.add_tools(
            HoverTool(
                renderers=[self.r_pts[0]],
                tooltips=[("", "@label: @what"), ("w", "@x{0.000000}"), ("f", "@y{0.000000}")],
            )
        )
        self.spans = [add_vline(fig, "gray", "dotted") for _ in range(3)]
        for sp, name in zip(self.spans, ("w_star", "alpha", "beta")):
            sp.name = f"force-{name}"  # read by the browser tests
        # a smooth law's represented interval (f, f', f'' from its Chebyshev kernel there)
        self.rep_box = BoxAnnotation(
            left=0.0,
            right=0.0,
            fill_color="#2ca02c",
            fill_alpha=0.07,
            visible=False,
            name="force-represented",
        )
        fig.add_layout(self.rep_box)
        self.rep_label = add_label(fig, color="#2ca02c", align="left")
        self.labels = [add_label(fig) for _ in range(3)]
        self.legend = dict(
            zip(
                ("f", "sk", "cp", "cm", "V"),
                add_legend(
                    fig,
                    "right",
                    [
                        ("f(w)", [self.r_f[0]]),
                        ("Rayleigh line (V_SK)", [self.r_sk[0]]),
                        ("sonic line c₊", [self.r_cp[0]]),
                        ("sonic line c₋", [self.r_cm[0]]),
                        ("Rayleigh line (current V)", [self.r_V[0]]),
                        ("special points (hover: values)", [self.r_pts[0]]),
                    ],
                ),
            )
        )
        return fig

    def render(self, info: Info):
        s = self.state
        lw = s.law()
        alpha, ws, beta = lw.alpha, lw.w_star, lw.beta
        try:
            sk_c = compute.run(lw, compute.QCWaveRequest("superkink", s.w_plus, s.V))
        except compute.ParameterError as exc:
            raise SceneMessage(str(exc)) from None
        sk = sk_c.value
        info.time("QC superkink", sk_c)
        info.error("Rayleigh residual", sk.rayleigh_residual)
        info.error("equal-area residual |G|", sk.driving_force)
        up = Updates()
        law_key = compute.laws.law_key(lw)
        wp_key = law_key + (exact(sk.w_plus),)

        corners = getattr(lw, "breakpoints", None)  # a piecewise-linear law's corners
        if corners is not None:  # α, β often infinite: the corners and the states in view
            near = [
                *corners,
                0.0,
                sk.w_plus,
                sk.w_minus,
                *(x for x in (alpha, beta) if np.isfinite(x)),
            ]
            left, right = min(near), max(near)
        else:  # alpha = −inf (a law hardening for every w < 0): the w₊ window's end instead
            left = alpha if np.isfinite(alpha) else s.w_plus_range()[0]
            right = beta
        span = right - left
        xa, xb = left - 0.06 * span, right + 0.06 * span
        rep = lw.interval if isinstance(lw, SmoothLaw) else None
        if rep is not None:  # f only where it is represented, the whole interval in view
            err = lw.representation_error
            info.error("represented |f − f_rep|", err.f)
            info.error("represented |f′ − f′_rep|", err.df)
            info.error("represented |f″ − f″_rep|", err.ddf)
            xpad = 0.03 * (rep[1] - rep[0])
            xa, xb = min(xa, rep[0] - xpad), max(xb, rep[1] + xpad)
            w = np.linspace(rep[0], rep[1], 801)
        else:
            w = np.linspace(xa, xb, 801)
        if corners is not None:  # each corner sampled exactly: drawn sharp, not cut
            w = np.union1d(w, [c for c in corners if xa <= c <= xb])
        fw = lw.f(w)
        up.data(self.r_f[1], law_key, x=w, y=fw)
        wp, wm = sk.w_plus, sk.w_minus
        fp = float(lw.f(wp))

        # equal areas between f and the superkink Rayleigh line, on each side of w*
        R = lambda x, V: fp + V * V * (x - wp)  # noqa: E731
        for (_, src), lo, hi in zip(
            self.r_areas, (min(wp, ws), min(wm, ws)), (max(wp, ws), max(wm, ws))
        ):
            x = np.linspace(lo, hi, 200)
            up.data(src, wp_key, x=x, y1=lw.f(x), y2=R(x, sk.V))
        x = np.linspace(min(wp, wm), max(wp, wm), 2)
        up.data(self.r_sk[1], wp_key, x=x, y=R(x, sk.V))
        pts = {
            "w": [wp, wm],
            "f": [fp, float(lw.f(wm))],
            "label": ["w₊", "w₋"],
            "what": ["state ahead of the wave", "superkink's state behind (equal areas)"],
        }
        shown = (
            f"superkink construction for w₊ = {fmt_num(wp)}: w₋ = {fmt_num(wm)}, "
            f"V_SK = {fmt_num(sk.V)}"
        )

        if corners is not None:
            slopes = lw.slopes
            names = (
                ("w₁", "w₂")
                if len(corners) == 2
                else tuple(f"b{k + 1}" for k in range(len(corners)))
            )
            for k, (c, name) in enumerate(zip(corners, names)):
                pts["w"].append(c)
                pts["f"].append(float(lw.f(c)))
                pts["label"].append(name)
                pts["what"].append(f"corner: slope {slopes[k]:.6g} → {slopes[k + 1]:.6g}")
            shown += "; corners at " + ", ".join(fmt_num(c) for c in corners)

        solitary = s.mode == "solitary"
        problem = s.problem() if solitary else None
        if solitary:
            cp, vsk, cm = qc.sound_speeds(lw, wp)
            wms = qc.w_minus_sonic(lw, wp)
            xl = np.array([xa, xb])
            up.data(self.r_cp[1], wp_key, x=xl, y=R(xl, cp))
            up.data(self.r_cm[1], wp_key, x=xl, y=R(xl, cm))
            pts["w"].append(wms)
            pts["f"].append(float(lw.f(wms)))
            pts["label"].append("w₋ˢ")
            pts["what"].append("tangency of the c₋ sonic line")
            if problem is None:
                up.data(self.r_V[1], x=xl, y=R(xl, s.V))
                for r in qc.rayleigh_roots(lw, wp, s.V):
                    if np.isfinite(r):
                        # a saddle of the phase plane where V² > f′(w), a centre otherwise
                        saddle = s.V * s.V > float(lw.df(r))
                        pts["w"].append(r)
                        pts["f"].append(float(lw.f(r)))
                        pts["label"].append("w_S" if saddle else "w_C")
                        pts["what"].append(
                            "saddle: Rayleigh line meets f, V² > f′"
                            if saddle
                            else "centre: Rayleigh line meets f, V² < f′"
                        )
                shown += f"; current V = {fmt_num(s.V)} in " + (
                    "(c₊, V_SK)" if s.V < vsk else "(V_SK, c₋)"
                )
            else:
                info.warning = f"current V not drawn: {problem}"
        for name in ("cp", "cm"):
            up.show(getattr(self, f"r_{name}")[0], self.legend[name], solitary)
        up.show(self.r_V[0], self.legend["V"], solitary and problem is None)
        up.set(
            self.r_pts[1],
            data={
                "x": np.asarray(pts["w"], float),
                "y": np.asarray(pts["f"], float),
                "label": np.asarray(pts["label"], dtype=object),
                "what": np.asarray(pts["what"], dtype=object),
            },
        )

        ymin, ymax = float(np.min(fw)), float(np.max(fw))
        pad = 0.08 * (ymax - ymin)
        for sp, lab, x0, text in zip(self.spans, self.labels, (ws, alpha, beta), ("w*", "α", "β")):
            if not np.isfinite(x0):  # α = −∞ / β = +∞: at the edge, said so
                x0, text = (float(w[0]), "α = −∞ ←") if x0 < 0 else (float(w[-1]), "β = +∞ →")
            up.set(sp, location=float(x0))
            up.set(lab, x=float(x0), y=ymax + 0.5 * pad, text=text)
        up.set(self.rep_box, visible=rep is not None)
        up.set(self.rep_label, visible=rep is not None)
        if rep is not None:
            up.set(self.rep_box, left=float(rep[0]), right=float(rep[1]))
            text = f"represented [{fmt_num(rep[0])}, {fmt_num(rep[1])}]"
            up.set(self.rep_label, x=float(rep[0]), y=ymin - 0.7 * pad, text=text)
            shown += f"; f represented on [{fmt_num(rep[0])}, {fmt_num(rep[1])}]"
        up.range(self.fig.x_range, xa, xb)
        up.range(self.fig.y_range, ymin - pad, ymax + pad)
        info.shown = shown
        self._data = {"w": w, "f": fw, "R_SK": R(w, sk.V)}
        self._header = shown
        return up

    def download_data(self):
        if not getattr(self, "_data", None):
            raise SceneMessage("nothing shown yet")
        hdr = provenance(self.state, self._header) + "\n" + self.python_code()
        return "force_law.csv", as_csv(self._data, hdr)

    def notebook_plot(self) -> str:
        return (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            "w = np.linspace(law.alpha - 0.5, law.beta + 0.5, 801) if np.isfinite(law.alpha) "
            "else np.linspace(sk.w_minus - 1, law.beta + 1, 801)\n"
            "x = np.array([sk.w_plus, sk.w_minus])\n"
            "fig, ax = plt.subplots(figsize=(8, 4.5))\n"
            "ax.plot(w, law.f(w), label='f(w)')\n"
            "ax.plot(x, law.f(sk.w_plus) + sk.V**2 * (x - sk.w_plus), 'r--', "
            "label=f'Rayleigh line V = {sk.V:.6g}')\n"
            "ax.plot(x, law.f(x), 'ko')\n"
            "ax.set(xlabel='w', ylabel='f(w)', title='force law and the superkink')\n"
            "ax.legend()\n"
        )

    def python_code(self) -> str:
        s = self.state
        code = python_preamble(s) + (
            f"sk = {compute.QCWaveRequest('superkink', s.w_plus, s.V).call().code()}"
            "  # equal areas, V_SK\n"
            "print(sk.V, sk.w_minus, sk.rayleigh_residual)\n"
        )
        if s.mode == "solitary":
            code += f"print(qc.sound_speeds(law, {float(s.w_plus)!r}))  # c+, V_SK, c-\n"
        return code
