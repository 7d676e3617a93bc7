"""Scene 4 — velocity–amplitude and velocity–energy diagrams, and the existence diagram.

(a) amplitude |w(0) − w_B| and (b) renormalized energy E_ren against V for the current w₊
(Figs. SWamp_energy_QCcubic, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC): QC curves (closed form),
discrete dots on demand, V_SK dashed red, sonic limits c₊ (blue) and c₋ (green), current V
marked; on (b) the extrema of E_ren^QC (and of the discrete E_ren once its dots are computed),
where by the energy criterion the family's stability can change.  (c) the existence diagram
V vs w₊ (Fig. SWvelocities_cubic) with TSW (dark) and CSW
(light) regions; a click picks (w₊, V).

Branch view (Figs. floquet_cubicSW, stabSW as MatCont/AUTO draw branches): on demand the Floquet
sweep of the family at the discrete velocities classifies each wave (stable, finite-size
artefact, unstable, not determined: fpucore.floquet's decision); its discrete E_ren is drawn on
(b) in the class's colour, and a click on a point makes that wave the current one (V).
In superkink mode the button sweeps the superkink family instead (Fig. floquet_SK: velocities
over the superkink interval of the current law, on the current w₊'s branch), drawn on (d) as the
amplitude |w₋ − w₊| against V in the class's colour — a superkink has no E_ren (it joins two
different states: eq. Eren_D's renormalization is the solitary waves') — and a click on a point
sets V, and w₊ with it (V = V_SK(w₊)).
"""

from __future__ import annotations

from contextlib import nullcontext

import numpy as np
import panel as pn
from bokeh.events import Tap
from bokeh.layouts import column, row
from panel.io.state import set_curdoc

from .. import compute
from ..compute.cache import exact
from ..paper_figures import FIGURE_PARTS
from .bokeh_scene import (
    BokehScene,
    FigurePane,
    Updates,
    add_band,
    add_label,
    add_legend,
    add_line,
    add_points,
    add_vline,
    finite_extent,
    new_figure,
)
from .branch_views import BranchViews
from .class_style import class_points
from .diagram_files import DiagramFiles
from .energy_marks import ExtremumMarks, criterion_words, fmt_extremum
from .formatting import fmt_num
from .report import Info, SceneMessage
from .untrusted import LiteralMarkdown, md_literal

TSW, CSW = "#6a51a3", "#cbc9e2"
CSW_LINE = "#9e9ac8"


