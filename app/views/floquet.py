"""Scene 5 — Floquet spectrum (paper's Figs. floquet_SK, Floquet_example, floquet_cubicSW).

(a) the 2N multipliers μ (blue ×) of the discrete wave at the current parameters with the unit
circle drawn over them (red); (b) a zoom on the multiplier of largest modulus away from the
trivial cluster at μ = 1, where instability quartets (|μ| − 1 beyond the error bar, red rings)
show; (c) on demand, max |μ| − 1 against V for the family on a log axis (the paper's
O(1e-8 … 1e-3) structure), points coloured by the stability decision, V_SK dashed, the current
V marked and, for a solitary family, the extrema of E_ren(V) (energy criterion: from the sweep's
own waves, solid, and the QC family, dotted) with the cross-check of the decisions against them
in one line; (d) the decision's evidence, max |μ| − 1 on the window of rings in [N/2, N].
Headline and sentence of the status are the decision record's (fpucore.floquet.Decision).

The four figures are built once, in the order (a), (b), (c), (d); panel (c) is hidden until a
sweep exists and (d) while the finite-size test has not run (their visibility changes, the layout
does not).  (a) and (b) have fixed square frames that never stretch or shrink with the page: the
unit circle stays a circle; when the column is too narrow for both, (b) wraps below (a).
Spectrum and sweep run in worker processes.
"""

from __future__ import annotations

import numpy as np
import panel as pn
from bokeh.layouts import column, row
from bokeh.models import BoxZoomTool, NoOverlap, Whisker

from fpucore import qc
from fpucore.floquet import CLASSES, changes_summary

from .. import compute
from ..paper_figures import FIGURE_PARTS
from .bokeh_scene import (
    BokehScene,
    Updates,
    add_legend,
    add_line,
    add_points,
    add_vline,
    finite_extent,
    new_figure,
)
from .class_style import CLASS_STYLE
from .energy_marks import ExtremumMarks, criterion_words, fmt_extremum
from .floquet_files import FloquetFiles
from .formatting import fmt_num
from .report import Info, SceneMessage
from .untrusted import md_literal

TH = np.linspace(0.0, 2.0 * np.pi, 721)
#: side of the square frames of (a) and (b) (px): both fit side by side in the main column of a
#: 1500 px wide window (800 px); narrower, (b) wraps below (a)
SQUARE_PX = 300


def square_figure(title: str):
    """A figure of the complex plane whose frame is SQUARE_PX × SQUARE_PX whatever the layout
    (with equal x and y spans, a circle is drawn as a circle).

    A figure with ``frame_width``/``frame_height`` alone has BokehJS's "fit" policy, which a
    flex row grows or shrinks (the unit circle became an ellipse); the "fixed" policy without
    an outer ``width``/``height`` keeps the frame's size.  Box zoom keeps the aspect too."""
    fig = new_figure(
        title,
        "Re μ",
        "Im μ",
        frame_width=SQUARE_PX,
        frame_height=SQUARE_PX,
        width=None,
        height=None,
        width_policy="fixed",
        height_policy="fixed",
        tools=["pan", "wheel_zoom", BoxZoomTool(match_aspect=True), "save", "reset"],
    )
    for axis in (fig.xaxis, fig.yaxis):
        # a label closer than 10 px to the previous one is not drawn (never run together)
        axis.major_label_policy = NoOverlap(min_distance=10)
    return fig


