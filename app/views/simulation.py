"""Scene 6 — direct simulation (Figs. stabSK, Riemann1, stabSW, SWdyn).

Space-time image of the strain w_n(t) for data seeded by the current discrete traveling wave
(eq. fixedBCs), Riemann data (eq. Riemann_data) or a Gaussian bump (eq. GaussIC), with the
waves the tracker found and their measured velocities.  Runs only when "Run" is pressed.
"""

from __future__ import annotations

import holoviews as hv
import numpy as np
import panel as pn

from .. import compute
from .base import Info, Scene, SceneMessage, as_json, fmt_num


class SimulationScene(Scene):
    key = "simulation"
    title = "Simulation"
    depends = ("a", "b", "w_plus", "V", "mode", "N", "tol")
    plot_height = 560

    def controls(self):
        self.kind = pn.widgets.RadioButtonGroup(
            options={"TW-seeded": "seeded", "Riemann": "riemann", "Gaussian": "gaussian"},
            value="seeded",
        )
        self.L = pn.widgets.IntInput(label="L (sites)", value=800, start=50, end=20000, width=140)
        self.t_end = pn.widgets.FloatInput(
            label="t_end", value=40.0, start=0.1, end=2000, width=140
        )
        self.w_l = pn.widgets.FloatInput(label="w^l (Riemann)", value=4.6, width=140)
        self.w_r = pn.widgets.FloatInput(label="w^r (Riemann)", value=0.0, width=140)
        self.w_B = pn.widgets.FloatInput(label="w_B (Gaussian)", value=1.0, width=140)
        self.A = pn.widgets.FloatInput(label="A (Gaussian)", value=6.0, width=140)
        # the paper's Gaussian data start above β (w_B = 1, A = 6 gives w = 7): with the convex
        # guard they would be refused, so the scene stops only where the force stops restoring
        self.guard = pn.widgets.Select(
            label="stop the run when a strain leaves",
            options={"the zeros of f (bounded)": "bounded", "the convex interval (α, β)": "convex"},
            value="bounded",
            width=290,
        )
        self.run_btn = pn.widgets.Button(
            label="Run simulation", color="primary", css_classes=["simulation-run"]
        )
        self.table = pn.pane.Markdown("", sizing_mode="stretch_width")
        return [
            self.kind,
            pn.Row(self.L, self.t_end),
            pn.Row(self.w_l, self.w_r),
            pn.Row(self.w_B, self.A),
            self.guard,
            self.run_btn,
            self.table,
        ]

    def _extra_watch(self):
        self._want_run = False
        self._params = None

        def go(_):
            self._want_run = True
            self.request()

        self.run_btn.on_click(go)

    def _job(self):
        s = self.state
        kind = self.kind.value
        p = {"L": int(self.L.value), "t_end": float(self.t_end.value), "guard": self.guard.value}
        if kind == "riemann":
            p.update(w_left=float(self.w_l.value), w_right=float(self.w_r.value))
        elif kind == "gaussian":
            p.update(w_B=float(self.w_B.value), A=float(self.A.value))
        else:
            if s.problem() is not None:
                raise SceneMessage(s.problem())
            p.update(mode=s.mode, w_plus=s.w_plus, V=s.V, N=s.N, tol=s.tol)
        return kind, p

    def render(self, info: Info):
        s = self.state
        job = self._job()
        if self._want_run:
            self._params = job
        self._want_run = False
        if self._params is None:
            raise SceneMessage("Choose the initial data and press 'Run simulation'.", "info")
        kind, p = self._params

        def progress(*args):
            if len(args) >= 2:
                self.set_progress(int(args[0]), int(args[1]))
            elif len(args) == 1 and isinstance(args[0], float):
                self.set_progress(int(100 * args[0]), 100)

        c = compute.simulation(kind, s.a, s.b, p, progress=progress)
        sim = c.value
        info.time(f"simulation ({kind})", c)
        info.error("energy drift", sim.energy_drift)
        info.error("error estimate", sim.error_estimate)
        info.notes.append(
            f"{sim.method}, {sim.n_steps} steps ({sim.n_rejected} rejected), rtol {sim.rtol:g}"
            if sim.method != "symplectic"
            else f"symplectic, dt {sim.dt:g}"
        )
        if getattr(sim, "status", 0) not in (0, "ok", "success", None):
            info.notes.append(f"status {sim.status}: {sim.message}")
        elif sim.details.get("left_convex_interval"):
            lo, hi = sim.details["strain_range"]
            info.notes.append(
                f"strains went outside the convex interval (α, β): [{lo:.4g}, {hi:.4g}]"
            )
        snaps = np.asarray(sim.snapshots, dtype=float)
        if snaps.size == 0 or not np.all(np.isfinite(snaps)):
            raise SceneMessage(f"the simulation returned no finite snapshots: {sim.message}")
        t, n = np.asarray(sim.t), np.asarray(sim.sites)
        img = hv.QuadMesh((n, t, snaps), ["n", "t"], "w").opts(
            cmap="viridis",
            colorbar=True,
            frame_width=560,
            frame_height=330,
            title=f"strain w_n(t), {kind} data",
            tools=["hover"],
        )
        last = hv.Curve((n, snaps[-1]), "n", "w", label=f"t = {t[-1]:.4g}").opts(color="black")
        first = hv.Curve((n, snaps[0]), "n", "w", label="t = 0").opts(
            color="gray", line_dash="dashed"
        )
        prof = (first * last).opts(
            frame_width=560,
            frame_height=170,
            legend_position="top_right",
            title="initial and final profiles",
        )
        rows = ["| kind | V measured | amplitude | left | right |", "|---|---|---|---|---|"]
        for wv in sim.waves:
            rows.append(
                f"| {wv.kind} | {wv.velocity:.8g} | {fmt_num(wv.amplitude, 5)} | "
                f"{fmt_num(wv.left_state, 5)} | {fmt_num(wv.right_state, 5)} |"
            )
        self.table.object = (
            "**Tracked waves**\n\n" + "\n".join(rows) if sim.waves else ("_no waves tracked_")
        )
        self._sim = (kind, p, sim)
        speeds = ", ".join(f"{wv.velocity:.6g}" for wv in sim.waves[:4])
        info.shown = f"{kind} simulation to t = {t[-1]:.4g}; tracked velocities: {speeds or 'none'}"
        if kind == "seeded":
            info.notes.append(f"seeding wave V = {fmt_num(p['V'])}")
        return (img + prof).cols(1).opts(shared_axes=False)

    def download_data(self):
        sim = getattr(self, "_sim", None)
        if sim is None:
            raise SceneMessage("no simulation yet")
        kind, p, s = sim
        out = {
            "kind": kind,
            "params": p,
            "t": s.t,
            "sites": s.sites,
            "energy_drift": s.energy_drift,
            "error_estimate": s.error_estimate,
            "waves": [
                {
                    "kind": w.kind,
                    "velocity": w.velocity,
                    "amplitude": w.amplitude,
                    "left_state": w.left_state,
                    "right_state": w.right_state,
                }
                for w in s.waves
            ],
            "final_profile": np.asarray(s.snapshots)[-1],
        }
        return "simulation.json", as_json(out)
