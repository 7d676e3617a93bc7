"""Scene 5 — Floquet spectrum (Figs. floquet_SK, Floquet_example, floquet_cubicSW).

(a) the 2N multipliers μ (blue ×) of the discrete wave at the current parameters with the unit
circle (red); (b) a zoom on the multiplier of largest modulus away from the trivial cluster at
μ = 1, where instability quartets (|μ| beyond the error bar, red) show; (c) on demand,
max |μ| against V for the family, V_SK dashed.
"""

from __future__ import annotations

import holoviews as hv
import numpy as np
import panel as pn

from fpucore import qc

from .. import compute
from .base import Info, Scene, SceneMessage, as_csv, as_json, fmt_num


class FloquetScene(Scene):
    key = "floquet"
    title = "Floquet"
    plot_height = 520

    def controls(self):
        self.n_sweep = pn.widgets.IntInput(
            label="velocities in the sweep", value=12, start=3, end=80, width=200
        )
        self.sweep_btn = pn.widgets.Button(
            label="Sweep max |μ| against V", color="primary", css_classes=["floquet-sweep"]
        )
        return [self.n_sweep, self.sweep_btn]

    def _extra_watch(self):
        self._want_sweep = False

        def go(_):
            self._want_sweep = True
            self.request()

        self.sweep_btn.on_click(go)

    def _sweep_values(self):
        s = self.state
        lw = s.law()
        k = int(self.n_sweep.value)
        if s.mode == "superkink":
            lo, hi = qc.superkink_velocity_bounds(lw)
            Vs = lo + (hi - lo) * (np.arange(k) + 0.5) / k
            return "superkink", None, Vs, None, ("lower" if s.w_plus < lw.w_star else "upper")
        (cp, vsk), (_, cm) = qc.solitary_intervals(lw, s.w_plus)
        t = (np.arange(k) + 0.5) / k
        Vs = np.concatenate([cp + (vsk - cp) * t, vsk + (cm - vsk) * t])
        return "solitary", s.w_plus, Vs, vsk, "lower"

    def _sweep(self, info: Info):
        s = self.state
        kind, wp, Vs, vsk, branch = self._sweep_values()
        key = (
            "fsweep",
            compute.rnd(s.a),
            compute.rnd(s.b),
            kind,
            None if wp is None else compute.rnd(wp),
            tuple(compute.rnd(v) for v in Vs),
            int(s.N),
            branch,
        )
        if compute.CACHE.peek(key) is None and not self._want_sweep:
            return None
        self._want_sweep = False

        def progress(*args):
            if len(args) >= 2:
                self.set_progress(int(args[0]), int(args[1]))

        c = compute.floquet_sweep(s.a, s.b, kind, wp, Vs, s.N, branch=branch, progress=progress)
        sw = c.value
        info.time(f"sweep ({len(Vs)} V)", c)
        self._sweep_result = sw
        items = [
            hv.Curve((sw.V, sw.max_modulus), "V", "max |μ|", label="max |μ|").opts(
                color="#1f77b4", line_width=2
            ),
            hv.Scatter((sw.V, sw.max_modulus), "V", "max |μ|").opts(color="#1f77b4", size=6),
            hv.ErrorBars((sw.V, sw.max_modulus, sw.error), "V", ["max |μ|", "err"]),
            hv.VLine(s.V).opts(color="black"),
        ]
        if vsk is not None:
            items.append(hv.VLine(vsk).opts(color="#d62728", line_dash="dashed"))
        return hv.Overlay(items).opts(
            title="(c) max |μ| against V", frame_width=420, frame_height=220, show_grid=True
        )

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        rc, fc = compute.floquet_spectrum(s.a, s.b, s.mode, s.w_plus, s.V, s.N, s.tol)
        r, fr = rc.value, fc.value
        info.time(f"discrete N={r.N}", rc)
        info.time("Floquet", fc)
        info.error("wave residual", r.residual)
        info.error("quartet symmetry", fr.symmetry_error)
        info.error("integrator", fr.integrator_error)
        if not r.converged:
            raise SceneMessage(f"the discrete wave did not converge: {r.message}")
        mu = np.asarray(fr.multipliers)
        unstable = np.asarray(fr.unstable)
        th = np.linspace(0, 2 * np.pi, 721)
        circle = hv.Curve((np.cos(th), np.sin(th)), "Re μ", "Im μ").opts(color="#d62728")
        pts = hv.Scatter((mu.real, mu.imag), "Re μ", "Im μ", label="μ").opts(
            marker="x", color="#1f77b4", size=8
        )
        items = [circle, pts]
        if unstable.size:
            items.append(
                hv.Scatter(
                    (unstable.real, unstable.imag), "Re μ", "Im μ", label="|μ| > 1 beyond error"
                ).opts(marker="circle", fill_alpha=0, line_color="#d62728", size=14)
            )
        full = hv.Overlay(items).opts(
            title="(a) Floquet multipliers",
            frame_width=300,
            frame_height=300,
            data_aspect=1,
            show_grid=True,
            legend_position="bottom_left",
        )
        # zoom: around the multiplier of largest modulus away from the trivial cluster at 1
        away = mu[np.abs(mu - 1.0) > 1e-3] if mu.size else mu
        focus = away[np.argmax(np.abs(away))] if away.size else 1.0 + 0j
        r0 = max(4.0 * (abs(focus) - 1.0), 20.0 * max(fr.symmetry_error, 1e-9), 1e-6)
        near = np.abs(mu - focus) < 6 * r0
        zoom = hv.Overlay(
            [
                hv.Curve((np.cos(th), np.sin(th)), "Re μ", "Im μ").opts(color="#d62728"),
                hv.Scatter((mu.real[near], mu.imag[near]), "Re μ", "Im μ").opts(
                    marker="x", color="#1f77b4", size=10
                ),
            ]
            + ([items[-1]] if unstable.size else [])
        ).opts(
            title=f"(b) zoom near μ = {focus.real:.6f}{focus.imag:+.6f}i",
            xlim=(focus.real - 3 * r0, focus.real + 3 * r0),
            ylim=(focus.imag - 3 * r0, focus.imag + 3 * r0),
            frame_width=300,
            frame_height=300,
            show_grid=True,
        )
        self._fr, self._r = fr, r
        info.shown = (
            f"{r.kind} V = {fmt_num(r.V)}, N = {r.N}: max |μ| = {fr.max_modulus:.10f}, "
            f"away from 1: {fr.max_modulus_away_from_1:.10f} — {fr.verdict}"
        )
        layout = full + zoom
        sweep = self._sweep(info)
        if sweep is not None:
            layout = layout + sweep
        else:
            info.notes.append("max |μ| vs V: press 'Sweep'")
        return layout.cols(2).opts(shared_axes=False)

    def download_data(self):
        fr = getattr(self, "_fr", None)
        if fr is None:
            raise SceneMessage("nothing shown yet")
        mu = np.asarray(fr.multipliers)
        out = {
            "V": self._r.V,
            "N": self._r.N,
            "kind": self._r.kind,
            "multipliers_re": mu.real,
            "multipliers_im": mu.imag,
            "max_modulus": fr.max_modulus,
            "symmetry_error": fr.symmetry_error,
            "integrator_error": fr.integrator_error,
            "verdict": fr.verdict,
        }
        sw = getattr(self, "_sweep_result", None)
        if sw is not None:
            out["sweep"] = {"V": sw.V, "max_modulus": sw.max_modulus, "error": sw.error}
        return "floquet.json", as_json(out)


_ = as_csv
