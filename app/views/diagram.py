"""Scene 4 — velocity–amplitude and velocity–energy diagrams, and the existence diagram.

(a) amplitude |w(0) − w_B| and (b) renormalized energy E_ren against V for the current w₊
(Figs. SWamp_energy_QCcubic, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC): QC curves (closed form),
discrete dots on demand, V_SK dashed red, sonic limits c₊ (blue) and c₋ (green), current V
marked.  (c) the existence diagram V vs w₊ (Fig. SWvelocities_cubic) with TSW (dark) and CSW
(light) regions; a click picks (w₊, V).
"""

from __future__ import annotations

import holoviews as hv
import numpy as np
import panel as pn
from panel.io.state import set_curdoc

from .. import compute
from .base import Info, Scene, SceneMessage, _identity, _signature, as_csv, fmt_num

TSW, CSW = "#6a51a3", "#cbc9e2"


class DiagramScene(Scene):
    key = "diagram"
    title = "Diagrams"
    cheap = True
    plot_height = 300

    def controls(self):
        self.n_discrete = pn.widgets.IntInput(
            label="discrete points per interval", value=6, start=2, end=40, width=200
        )
        self.discrete_btn = pn.widgets.Button(
            label="Add discrete points", color="primary", css_classes=["diagram-discrete"]
        )
        hint = pn.pane.Markdown("_Click the existence diagram (c) to pick (w₊, V)._")
        return [hint, self.n_discrete, self.discrete_btn]

    def _extra_watch(self):
        self._want_discrete = False

        def go(_):
            self._want_discrete = True
            self.request()

        self.discrete_btn.on_click(go)

    def extra_panes(self):
        """The existence diagram has its own pane: one DynamicMap fed by a Pipe, with a Tap
        stream on it (clicks pick (w₊, V)); it is built once and updated in place."""
        # background (regions, limit curves) and current point: two DynamicMaps overlaid.  A
        # Tap on a DynamicMap of overlays does not reach the plot (HoloViews re-wraps it), a
        # Tap on the single-element point map does, and a tap anywhere in the frame fires it.
        self._bg_pipe = hv.streams.Pipe(data=None)
        self._pt_pipe = hv.streams.Pipe(data=hv.Scatter([], "w₊", "V", label="current"))
        self._pt_dmap = hv.DynamicMap(_identity, streams=[self._pt_pipe])
        self._tap = hv.streams.Tap(source=self._pt_dmap, x=None, y=None)
        self._tap.add_subscriber(self._on_tap)
        self._exist_sig = None
        self.exist_pane = pn.pane.HoloViews(
            None, linked_axes=False, min_height=330, css_classes=["existence-diagram"]
        )
        return [self.exist_pane]

    def publish(self, obj):
        """(a), (b) go to the main pane; (c) to the clickable existence pane."""
        panels = list(obj) if isinstance(obj, hv.Layout) else [obj]
        exist, rest = panels[-1], panels[:-1]
        point = self._exist_point
        sig = _signature(exist)
        if sig != self._exist_sig or self.exist_pane.object is None:
            self._bg_pipe = hv.streams.Pipe(data=exist)
            self._pt_pipe.event(data=point)
            bg = hv.DynamicMap(_identity, streams=[self._bg_pipe])
            self._exist_sig = sig
            self.exist_pane.object = (bg * self._pt_dmap).opts(
                hv.opts.Overlay(
                    title="(c) existence diagram — click to pick (w₊, V)",
                    legend_position="bottom_right",
                    frame_width=460,
                    frame_height=250,
                    show_grid=True,
                )
            )
        else:
            bg_pipe, pt_pipe = self._bg_pipe, self._pt_pipe

            def send():
                bg_pipe.send(exist)
                pt_pipe.send(point)

            doc = self._doc
            if doc is not None and doc.session_context is not None:
                pn.state.execute(send, schedule=True)
            else:
                send()
        self.exist_pane.visible = True
        if rest:
            super().publish(hv.Layout(rest).cols(2) if len(rest) > 1 else rest[0])
        self.plot.visible = bool(rest)

    # ---------------------------------------------------------------- pieces
    def _on_tap(self, x=None, y=None):
        if x is None or y is None:
            return
        doc = self._doc
        if doc is not None and doc.session_context is not None:
            # HoloViews delivers the click outside the session's context: apply it on the
            # session's loop so that the URL and the widgets follow
            def apply():
                with set_curdoc(doc):
                    self.state.pick(x, y)

            doc.add_next_tick_callback(apply)
        else:
            self.state.pick(x, y)

    def _existence(self, info: Info):
        s = self.state
        c = compute.existence_diagram(s.a, s.b)
        d = c.value
        info.time("existence diagram", c)
        items = []
        for side in (d.w_plus < d.w_star, d.w_plus > d.w_star):
            x = d.w_plus[side]
            lower_tensile = bool(np.all(x < d.w_star))
            items.append(
                hv.Area((x, d.c_plus[side], d.V_SK[side]), "w₊", ["V", "V2"]).opts(
                    color=TSW if lower_tensile else CSW, alpha=0.8, line_alpha=0
                )
            )
            items.append(
                hv.Area((x, d.V_SK[side], d.c_minus[side]), "w₊", ["V", "V2"]).opts(
                    color=CSW if lower_tensile else TSW, alpha=0.8, line_alpha=0
                )
            )
        items += [
            hv.Curve((d.w_plus, d.V_SK), "w₊", "V", label="V_SK").opts(
                color="#d62728", line_width=2
            ),
            hv.Curve((d.w_plus, d.c_plus), "w₊", "V", label="c₊").opts(color="#1f77b4"),
            hv.Curve((d.w_plus, d.c_minus), "w₊", "V", label="c₋").opts(color="#2ca02c"),
            hv.Text(
                0.5 * (d.alpha + d.w_star), float(np.min(d.c_plus)) * 1.02, "dark: TSW, light: CSW"
            ).opts(text_font_size="9pt"),
        ]
        # the current point is its own DynamicMap (see publish): the click stream hangs on it
        self._exist_point = hv.Scatter(([s.w_plus], [s.V]), "w₊", "V", label="current").opts(
            color="black", size=11, marker="circle"
        )
        self._exist = d
        return hv.Overlay(items)

    def _discrete_points(self, info: Info, fam):
        s = self.state
        Vs = []
        k = int(self.n_discrete.value)
        for lo, hi in ((fam.c_plus, fam.V_SK), (fam.V_SK, fam.c_minus)):
            t = (np.arange(k) + 0.5) / k
            Vs += list(lo + (hi - lo) * t)
        key_args = (s.a, s.b, s.w_plus, Vs, s.N, s.tol)
        cached = compute.CACHE.peek(
            (
                "dfamily",
                compute.rnd(s.a),
                compute.rnd(s.b),
                compute.rnd(s.w_plus),
                tuple(compute.rnd(v) for v in Vs),
                s.N,
                compute.rnd(s.tol, 3),
            )
        )
        if cached is None and not self._want_discrete:
            info.notes.append("discrete dots: press 'Add discrete points'")
            return None
        self._want_discrete = False
        c = compute.discrete_family(*key_args, progress=self.set_progress)
        info.time(f"{len(Vs)} discrete waves", c)
        rows = [r for r in c.value if hasattr(r, "amplitude")]
        bad = [r for r in rows if not r.converged]
        if bad:
            info.notes.append(f"{len(bad)} discrete solves did not converge (not drawn)")
        rows = [r for r in rows if r.converged]
        if rows:
            info.error("max discrete residual", max(r.residual for r in rows))
        return rows

    def render(self, info: Info):
        s = self.state
        try:
            exist = self._existence(info)
        except compute.ParameterError as exc:
            raise SceneMessage(str(exc)) from None
        problem = s.problem() if s.mode == "solitary" else None
        try:
            c = compute.qc_family(s.a, s.b, s.w_plus)
        except compute.ParameterError as exc:
            info.warning = str(exc)
            info.shown = "existence diagram only (w₊ invalid)"
            return exist
        fam = c.value
        info.time("QC family", c)
        amp = [
            hv.Curve(
                (fam.V_below, fam.amp_below), "V", "amplitude", label=f"QC {fam.kind_below}"
            ).opts(color=TSW if fam.kind_below == "tensile" else "#9e9ac8", line_width=2.5),
            hv.Curve(
                (fam.V_above, fam.amp_above), "V", "amplitude", label=f"QC {fam.kind_above}"
            ).opts(color=TSW if fam.kind_above == "tensile" else "#9e9ac8", line_width=2.5),
        ]
        en = [
            hv.Curve((fam.V_below, fam.energy_below), "V", "E_ren").opts(
                color=TSW if fam.kind_below == "tensile" else "#9e9ac8", line_width=2.5
            ),
            hv.Curve((fam.V_above, fam.energy_above), "V", "E_ren").opts(
                color=TSW if fam.kind_above == "tensile" else "#9e9ac8", line_width=2.5
            ),
        ]
        lines = [
            hv.VLine(fam.V_SK).opts(color="#d62728", line_dash="dashed"),
            hv.VLine(fam.c_plus).opts(color="#1f77b4", line_dash="dotted"),
            hv.VLine(fam.c_minus).opts(color="#2ca02c", line_dash="dotted"),
        ]
        if s.mode == "solitary" and problem is None:
            q = compute.qc_wave(s.a, s.b, "solitary", s.w_plus, s.V)
            info.error("QC first-integral residual", q.value.first_integral_residual)
            info.error("QC energy round-off", q.value.energy_error)
            amp.append(
                hv.Scatter(([s.V], [q.value.amplitude]), "V", "amplitude").opts(
                    color="black", size=10, marker="diamond"
                )
            )
            en.append(
                hv.Scatter(([s.V], [q.value.energy]), "V", "E_ren").opts(
                    color="black", size=10, marker="diamond"
                )
            )
            lines.append(hv.VLine(s.V).opts(color="black", line_width=1))
        elif problem:
            info.warning = f"current V not marked: {problem}"
        # the energy diverges at V_SK: clip the axis to the finite part of the family
        allE = np.concatenate([fam.energy_below, fam.energy_above])
        lo, hi = (float(q) for q in np.quantile(allE, [0.08, 0.92]))
        elim = (lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo))
        rows = self._discrete_points(info, fam)
        self._rows = rows or []
        if rows:
            Vd = [r.V for r in rows]
            amp.append(
                hv.Scatter(
                    (Vd, [r.amplitude for r in rows]), "V", "amplitude", label="discrete"
                ).opts(color="black", size=6, marker="circle")
            )
            en.append(
                hv.Scatter((Vd, [r.energy for r in rows]), "V", "E_ren").opts(
                    color="black", size=6, marker="circle"
                )
            )
        size = dict(frame_width=250, frame_height=200, show_grid=True)
        pa = hv.Overlay(amp + lines).opts(
            title=f"(a) amplitude, w₊ = {fmt_num(s.w_plus, 5)}", legend_position="top_left", **size
        )
        pe = hv.Overlay(en + lines).opts(
            title="(b) renormalized energy", ylim=elim, show_legend=False, **size
        )
        self._fam = fam
        info.shown = (
            f"w₊ = {fmt_num(s.w_plus)}: c₊ = {fmt_num(fam.c_plus)}, "
            f"V_SK = {fmt_num(fam.V_SK)}, c₋ = {fmt_num(fam.c_minus)}; "
            f"current V = {fmt_num(s.V)}"
        )
        return hv.Layout([pa, pe, exist])

    def download_data(self):
        fam = getattr(self, "_fam", None)
        if fam is None:
            raise SceneMessage("nothing shown yet")
        cols = {
            "V_below": fam.V_below,
            "amp_below": fam.amp_below,
            "E_below": fam.energy_below,
            "V_above": fam.V_above,
            "amp_above": fam.amp_above,
            "E_above": fam.energy_above,
        }
        if self._rows:
            cols["V_discrete"] = np.array([r.V for r in self._rows])
            cols["amp_discrete"] = np.array([r.amplitude for r in self._rows])
            cols["E_discrete"] = np.array([r.energy for r in self._rows])
            cols["residual_discrete"] = np.array([r.residual for r in self._rows])
        d = getattr(self, "_exist", None)
        if d is not None:
            cols.update(w_plus=d.w_plus, c_plus=d.c_plus, V_SK=d.V_SK, c_minus=d.c_minus)
        hdr = (
            f"QC solitary family for w_plus={fam.w_plus!r} (c_plus={fam.c_plus!r}, "
            f"V_SK={fam.V_SK!r}, c_minus={fam.c_minus!r}); existence diagram columns"
        )
        return "diagram.csv", as_csv(cols, hdr)
