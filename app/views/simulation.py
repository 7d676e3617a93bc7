"""Scene 6 — direct simulation (paper's Figs. stabSK, Riemann1, stabSW, SWdyn).

Space-time image of the strain w_n(t) for data seeded by the current discrete traveling wave
(eq. fixedBCs), Riemann data (eq. Riemann_data) or a Gaussian bump (eq. GaussIC), the initial and
final profiles, and the table of the waves the tracker found with their measured velocities.
Runs only when "Run" is pressed, in a worker process (progress and Cancel).  The image is a
Bokeh ``image`` glyph (one texture, no per-cell quads: no moiré).

Tracked sites (Fig. Riemann1 (c)–(e)): for each site typed in "tracked sites", its history
w_k(t) (the run's probes) against the traveling wave fpucore.wave computes at the velocity and
background the tracker measured for the last wave to pass that site, placed at its passage
(eq. TWansatz, ξ = n − Vt; fpucore.paper.figures_dynamics' site_overlay and passage_time).
"""

from __future__ import annotations

import io

import numpy as np
from bokeh.layouts import column
from bokeh.models import ColorBar, ColumnDataSource, LinearColorMapper
from bokeh.palettes import Viridis256

from fpucore import qc, simulate
from fpucore.paper.figures_dynamics import (
    WINDOW_SITES,
    passage_time,
    seeded_comparison,
    seeded_title,
    site_overlay,
)

from .. import compute, sim_url
from .bokeh_scene import BokehScene, Updates, add_legend, add_line, new_figure
from .formatting import comparison_parts, fmt_num, provenance, state_stamp
from .python_code import python_preamble
from .report import Info, SceneMessage
from .simulation_inputs import SimulationInputs
from .simulation_table import (
    KIND_WORDS,
    MAX_PROBES,
    SHORT_NAMES,
    fmt_pm,
    last_to_pass,
    run_stamp,
    tracked_velocities,
    wave_table,
)
from .untrusted import LiteralMarkdown, md_literal

#: the space–time image's most columns (about the plot's width in pixels)
MAX_COLUMNS = 1000