class FloquetScene(FloquetFiles, BokehScene):
    title = "Floquet stability"
    caption = (
        "_Floquet multipliers of the discrete traveling wave: a multiplier outside the unit "
        "circle (beyond its error bar) means a linear instability. Paper: Figs. 11, 12 and 15 "
        "(floquet_SK, Floquet_example, floquet_cubicSW)._"
    )
    plot_height = 340
    depends = (*BokehScene.depends, "figure")  # a figure's click runs its sweep

    def controls(self):
        # the total: a solitary sweep shares it between its two intervals (_sweep_values)
        self.n_sweep = pn.widgets.IntInput(
            label="velocities in the sweep (total)", value=12, start=3, end=80, width=200
        )
        self.sweep_btn = pn.widgets.Button(
            label="Sweep max |μ| against V", color="primary", css_classes=["floquet-sweep"]
        )
        return [self.n_sweep, self.sweep_btn]

    def __init__(self, state):
        super().__init__(state)
        self._want_sweep = False
        self._fr = self._r = self._sweep_result = None
        self.sweep_btn.on_click(self._on_sweep)

    def _on_sweep(self, _) -> None:
        self._want_sweep = True
        self.request()

    def build(self):
        fa = square_figure("(a) Floquet multipliers μ in the complex plane")
        fb = square_figure("(b) zoom")
        # (b)'s labels carry 5–8 significant digits: few ticks, and a label that would touch
        # its neighbour is left out rather than drawn over it
        fb.xaxis.ticker.desired_num_ticks = 4
        fc = new_figure(
            "(c) largest |μ| − 1 against V along the family",
            "V",
            "max |μ| − 1",
            sizing_mode="stretch_width",
            height=260,
            y_axis_type="log",
        )
        self.fig_a, self.fig_b, self.fig_c = fa, fb, fc
        # markers first, unit circle after: drawn over the 2N crosses (visible at N = 500)
        self.r_mu = add_points(fa, "x", 7, color="#1f77b4", line_width=1.5)
        self.r_unst = add_points(fa, "circle", 14, fill_alpha=0.0, line_color="#d62728")
        self.r_circle = add_line(fa, "#d62728", 1.5)
        self.r_zmu = add_points(fb, "x", 10, color="#1f77b4", line_width=2)
        self.r_zunst = add_points(fb, "circle", 18, fill_alpha=0.0, line_color="#d62728")
        self.r_zcircle = add_line(fb, "#d62728", 1.5)
        self.r_mu[1].name = "floquet-multipliers"  # read by the browser tests
        for _, src_c in (self.r_circle, self.r_zcircle):
            src_c.data = {"x": np.cos(TH), "y": np.sin(TH)}
        self.legend_a = add_legend(
            fa,
            "below",
            [
                ("multipliers μ", [self.r_mu[0]]),
                ("|μ| − 1 beyond error", [self.r_unst[0]]),
                ("unit circle", [self.r_circle[0]]),
            ],
        )
        self.r_sw = add_line(fc, "#9e9e9e", 1)
        self.r_sw[1].name = "floquet-sweep"
        # one renderer per decision: the legend names the colours
        self.r_cls = {c: add_points(fc, "circle", 7, color=CLASS_STYLE[c][1]) for c in CLASSES}
        for c, (_, src) in self.r_cls.items():
            src.name = f"floquet-sweep-{c}"
        self.sw_V = add_vline(fc, "black")
        self.sw_vsk = add_vline(fc, "#d62728", "dashed")
        self.ext_d = ExtremumMarks(fc, "#ff7f0e", "solid", "floquet-energy-extremum")
        self.ext_q = ExtremumMarks(fc, "#ff7f0e", "dotted", "floquet-energy-extremum-qc")
        self.sw_legend = add_legend(
            fc,
            "right",
            [
                ("max |μ| − 1", [self.r_sw[0]]),
                ("E_ren extremum (sweep's waves)", self.ext_d.renderers),
                ("E_ren^QC extremum", self.ext_q.renderers),
            ]
            + [(CLASS_STYLE[c][0], [self.r_cls[c][0]]) for c in CLASSES],
        )
        fc.visible = False
        # (d) the decision's evidence: max|μ| − 1 ± error on the window of rings in [N/2, N]
        fd = new_figure(
            "(d) finite-size window: largest |μ| − 1 against the chain size N",
            "N",
            "max |μ| − 1",
            sizing_mode="stretch_width",
            height=240,
        )
        self.fig_d = fd
        self.r_fs = add_points(fd, "circle", 8, color="#ff7f0e")
        self.r_fs[1].data = {"x": [], "y": [], "hi": [], "lo": []}
        self.r_fs[1].name = "floquet-finite-size"
        fd.add_layout(
            Whisker(source=self.r_fs[1], base="x", upper="hi", lower="lo", line_color="#ff7f0e")
        )
        add_legend(fd, "right", [("max |μ| − 1 ± error", [self.r_fs[0]])])
        fd.visible = False
        # flex-wrap: the fixed-size (a) and (b) wrap instead of being squeezed (row's default)
        squares = row(fa, fb, styles={"flex-wrap": "wrap"})
        return column(squares, fc, fd, sizing_mode="stretch_width")

    def _sweep_values(self):
        s = self.state
        lw = s.law()
        k = int(self.n_sweep.value or 12)  # the total number of velocities

        def midpoints(lo, hi, n):
            return lo + (hi - lo) * (np.arange(n) + 0.5) / n

        if s.mode == "superkink":
            Vs = midpoints(*qc.superkink_velocity_bounds(lw), k)
            return "superkink", None, Vs, None, ("lower" if s.w_plus < lw.w_star else "upper")
        # solitary: tensile (c₊, V_SK) and compressive (V_SK, c₋) share the k velocities, the
        # odd one to the tensile interval
        (cp, vsk), (_, cm) = qc.solitary_intervals(lw, s.w_plus)
        Vs = np.concatenate([midpoints(cp, vsk, k - k // 2), midpoints(vsk, cm, k // 2)])
        return "solitary", s.w_plus, Vs, vsk, "lower"

    def _sweep(self, info: Info, up: Updates) -> bool:
        s = self.state
        kind, wp, Vs, vsk, branch = self._sweep_values()
        lw, req = s.law(), compute.SweepRequest(kind, wp, Vs, s.N, branch)
        wanted = self._want_sweep or FIGURE_PARTS.get(s.figure) == "sweep"
        if not wanted and not compute.is_cached(lw, req):
            self._sweep_result = self._ec = None
            return False
        self._want_sweep = False
        c = compute.run(lw, req, **self.job_hooks(progress=self.set_progress))
        sw = c.value
        info.time(f"sweep ({len(Vs)} V)", c)
        self._sweep_result = sw
        mm, err = np.asarray(sw.max_modulus, float), np.asarray(sw.max_modulus_error, float)
        ok = np.isfinite(mm) & np.isfinite(err)
        # max|μ| − 1 on a log axis; a point within its error bar is drawn at the bar (a bound)
        y = np.maximum(mm - 1.0, np.maximum(err, 1e-16))
        up.data(self.r_sw[1], x=sw.V[ok], y=y[ok])
        cls = np.array([c or "" for c in sw.classification])
        for c, (r, src) in self.r_cls.items():
            sel = ok & (cls == c)
            up.data(src, x=sw.V[sel], y=y[sel])
            up.show(r, self.sw_legend[3 + CLASSES.index(c)], bool(sel.any()))
        up.set(self.sw_V, location=float(s.V))
        x_sk = float(vsk if vsk is not None else s.V)
        up.set(self.sw_vsk, location=x_sk, visible=vsk is not None)
        up.range(self.fig_c.x_range, float(np.min(sw.V)), float(np.max(sw.V)), pad=0.04)
        lo = float(np.min(y[ok])) / 3.0 if ok.any() else 1e-12
        hi = float(np.max(y[ok])) * 3.0 if ok.any() else 1e-2
        up.range(self.fig_c.y_range, lo, hi)
        self._energy_criterion(info, up, kind, wp, Vs, (lo, hi))
        # a velocity left out of (c): its wave did not converge, or it was never computed (a
        # sweep stopped early) — two different statements
        lost = np.array([r["status"] == "not_converged" and not r["converged"] for r in sw.rows])
        if (~ok & lost).any():
            k = int((~ok & lost).sum())
            info.notes.append(
                f"sweep: {k} velocit{'y' if k == 1 else 'ies'} did not converge (not drawn)"
            )
        if (~ok & ~lost).any():
            why = {
                str(r.get("message") or "not computed") for r, k in zip(sw.rows, ~ok & ~lost) if k
            }
            info.notes.append(
                f"sweep: {int((~ok & ~lost).sum())} of {len(sw.rows)} velocities "
                f"not computed (not drawn): {md_literal('; '.join(sorted(why))[:200])}"
            )
        return True

    def _energy_criterion(self, info: Info, up: Updates, kind, wp, Vs, ylim) -> None:
        """(c): extrema of E_ren along the swept solitary family (the sweep's own waves and the
        QC family) and the cross-check of the sweep's classifications against them."""
        s = self.state
        self._ec = None
        c = None
        if kind == "solitary":  # the sweep's own request (_sweep: the solitary one is "lower")
            req = compute.SweepRequest(kind, wp, Vs, s.N, "lower")
            c = compute.run(s.law(), compute.SampledEnergyRequest(req))
        if c is None:
            for marks, item in ((self.ext_d, self.sw_legend[1]), (self.ext_q, self.sw_legend[2])):
                marks.update(up, [], [], (), *ylim, item)
            if kind != "solitary":
                info.notes.append("energy criterion: for solitary-wave families only")
            return
        ec, changes = self._ec = c.value
        info.time("energy criterion", c)
        for marks, item, V, dV, kinds, what in (
            (
                self.ext_d,
                self.sw_legend[1],
                ec.extrema_V,
                ec.extrema_V_error,
                ec.extrema_kind,
                "E_ren (sweep's waves)",
            ),
            (
                self.ext_q,
                self.sw_legend[2],
                ec.qc_extrema_V,
                ec.qc_extrema_V_error,
                ec.qc_extrema_kind,
                "E_ren^QC",
            ),
        ):
            marks.update(up, V, dV, kinds, *ylim, item)
            if len(V):
                text = "; ".join(fmt_extremum(k, v, d) for k, v, d in zip(kinds, V, dV))
                up.set(item, label={"value": f"{what} {text}"})
        if ec.location_error > 0:
            info.error("E_ren extremum location", ec.location_error)
        if len(ec.extrema_V) == 0 and len(ec.qc_extrema_V) == 0:
            info.notes.append(
                "Energy criterion: E_ren(V) has no minimum or maximum, neither along the sweep's "
                "discrete waves nor in the QC family between c₊ and c₋, so along this family "
                "the stability cannot change through its translation mode."
            )
        else:
            info.notes.append(
                criterion_words(
                    ec.extrema_V,
                    ec.extrema_V_error,
                    ec.extrema_kind,
                    "the sweep's discrete waves",
                    "that the swept velocities resolve (more may find one)",
                )
                + " "
                + criterion_words(
                    ec.qc_extrema_V,
                    ec.qc_extrema_V_error,
                    ec.qc_extrema_kind,
                    "the QC family",
                    "between c₊ and c₋",
                )
            )
        # the cross-check in one line (fpucore.floquet.changes_summary)
        info.notes.append(f"Cross-check with the energy criterion: {changes_summary(changes)}")

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        self._fr = self._r = None
        req = compute.WaveRequest(s.mode, s.w_plus, s.V, s.N, s.tol)
        spectrum = compute.SpectrumRequest(req)
        rc, fc = compute.run(s.law(), spectrum, **self.job_hooks(progress=self.set_progress)).value
        r = rc.value
        info.time(f"discrete wave N={r.N}", rc)
        info.error("wave residual", r.residual)
        if not r.converged or fc is None:
            raise SceneMessage(
                f"The discrete wave at N = {r.N} did not converge, so it has no Floquet spectrum "
                f"to show: {r.message} Try a larger N (accuracy card) or a V farther from the "
                "limits."
            )
        fr = fc.value
        info.time("Floquet", fc)
        info.error("quartet symmetry", fr.symmetry_error)
        info.error("integrator", fr.integrator_error)
        up = Updates()
        mu = np.asarray(fr.multipliers)
        unstable = np.asarray(fr.unstable)
        key = compute.job_key(s.law(), spectrum)
        up.data(self.r_mu[1], key, x=mu.real, y=mu.imag)
        up.data(self.r_unst[1], key, x=unstable.real, y=unstable.imag)
        up.show(self.r_unst[0], self.legend_a[1], unstable.size > 0)
        ext = max(1.1, float(np.max(np.abs(mu))) * 1.05) if mu.size else 1.1
        up.range(self.fig_a.x_range, -ext, ext)
        up.range(self.fig_a.y_range, -ext, ext)
        # zoom: around the multiplier of largest modulus away from the trivial cluster at 1
        away = mu[np.abs(mu - 1.0) > 1e-3] if mu.size else mu
        focus = away[np.argmax(np.abs(away))] if away.size else 1.0 + 0j
        r0 = max(4.0 * (abs(focus) - 1.0), 20.0 * max(fr.symmetry_error, 1e-9), 1e-6)
        near = np.abs(mu - focus) < 6 * r0
        zu = unstable[np.abs(unstable - focus) < 6 * r0] if unstable.size else unstable
        up.data(self.r_zmu[1], key, x=mu.real[near], y=mu.imag[near])
        up.data(self.r_zunst[1], key, x=zu.real, y=zu.imag)
        up.range(self.fig_b.x_range, focus.real - 3 * r0, focus.real + 3 * r0)
        up.range(self.fig_b.y_range, focus.imag - 3 * r0, focus.imag + 3 * r0)
        up.set(self.fig_b.title, text=f"(b) zoom near μ = {focus.real:.6f}{focus.imag:+.6f}i")
        self._fr, self._r = fr, r
        info.shown = (
            f"{r.kind} wave V = {fmt_num(r.V)}, N = {r.N}: {len(mu)} multipliers, "
            f"max |μ| = {fr.max_modulus:.10f}, away from 1: {fr.max_modulus_away_from_1:.10f} — "
            f"**{fr.decision.headline}**: {fr.decision.evidence}"
        )
        self._finite_size(fr, up)
        shown = self._sweep(info, up)
        up.set(self.fig_c, visible=shown)
        if not shown:
            info.notes.append("max |μ| against V: press 'Sweep'")
        return up

    def _finite_size(self, fr, up: Updates) -> None:
        """(d): the window behind the decision (hidden when the test did not run)."""
        Ns = np.asarray(fr.finite_size_N, float)
        ex = np.asarray(fr.finite_size_excess, float)
        er = np.asarray(fr.finite_size_error, float)
        ok = np.isfinite(ex) & np.isfinite(er)
        shown = bool(ok.sum() >= 2)
        up.set(self.fig_d, visible=shown)
        if not shown:
            up.set(self.r_fs[1], data={"x": [], "y": [], "hi": [], "lo": []})
            return
        Ns, ex, er = Ns[ok], ex[ok], er[ok]
        up.set(self.r_fs[1], data={"x": Ns, "y": ex, "hi": ex + er, "lo": ex - er})
        up.range(self.fig_d.x_range, 0.0, float(Ns.max()), pad=0.05)
        up.range(self.fig_d.y_range, *finite_extent(ex - er, ex + er, [0.0]), pad=0.1)
        d = fr.decision
        title = f"(d) finite-size window: max |μ| − 1 on rings N = {int(Ns[0])} … {int(Ns[-1])}"
        # the envelope's exponent only beside the verdict it supports (a decay): beside "not
        # determined" it read as a result; "" for a fit without an error bar below its value
        fit = d.fit_words("±") if d.reason == "decays" else ""
        if fit:
            title += f"; upper envelope ∝ N^−p, {fit}"
        up.set(self.fig_d.title, text=title)