class DiagramScene(DiagramFiles, BranchViews, BokehScene):
    title = "Amplitude, energy, existence"
    caption = (
        "_Amplitude and renormalized energy of the solitary waves against their velocity "
        "(quasicontinuum curves, discrete dots on demand), and where tensile and compressive "
        "solitary waves exist. Paper: Figs. 4, 6, 9 and 10 (SWvelocities_cubic, "
        "SWamp_energy_QCcubic, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC)._"
    )
    cheap = True
    plot_height = 300
    depends = (*BokehScene.depends, "figure")  # a figure's click adds its discrete dots
    pane_kw: dict = {}

    def controls(self):
        self.n_discrete = pn.widgets.IntInput(
            label="discrete points per interval", value=6, start=2, end=40, width=200
        )
        self.discrete_btn = pn.widgets.Button(
            label="Add discrete points", color="primary", css_classes=["diagram-discrete"]
        )
        hint = LiteralMarkdown("_Click the existence diagram (c) to pick (w₊, V)._")
        self.classify_btn = pn.widgets.Button(
            label="Classify stability (Floquet)", css_classes=["diagram-classify"]
        )
        branch = LiteralMarkdown(
            "_Branch view: the Floquet sweep at the same velocities colours the discrete E_ren "
            "on (b) by stability (in superkink mode: the superkinks over their velocity "
            "interval, on (d)); click a point to open that wave._"
        )
        return [hint, self.n_discrete, self.discrete_btn, branch, self.classify_btn]

    def __init__(self, state):
        super().__init__(state)
        self._want_discrete = False
        self._want_branch = False
        self._branch = None
        self._sk_branch = None  # (SweepResult, amplitudes, branch) of the superkink family
        self.discrete_btn.on_click(self._on_discrete)
        self.classify_btn.on_click(self._on_classify)

    def _on_discrete(self, _) -> None:
        self._want_discrete = True
        self.request()

    def _on_classify(self, _) -> None:
        self._want_branch = True
        self.request()

    def extra_panes(self):
        """The existence diagram has its own pane; a click on it picks (w₊, V)."""
        self.exist_pane = FigurePane(None, css_classes=["existence-diagram"])
        return [self.exist_pane]

    def build(self):
        size = dict(frame_width=340, frame_height=240)
        fa = new_figure("(a) amplitude against velocity", "V", "amplitude", **size)
        fe = new_figure("(b) renormalized energy against velocity", "V", "E_ren", **size)
        self.fig_a, self.fig_e = fa, fe
        # per panel: QC below / above V_SK, current point, discrete dots, and the V lines
        self.panels = {}
        for name, fig in (("amp", fa), ("en", fe)):
            self.panels[name] = {
                "qc": [add_line(fig, TSW, 2.5) for _ in range(2)],
                "cur": add_points(fig, "diamond", 10, color="black"),
                "dots": add_points(fig, "circle", 6, color="black"),
                "spans": [
                    add_vline(fig, "#d62728", "dashed"),
                    add_vline(fig, "#1f77b4", "dotted"),
                    add_vline(fig, "#2ca02c", "dotted"),
                ],
                "V": add_vline(fig, "black"),
            }
        # energy criterion on (b): extrema of E_ren^QC (solid) and of the discrete dots (dashed)
        self.ext_qc = ExtremumMarks(fe, "#ff7f0e", "solid", "diagram-energy-extremum-qc")
        self.ext_d = ExtremumMarks(fe, "#8c564b", "dashed", "diagram-energy-extremum-discrete")
        self.ext_legend = add_legend(
            fe,
            "below",
            [("E_ren^QC extremum", self.ext_qc.renderers),
             ("discrete E_ren extremum", self.ext_d.renderers)],
        )  # fmt: skip
        # branch view: the sweep's waves on (b), one renderer per stability class
        self.r_branch, self.branch_legend = class_points(fe, "diagram-branch")
        fe.on_event(Tap, self._on_branch_tap)
        pa = self.panels["amp"]
        self.amp_legend = add_legend(
            fa,
            "below",
            [("QC below", [pa["qc"][0][0]]), ("QC above", [pa["qc"][1][0]])]
            + [("discrete", [pa["dots"][0]])],
        )

        fc = new_figure(
            "(c) where solitary waves exist — click to pick (w₊, V)",
            "w₊",
            "V",
            frame_width=620,
            frame_height=300,
        )
        self.fig_c = fc
        # bands (c₊, V_SK) and (V_SK, c₋) left and right of w*: TSW below V_SK on the left,
        # above it on the right (Fig. SWvelocities_cubic)
        self.bands = [add_band(fc, color, 0.8) for color in (TSW, CSW, CSW, TSW)]
        self.exist_lines = [
            add_line(fc, "#d62728", 2),
            add_line(fc, "#1f77b4", 1),
            add_line(fc, "#2ca02c", 1),
        ]
        self.exist_label = add_label(fc, color="black", size="9pt", align="left")
        self.exist_point = add_points(fc, "circle", 11, color="black")
        self.exist_point[1].name = "diagram-current"  # read by the browser tests
        add_legend(
            fc,
            "right",
            [
                (lab, [r])
                for lab, (r, _) in zip(
                    ("V_SK", "c₊", "c₋", "current"), [*self.exist_lines, self.exist_point]
                )
            ],
        )
        fc.on_event(Tap, self._on_tap)
        # (d) the superkink branch view (superkink mode, after "Classify")
        fs = new_figure(
            "(d) superkinks by Floquet class — click a point to open it",
            "V",
            "amplitude |w₋ − w₊|",
            frame_width=620,
            frame_height=220,
        )
        self.fig_sk = fs
        self.sk_line = add_line(fs, "#d62728", 1.5)  # eq. wpm_cubic over the interval
        self.sk_V = add_vline(fs, "black")
        self.r_sk, self.sk_legend = class_points(fs, "diagram-sk-branch")
        fs.on_event(Tap, self._on_sk_tap)
        fs.visible = False
        return column(row(fa, fe), fs)

    def attach(self):
        self.exist_pane.object = self.fig_c
        self.plot.object = self._root

    def publish(self, upd: Updates):
        """(a), (b) in the main pane — hidden when only (c) is valid; (c) in its own pane."""
        super().publish(upd)
        self.plot.visible = self._family_shown

    # ---------------------------------------------------------------- pieces
    def _on_tap(self, event: Tap) -> None:
        """A click on (c) → state.pick(w₊, V).

        Bokeh runs this callback on the session's event loop, holding the document lock, while
        it handles the browser's event message; the pick runs right here with the session's
        document current, so Panel pushes the widget, scene and URL (Location) changes with the
        events Bokeh dispatches when the callback returns — as for a slider.  (Deferring it to
        a next-tick callback let the worker's status updates overtake the sidebar's patch, which
        carries new stylesheet models: "reference … isn't known" in the browser.)  With the
        earlier HoloViews Tap stream the widgets followed a click but the URL did not.
        """
        x, y = event.x, event.y
        if x is None or y is None:
            return
        doc = self._doc
        with set_curdoc(doc) if doc is not None else nullcontext():
            self.state.pick(x, y)

    def _velocities(self, fam) -> list[float]:
        """The velocities of the discrete dots and of the branch view: k midpoints per
        interval (c₊, V_SK) and (V_SK, c₋)."""
        k = int(self.n_discrete.value)
        t = (np.arange(k) + 0.5) / k
        Vs = []
        for lo, hi in ((fam.c_plus, fam.V_SK), (fam.V_SK, fam.c_minus)):
            Vs += list(lo + (hi - lo) * t)
        return Vs

    def _existence(self, info: Info, up: Updates) -> None:
        s = self.state
        lw = s.law()
        c = compute.run(lw, compute.ExistenceRequest())
        d = c.value
        info.time("existence diagram", c)
        key = compute.laws.law_key(lw)
        k = 0
        for side in (d.w_plus < d.w_star, d.w_plus > d.w_star):
            x = d.w_plus[side]
            for y1, y2 in ((d.c_plus, d.V_SK), (d.V_SK, d.c_minus)):
                up.data(self.bands[k][1], key, x=x, y1=y1[side], y2=y2[side])
                k += 1
        for (_, src), y in zip(self.exist_lines, (d.V_SK, d.c_plus, d.c_minus)):
            up.data(src, key, x=d.w_plus, y=y)
        up.set(
            self.exist_label,
            x=float(d.w_plus[0] + 0.02 * (d.w_plus[-1] - d.w_plus[0])),
            y=float(np.min(d.c_plus)) * 1.02,
            text="dark: tensile solitary waves, light: compressive",
        )
        up.data(self.exist_point[1], x=[float(s.w_plus)], y=[float(s.V)])
        up.range(self.fig_c.x_range, d.w_plus[0], d.w_plus[-1], pad=0.02)
        up.range(self.fig_c.y_range, *finite_extent(d.c_plus, d.c_minus), pad=0.05)
        self._exist = d

    def _discrete_points(self, info: Info, fam):
        s = self.state
        Vs = self._velocities(fam)
        lw, req = s.law(), compute.FamilyRequest(s.w_plus, Vs, s.N, s.tol)
        wanted = self._want_discrete or FIGURE_PARTS.get(s.figure) == "discrete"
        if not wanted and not compute.is_cached(lw, req):
            info.notes.append("discrete dots: press 'Add discrete points'")
            return None
        self._want_discrete = False
        self._family = (lw, compute.SampledEnergyRequest(req))  # its energy criterion
        c = compute.run(lw, req, **self.job_hooks("discrete family"))
        info.time(f"{len(Vs)} discrete waves", c)
        rows = [r for r in c.value if hasattr(r, "amplitude")]
        bad = [r for r in rows if not r.converged]
        if bad:
            info.notes.append(f"{len(bad)} discrete solves did not converge (not drawn)")
        rows = [r for r in rows if r.converged]
        if rows:
            info.error("max discrete residual", max(r.residual for r in rows))
            info.error("max amplitude error bound", max(r.amplitude_error for r in rows))
            info.error("max energy error bound", max(r.energy_error for r in rows))
        return rows

    def render(self, info: Info):
        s = self.state
        up = Updates()
        try:
            self._existence(info, up)
        except compute.ParameterError as exc:
            raise SceneMessage(str(exc)) from None
        problem = s.problem() if s.mode == "solitary" else None
        try:
            c = compute.run(s.law(), compute.QCFamilyRequest(s.w_plus))
        except compute.ParameterError as exc:
            info.warning = str(exc)
            info.shown = "existence diagram only (w₊ invalid)"
            self._family_shown = False
            return up
        self._family_shown = True
        fam = c.value
        info.time("QC family", c)
        key = (s.law_key(), exact(s.w_plus))
        kinds = (fam.kind_below, fam.kind_above)
        colors = [TSW if kind == "tensile" else CSW_LINE for kind in kinds]
        cur = None
        if s.mode == "solitary" and problem is None:
            q = compute.run(s.law(), compute.QCWaveRequest("solitary", s.w_plus, s.V))
            info.error("QC first-integral residual", q.value.first_integral_residual)
            info.error("QC energy round-off", q.value.energy_error)
            cur = q.value
        elif problem:
            info.warning = f"current V not marked: {problem}"
        rows = self._discrete_points(info, fam)
        self._rows = rows or []
        Vd = np.array([r.V for r in self._rows], float)
        # the energy diverges at V_SK: clip the axis to the finite part of the family
        allE = np.concatenate([fam.energy_below, fam.energy_above])
        lo, hi = (float(q) for q in np.quantile(allE, [0.08, 0.92]))
        elim = (lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo))
        for name, below, above, attr in (
            ("amp", fam.amp_below, fam.amp_above, "amplitude"),
            ("en", fam.energy_below, fam.energy_above, "energy"),
        ):
            p = self.panels[name]
            for (r, src), V, y, color in zip(
                p["qc"], (fam.V_below, fam.V_above), (below, above), colors
            ):
                up.data(src, key, x=V, y=y)
                up.set(r.glyph, line_color=color)
            for span, x0 in zip(p["spans"], (fam.V_SK, fam.c_plus, fam.c_minus)):
                up.set(span, location=float(x0))
            up.set(p["V"], location=float(s.V), visible=cur is not None)
            if cur is None:
                up.data(p["cur"][1], x=[], y=[])
            else:
                up.data(p["cur"][1], x=[float(s.V)], y=[float(getattr(cur, attr))])
            up.data(p["dots"][1], x=Vd, y=[getattr(r, attr) for r in self._rows])
        for item, kind in zip(self.amp_legend, kinds):
            up.set(item, label={"value": f"QC {kind}"})
        up.show(self.panels["amp"]["dots"][0], self.amp_legend[2], len(Vd) > 0)
        up.show(self.panels["en"]["dots"][0], None, len(Vd) > 0)
        amps = [fam.amp_below, fam.amp_above, [r.amplitude for r in self._rows]]
        for fig in (self.fig_a, self.fig_e):
            up.range(fig.x_range, fam.c_plus, fam.c_minus, pad=0.03)
        up.range(self.fig_a.y_range, *finite_extent(*amps), pad=0.05)
        up.range(self.fig_e.y_range, *elim)
        up.set(self.fig_a.title, text=f"(a) amplitude, w₊ = {fmt_num(s.w_plus, 5)}")
        self._fam = fam
        info.shown = (
            f"w₊ = {fmt_num(s.w_plus)}: c₊ = {fmt_num(fam.c_plus)}, "
            f"V_SK = {fmt_num(fam.V_SK)}, c₋ = {fmt_num(fam.c_minus)}; "
            f"current V = {fmt_num(s.V)}"
        )
        self._energy_criterion(info, up, elim, bool(self._rows))
        self._branch_view(info, up, fam)
        return up

    def _energy_criterion(self, info: Info, up: Updates, ylim, with_discrete: bool) -> None:
        """(b): where E_ren(V) is stationary (QC closed forms always — cheap; the discrete E_ren
        only when its dots are computed), and the sentence saying so in the status."""
        s = self.state
        self._ec_qc = self._ec_d = None
        try:
            c = compute.run(s.law(), compute.EnergyRequest(s.w_plus))
        except compute.ParameterError as exc:
            info.notes.append(f"energy criterion not shown: {md_literal(exc)}")
            self.ext_qc.update(up, [], [], (), *ylim, self.ext_legend[0])
            self.ext_d.update(up, [], [], (), *ylim, self.ext_legend[1])
            return
        ec = self._ec_qc = c.value
        info.time("energy criterion (QC)", c)
        V, dV, kinds = ec.qc_extrema_V, ec.qc_extrema_V_error, ec.qc_extrema_kind
        self.ext_qc.update(up, V, dV, kinds, *ylim, self.ext_legend[0])
        if len(V):
            info.error("E_ren^QC extremum location", ec.location_error)
            label = "E_ren^QC " + "; ".join(fmt_extremum(k, v, d) for k, v, d in zip(kinds, V, dV))
            up.set(self.ext_legend[0], label={"value": label})
        words = [criterion_words(V, dV, kinds, "the QC family", "between c₊ and c₋")]
        cd = compute.run(*self._family) if with_discrete else None
        if cd is not None:
            ed = self._ec_d = cd.value
            info.time("energy criterion (discrete dots)", cd)
            Vd, dVd, kd = ed.extrema_V, ed.extrema_V_error, ed.extrema_kind
            self.ext_d.update(up, Vd, dVd, kd, *ylim, self.ext_legend[1])
            if len(Vd):
                label = "discrete E_ren " + "; ".join(
                    fmt_extremum(k, v, d) for k, v, d in zip(kd, Vd, dVd)
                )
                up.set(self.ext_legend[1], label={"value": label})
            words.append(
                criterion_words(Vd, dVd, kd, "the discrete dots", "that the dots resolve (more "
                                "points per interval may find one)")
            )  # fmt: skip
        else:
            self.ext_d.update(up, [], [], (), *ylim, self.ext_legend[1])
        info.shown += ". " + " ".join(words)