class SimulationScene(SimulationInputs, BokehScene):
    title = "Simulation"
    caption = (
        "_Direct simulation of the FPU chain: strain w_n(t) in space and time, and the waves "
        "it forms. Paper: Figs. 13, 14, 16 and 17 (stabSK, "
        "Riemann1, stabSW, SWdyn)._"
    )
    plot_height = 380

    def extra_panes(self):
        self.table = LiteralMarkdown("", sizing_mode="stretch_width", css_classes=["sim-table"])
        return [self.table]

    def __init__(self, state):
        super().__init__(state)
        self._want_run = False
        self._request: compute.SimulationRequest | None = None
        self._sim = None
        self._applying = False
        self.run_btn.on_click(self._on_run)
        inputs = [self.kind, self.L, self.t_end, self.w_l, self.w_r, self.w_B, self.A,
                  self.guard, self.probes]  # fmt: skip
        for w in inputs:
            w.param.watch(lambda _: self._inputs_to_url(), "value")
        if state.scenario:  # a paper figure's initial data: run (if asked) at the first render
            self.show_scenario(**state.scenario)
        state.param.watch(self._on_scenario, "scenario")

    def _on_run(self, _) -> None:
        self._want_run = True
        self._inputs_to_url()  # a run with the widgets' defaults is a link's too
        self.request()

    def build(self):
        fi = new_figure(
            "Strain w_n(t) in space and time",
            "site n",
            "time t",
            sizing_mode="stretch_width",
            height=self.plot_height,
            tools="pan,wheel_zoom,box_zoom,save,reset,hover",
        )
        self.mapper = LinearColorMapper(palette=Viridis256, low=0.0, high=1.0)
        self.img_src = ColumnDataSource(
            {"image": [np.zeros((2, 2))], "x": [0.0], "y": [0.0], "dw": [1.0], "dh": [1.0]}
        )
        fi.image(
            image="image", x="x", y="y", dw="dw", dh="dh", source=self.img_src,
            color_mapper=self.mapper,
        )  # fmt: skip
        fi.add_layout(ColorBar(color_mapper=self.mapper, title="w"), "right")
        fp = new_figure(
            "Initial and final strain profiles",
            "site n",
            "w",
            sizing_mode="stretch_width",
            height=220,
        )
        self.fig_probe, self.r_probe, self.r_probe_wave, self.probe_legend = [], [], [], []
        for k in range(MAX_PROBES):
            # one above the other, each the scene's width: a title names the site, the wave,
            # its V and w_B ± error (~300 px; three side by side got ~266 px each and cut it)
            f = new_figure(f"({'cde'[k]}) site", "t", "w", height=200, width=300,
                           sizing_mode="stretch_width")  # fmt: skip
            site = add_line(f, "black", 1.5)
            site[1].name = f"sim-probe-{k}"  # read by the tests
            tw = add_line(f, "#d62728", 2.0, "dashed")
            tw[1].name = f"sim-probe-wave-{k}"
            entries = [("w_k(t)", [site[0]]), ("TW at measured V, w_B", [tw[0]])]
            self.probe_legend.append(add_legend(f, "below", entries))
            self.fig_probe.append(f)
            self.r_probe.append(site)
            self.r_probe_wave.append(tw)
        self.fig_img, self.fig_prof = fi, fp
        self.r_first = add_line(fp, "gray", 1.5, "dashed")
        self.r_last = add_line(fp, "black", 1.5)
        # read by the tests (the drawn data against the run's)
        self.r_first[1].name, self.r_last[1].name = "sim-profile-initial", "sim-profile-final"
        self.img_src.name, self.mapper.name = "sim-image", "sim-colour"
        self.prof_legend = add_legend(
            fp, "right", [("t = 0", [self.r_first[0]]), ("final", [self.r_last[0]])]
        )
        # shown and hidden as one (a visibility change lays out the whole tab in the browser:
        # 0.7-1 s each beside these figures, three per tracked run)
        self.probe_col = column(*self.fig_probe, sizing_mode="stretch_width", visible=False)
        return column(fi, fp, self.probe_col, sizing_mode="stretch_width")

    def _tracked_sites(self, info: Info, up: Updates, sim) -> None:
        """Panels (c)–(e): each tracked site's history against the wave computed at the
        measured V and w_B of the last tracked wave to pass it."""
        sites = list(np.asarray(getattr(sim, "probe_sites", []), int))
        self._probe_waves = []
        s = self.state
        up.set(self.probe_col, visible=bool(sites))
        for k in range(MAX_PROBES):
            fig = self.fig_probe[k]
            up.set(fig, visible=k < len(sites) or not sites)  # (a change only if it differs)
            if k >= len(sites):
                continue
            site, t = sites[k], np.asarray(sim.probe_t, float)
            w_k = np.asarray(sim.probe_series[k], float)
            wv = last_to_pass(sim.waves, site, float(t[-1]))
            x, y, title, call = np.empty(0), np.empty(0), f"({'cde'[k]}) site {site}", None
            keep = np.ones(t.size, bool)
            if wv is None:
                info.notes.append(f"site {site}: no tracked wave passed it")
            else:
                try:
                    r, call = self._wave_at(wv, info)
                except compute.ParameterError as exc:
                    r = None
                    info.notes.append(
                        f"site {site}: no traveling wave at the measured V = "
                        f"{wv.velocity:.6g}, w_B = {wv.background:.6g}: {md_literal(exc)}"
                    )
                V = abs(wv.velocity)
                t_c = passage_time(s.law(), t, w_k, wv)
                keep = np.abs(t - t_c) <= WINDOW_SITES / V
                title += f": {SHORT_NAMES.get(wv.kind, wv.kind)} V = {wv.velocity:.6g}"
                if r is not None and r.converged:
                    tt, ww = site_overlay(r, t_c, wv.velocity < 0)
                    near = np.abs(tt - t_c) <= WINDOW_SITES / V
                    x, y = tt[near], ww[near]
                    title += f", w_B = {fmt_pm(wv.background, wv.background_error)}"
            self._probe_waves.append((site, wv, call))
            up.set(fig.title, text=title)
            up.data(self.r_probe[k][1], x=t[keep], y=w_k[keep])
            up.data(self.r_probe_wave[k][1], x=x, y=y)
            up.show(self.r_probe_wave[k][0], self.probe_legend[k][1], len(x) > 0)
            ys = np.concatenate([w_k[keep], y])
            up.range(fig.x_range, float(t[keep][0]), float(t[keep][-1]))
            up.range(fig.y_range, float(ys.min()), float(ys.max()), pad=0.08)

    def _measured_velocity(self, sim, tracked: str) -> str:
        """A seeded run's velocity: the fit of the wave's passage times at the sites it crossed
        (fpucore.simulate.seeded, details V_measured), checked as the Paper tab checks it
        (fpucore.paper.figures_dynamics.seeded_comparison: the same row for the same run), then
        the tracker's estimate, labelled; the tracker's alone if no velocity was measured."""
        d = sim.details
        title = seeded_title(d.get("kind", ""), d.get("V_prescribed", np.nan))
        fig = self.state.figure if self.state.figure in ("stabSK", "stabSW") else "simulation"
        c = seeded_comparison(fig, sim, title, sim.elapsed_s)
        if c is None:
            return f"no velocity measured from passage times (the run stopped early); {tracked}"
        return (
            f"measured velocity V = {d['V_measured']!r} (fit of the passage times at "
            f"{d.get('n_sites_timed', '?')} sites); {comparison_parts([c])[0]}; "
            f"the tracker's estimate: {tracked.removeprefix('tracked velocities: ')}"
        )

    def _image(self, info: Info, up: Updates, sim, snaps, t, n) -> None:
        """The space–time image: at most MAX_COLUMNS columns, each a block of sites showing its
        extreme strain (fpucore.simulate.extreme_blocks), the colour bar over the whole field;
        the title says how many sites a column holds."""
        b = simulate.extreme_blocks(snaps, n, MAX_COLUMNS)
        dn = (n[-1] - n[0]) / max(len(n) - 1, 1) if len(n) > 1 else 1.0
        dt = (t[-1] - t[0]) / max(len(t) - 1, 1)
        width = b.image.shape[1] * b.width
        up.set(
            self.img_src,
            data={"image": [b.image], "x": [b.x0], "y": [t[0] - 0.5 * dt], "dw": [width],
                  "dh": [t[-1] - t[0] + dt]},
        )  # fmt: skip
        up.set(self.mapper, low=float(snaps.min()), high=float(snaps.max()))
        up.range(self.fig_img.x_range, n[0] - 0.5 * dn, n[-1] + 0.5 * dn)
        up.range(self.fig_img.y_range, t[0] - 0.5 * dt, t[-1] + 0.5 * dt)
        title = f"Strain w_n(t) in space and time ({len(t)} snapshots"
        if len(n) < sim.L:
            title += f", {len(n)} of {sim.L} sites: every {sim.L / len(n):.3g}th"
        if b.block > 1:
            title += f"; each block of {b.block} sites drawn as its min and max"
            info.notes.append(f"space–time image: {b.note}; colour bar over the whole field")
        up.set(self.fig_img.title, text=title + ")")

    def _wave_at(self, wv, info: Info):
        """The discrete traveling wave at a tracked wave's measured V (and w_B): a superkink of
        that velocity, or the solitary wave on the measured background.  (WaveResult, the
        fpucore call as text)."""
        s = self.state
        V = abs(float(wv.velocity))
        if wv.kind == "superkink":
            sk = qc.superkink_from_V(s.law(), V)
            mode, w_plus = "superkink", sk.w_plus
        else:
            mode, w_plus = "solitary", float(wv.background)
        req = compute.WaveRequest(mode, w_plus, V, s.N, s.tol)
        c = compute.run(s.law(), req, **self.job_hooks())
        r = c.value
        info.time(f"wave at V = {V:.6g}", c)
        return r, req.call(s.law()).code()

    def render(self, info: Info):
        # a failed or superseded run must not leave the previous run's numbers on screen
        self._sim = None
        self.table.object = ""
        if self._want_run:
            self._want_run = False
            self._request = self._job()
        if self._request is None:
            raise SceneMessage("Choose the initial data and press 'Run simulation'.", "info")
        req = self._request
        s = self.state
        # the run's own inputs on the parameter line (a Riemann run does not use the state's
        # wave; a seeded one uses the wave of the moment Run was pressed)
        info.stamp = run_stamp(state_stamp(s), req)
        self.computing_for(info.stamp)
        c = compute.run(s.law(), req, **self.job_hooks("simulation"))
        sim = c.value
        info.time(f"simulation ({req.kind})", c)
        info.error("relative energy drift", sim.energy_drift)
        # what the integrator's own estimate bounds depends on the method (SimulationResult)
        what = (
            "strain step-doubling error max|w_h − w_2h|/15"
            if sim.method == "symplectic"
            else "accumulated local error (RMS over the state)"
        )
        info.error(what, sim.error_estimate)
        info.notes.append(
            f"{sim.method}, {sim.n_steps} steps ({sim.n_rejected} rejected), rtol {sim.rtol:g}"
            if sim.method != "symplectic"
            else f"symplectic, dt {sim.dt:g}"
        )
        if getattr(sim, "status", "ok") not in ("ok", None):
            info.notes.append(f"status {sim.status}: {md_literal(sim.message)}")
        elif sim.details.get("left_convex_interval"):
            lo, hi = sim.details["strain_range"]
            info.notes.append(
                f"strains went outside the convex interval (α, β): [{lo:.4g}, {hi:.4g}]"
            )
        snaps = np.asarray(sim.snapshots, dtype=float)
        if snaps.size == 0 or not np.all(np.isfinite(snaps)):
            raise SceneMessage(f"the simulation returned no finite snapshots: {sim.message}")
        t, n = np.asarray(sim.t, float), np.asarray(sim.sites, float)
        up = Updates()
        self._image(info, up, sim, snaps, t, n)
        up.data(self.r_first[1], x=n, y=snaps[0])
        up.data(self.r_last[1], x=n, y=snaps[-1])
        up.set(self.prof_legend[1], label={"value": f"t = {t[-1]:.4g}"})
        up.range(self.fig_prof.x_range, n[0], n[-1])
        up.range(self.fig_prof.y_range, float(snaps.min()), float(snaps.max()), pad=0.05)
        if len(n) < sim.L:  # a stored field of fewer sites (fpucore's max_sites_out)
            up.set(self.fig_prof.title, text=f"Initial and final strain profiles ({len(n)} of "
                   f"{sim.L} sites: every {sim.L / len(n):.3g}th)")  # fmt: skip
        else:
            up.set(self.fig_prof.title, text="Initial and final strain profiles (every site)")
        self.table.object = wave_table(sim.waves)
        self._tracked_sites(info, up, sim)
        self._sim = (req, sim)
        velocities = tracked_velocities(sim.waves)
        if isinstance(req, compute.SeededRequest):
            info.notes.append(f"seeding wave V = {fmt_num(req.wave.V)}, N = {req.wave.N}")
            velocities = self._measured_velocity(sim, velocities)
        info.shown = f"simulation of {KIND_WORDS[req.kind]} to t = {t[-1]:.4g}; {velocities}"
        if sim_url.format_sim(req.kind, **req.params()) == s.simulation:
            s.sim_shown = True  # the link's run is on screen (run=1)
        return up

    def hide_plot(self) -> None:
        super().hide_plot()
        self.table.object = ""

    def python_code(self) -> str:
        code = python_preamble(self.state)
        if self._sim is None:
            return code + "# no simulation yet: press 'Run simulation'\n"
        req, _ = self._sim
        first = "law"
        if isinstance(req, compute.SeededRequest):
            code += f"r = {req.wave.call(self.state.law()).code()}\n"
            first = "r"
        code += f"sim = {req.call().code(first)}\n"
        code += (
            "print(sim.energy_drift, [(w.kind, w.velocity, w.velocity_error) for w in sim.waves])\n"
        )
        for k, (site, _, call) in enumerate(getattr(self, "_probe_waves", [])):
            if call is not None:  # the wave at the measured V, w_B of the wave passing the site
                code += f"tw{k} = {call}  # site {site}\nprint(tw{k}.converged, tw{k}.V)\n"
        return code

    def notebook_plot(self) -> str:
        if self._sim is None:
            return ""
        return (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            "from fpucore.simulate import extreme_blocks\n\n"
            "z, t, n = np.asarray(sim.snapshots), np.asarray(sim.t), np.asarray(sim.sites)\n"
            "# the explorer's image: blocks of sites, each drawn as its minimum and maximum\n"
            f"b = extreme_blocks(z, n, {MAX_COLUMNS})\n"
            "fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7))\n"
            "im = ax1.imshow(b.image, origin='lower', aspect='auto', interpolation='nearest',\n"
            "                vmin=z.min(), vmax=z.max(),\n"
            "                extent=(b.x0, b.x0 + b.image.shape[1] * b.width,\n"
            "                        t[0], t[-1]))\n"
            "fig.colorbar(im, ax=ax1, label='w')\n"
            "ax1.set(xlabel='site n', ylabel='time t')\n"
            "ax2.plot(n, z[0], '--', color='gray', label='t = 0')\n"
            "ax2.plot(n, z[-1], 'k', label=f't = {t[-1]:.4g}')\n"
            "ax2.set(xlabel='site n', ylabel='w')\n"
            "ax2.legend()\n"
        )

    def download_data(self):
        if self._sim is None:
            raise SceneMessage("no simulation yet")
        req, sim = self._sim
        sites = np.asarray(sim.sites)
        if len(sites) == sim.L:
            cols = f"one column per site n (all {sim.L})"
        else:  # fpucore keeps at most max_sites_out sites, evenly spread (engine.py)
            cols = (
                f"one column for each of {len(sites)} sites n spread evenly over the {sim.L} "
                f"(about every {sim.L / len(sites):.3g}th; the column names give n)"
            )
        hdr = provenance(
            self.state,
            f"space-time strain field w_n(t) of a simulation of {KIND_WORDS[req.kind]}: one row "
            f"per time t, {cols}",
            kind=req.kind,
            **req.params(),
            energy_drift=float(sim.energy_drift),
            error_estimate=float(sim.error_estimate),
        )
        hdr += "\nwaves: " + "; ".join(
            f"{w.kind} V={w.velocity!r} +- {w.velocity_error!r} w_B={w.background!r} +- "
            f"{w.background_error!r} amplitude={w.amplitude!r}"
            for w in sim.waves
        )
        hdr += "\n" + self.python_code()
        buf = io.StringIO()
        for line in hdr.splitlines():
            buf.write(f"# {line}\n")
        buf.write("t," + ",".join(f"n={int(k)}" for k in sites) + "\n")
        for ti, rowv in zip(np.asarray(sim.t), np.asarray(sim.snapshots)):
            buf.write(repr(float(ti)) + "," + ",".join(repr(float(v)) for v in rowv) + "\n")
        buf.seek(0)
        return "simulation_field.csv", buf
