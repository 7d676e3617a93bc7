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
import math
import re

import numpy as np
import panel as pn
from bokeh.layouts import column, row
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
from .formatting import fmt_num, provenance, state_stamp
from .paper import comparison_parts
from .python_code import python_preamble
from .report import Info, SceneMessage
from .untrusted import LiteralMarkdown, md_literal

#: the space–time image's most columns (about the plot's width in pixels)
MAX_COLUMNS = 1000
MAX_PROBES = 3  # tracked-site panels drawn (the paper's (c), (d), (e))
SHORT_NAMES = {"dsw_edge": "DSW edge", "solitary": "solitary wave"}  # panel titles

KIND_WORDS = {
    "seeded": "the current traveling wave (TW-seeded)",
    "riemann": "Riemann data",
    "gaussian": "a Gaussian bump",
}
#: the tracker's kinds in plain words, with a one-line explanation (paper §6)
WAVE_NAMES = {
    "superkink": (
        "superkink",
        "a supersonic front between two states on opposite sides of w*, moving steadily",
    ),
    "solitary": ("solitary wave", "a single pulse on a uniform background, moving steadily"),
    "dsw_edge": (
        "edge of the dispersive shock",
        "the leading pulse of a spreading train of oscillations; not a steady wave, so its "
        "speed depends on when it is measured (included in the ±)",
    ),
    "front": ("front", "a jump between two states on the same side of w*"),
}


def last_to_pass(waves, site: int, t_end: float):
    """The tracked wave that passed ``site`` last before t_end (its straight path through
    ``position`` at t_end, at its measured velocity), or None: the wave a site's history ends
    with (Fig. Riemann1: site 200 sees the superkink, then the left DSW edge)."""
    best, t_best = None, -np.inf
    for w in waves:
        if not (np.isfinite(w.velocity) and w.velocity != 0 and np.isfinite(w.position)):
            continue
        t = t_end + (site - w.position) / w.velocity
        if 0.0 <= t <= t_end and t > t_best:
            best, t_best = w, t
    return best


def run_stamp(state_line: str, req) -> str:
    """The parameter line of a simulation: the state's (state_stamp), then the run's inputs
    exactly ("; run: riemann L=3600 t_end=300.0 … w_left=4.6 w_right=0.0")."""
    run = " ".join(f"{k}={v!r}" for k, v in req.params().items())
    return f"{state_line}; run: {req.kind} {run}"


def fmt_pm(x: float, err: float) -> str:
    """x ± err with x rounded to the error's second significant digit ("± 0": no spread)."""
    if not math.isfinite(err):
        return f"{x:.8g} ± ?"
    if err <= 0.0:
        return f"{x:.8g} ± 0"
    d = min(12, max(0, 1 - math.floor(math.log10(err))))
    return f"{x:.{d}f} ± {err:.1e}"


def tracked_velocities(waves, k: int = 4) -> str:
    """The status line's velocities: each with its error bar and digits (a DSW edge's V is
    known to ~1e-4, not to the 6 digits printed before), the count when more are tracked."""
    if not waves:
        return "tracked velocities: none"
    shown = ", ".join(fmt_pm(wv.velocity, wv.velocity_error) for wv in waves[:k])
    more = f" (and {len(waves) - k} more in the table)" if len(waves) > k else ""
    return f"tracked velocities: {shown}{more}"


def wave_table(waves) -> str:
    """Markdown table of the tracked waves: plain name, V ± error, w_B ± error, the states;
    then one line per kind present saying what it is and what the ± contains."""
    if not waves:
        return "_no waves tracked_"
    rows = [
        "| wave | velocity V ± error | state ahead w_B ± error | amplitude | strain left | "
        "strain right |",
        "|---|---|---|---|---|---|",
    ]
    for wv in waves:
        name = WAVE_NAMES.get(wv.kind, (wv.kind, ""))[0]
        rows.append(
            f"| {name} | {fmt_pm(wv.velocity, wv.velocity_error)} | "
            f"{fmt_pm(wv.background, wv.background_error)} | {fmt_num(wv.amplitude, 5)} | "
            f"{fmt_num(wv.left_state, 5)} | {fmt_num(wv.right_state, 5)} |"
        )
    kinds = dict.fromkeys(wv.kind for wv in waves)
    lines = [f"- **{WAVE_NAMES[k][0]}**: {WAVE_NAMES[k][1]}" for k in kinds if k in WAVE_NAMES]
    lines.append(
        "- ± of V: the fit's standard error plus the measured spread over fit windows and "
        "tracking thresholds; ± of w_B: its spread over the window and the thresholds"
    )
    return "**Waves found by the tracker**\n\n" + "\n".join(rows) + "\n\n" + "\n".join(lines)


class SimulationScene(BokehScene):
    title = "Simulation"
    caption = (
        "_Direct simulation of the FPU chain: strain w_n(t) in space and time, and the waves "
        "it forms. Paper: Figs. 13, 14, 16 and 17 (stabSK, "
        "Riemann1, stabSW, SWdyn)._"
    )
    plot_height = 380

    def controls(self):
        self.kind = pn.widgets.RadioButtonGroup(
            options={"TW-seeded": "seeded", "Riemann": "riemann", "Gaussian": "gaussian"},
            value="seeded",
        )
        # TW-seeded runs need L >= 900 (the seeding wave plus the margins): default 1000
        self.L = pn.widgets.IntInput(label="L (sites)", value=1000, start=50, end=20000, width=140)
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
        self.probes = pn.widgets.TextInput(
            name="tracked sites (e.g. 100, 200, 3000 for L = 3600)",
            value="",
            placeholder="site numbers, comma-separated",
            width=290,
        )
        self.run_btn = pn.widgets.Button(
            label="Run simulation", color="primary", css_classes=["simulation-run"]
        )
        return [
            self.kind,
            pn.Row(self.L, self.t_end),
            pn.Row(self.w_l, self.w_r),
            pn.Row(self.w_B, self.A),
            self.guard,
            self.probes,
            self.run_btn,
        ]

    def extra_panes(self):
        self.table = LiteralMarkdown("", sizing_mode="stretch_width", css_classes=["sim-table"])
        return [self.table]

    def _extra_watch(self):
        self._want_run = False
        self._request: compute.SimulationRequest | None = None
        self._sim = None

        def go(_):
            self._want_run = True
            self._inputs_to_url()  # a run with the widgets' defaults is a link's too
            self.request()

        self.run_btn.on_click(go)
        self._applying = False
        inputs = [self.kind, self.L, self.t_end, self.w_l, self.w_r, self.w_B, self.A,
                  self.guard, self.probes]  # fmt: skip
        for w in inputs:
            w.param.watch(lambda _: self._inputs_to_url(), "value")

    def _inputs(self) -> dict | None:
        """The widgets' run inputs (app.sim_url's keywords); None while the sites are not a
        list of numbers (the run names the problem)."""
        try:
            probes = self._probe_sites()
        except SceneMessage:
            return None
        data = {"w_left": self.w_l.value, "w_right": self.w_r.value, "w_B": self.w_B.value,
                "A": self.A.value}  # fmt: skip
        return dict(kind=self.kind.value, L=self.L.value, t_end=self.t_end.value,
                    guard=self.guard.value, probes=probes, **data)  # fmt: skip

    def _inputs_to_url(self) -> None:
        """The widgets into the state's ``simulation`` (the URL's sim=): a change the figure
        did not make leaves it (ExplorerState._leave_figure); its run is not on screen."""
        if self._applying:
            return
        inputs = self._inputs()
        if inputs is None or None in inputs.values():
            return
        try:
            text = sim_url.format_sim(**inputs)
        except (TypeError, ValueError):
            return
        if text != self.state.simulation:
            self.state.param.update(simulation=text, sim_shown=False)

    def show_scenario(self, kind: str, run: bool = False, probes=(), **params) -> None:
        """Set the initial-data widgets (a paper figure's run, app.paper_figures): ``kind``
        ("seeded", "riemann", "gaussian"), L, t_end, guard, w_left, w_right (Riemann), w_B, A
        (Gaussian) and the tracked sites; ``run``: the next render runs it (as "Run").  The
        caller renders (the scene's base class: at once if the scene is shown)."""
        widgets = {"L": self.L, "t_end": self.t_end, "guard": self.guard, "w_left": self.w_l,
                   "w_right": self.w_r, "w_B": self.w_B, "A": self.A}  # fmt: skip
        self._applying = True
        try:
            self.kind.value = kind
            for name, value in params.items():
                widgets[name].value = value
            self.probes.value = ", ".join(str(int(k)) for k in probes)
        finally:
            self._applying = False
        self._inputs_to_url()  # the figure's (or the link's) own: no change of the state
        self._want_run = bool(run)
        if not run:  # not the previous run's result under the new widgets: "press Run"
            self._params = None
        self.stale = True

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
            f = new_figure(f"({'cde'[k]}) site", "t", "w", height=240, width=300,
                           sizing_mode="stretch_width")  # fmt: skip
            site = add_line(f, "black", 1.5)
            site[1].name = f"sim-probe-{k}"  # read by the tests
            tw = add_line(f, "#d62728", 2.0, "dashed")
            tw[1].name = f"sim-probe-wave-{k}"
            entries = [("w_k(t)", [site[0]]), ("TW at measured V, w_B", [tw[0]])]
            self.probe_legend.append(add_legend(f, "below", entries))
            f.visible = False
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
        probes = row(*self.fig_probe, sizing_mode="stretch_width")
        return column(fi, fp, probes, sizing_mode="stretch_width")

    def _job(self) -> compute.SimulationRequest:
        """The run the widgets ask for (ParameterError for a value it cannot take)."""
        s = self.state
        kind = self.kind.value
        run = dict(L=int(self.L.value), t_end=float(self.t_end.value), guard=self.guard.value,
                   probes=self._probe_sites())  # fmt: skip
        if kind == "riemann":
            return compute.RiemannRequest(
                w_left=float(self.w_l.value), w_right=float(self.w_r.value), **run
            )
        if kind == "gaussian":
            return compute.GaussianRequest(w_B=float(self.w_B.value), A=float(self.A.value), **run)
        if s.problem() is not None:
            raise SceneMessage(s.problem())
        wave = compute.WaveRequest(s.mode, s.w_plus, s.V, int(s.N), s.tol)
        return compute.SeededRequest(wave=wave, **run)

    def _probe_sites(self) -> tuple[int, ...]:
        """The typed sites (fpucore checks them against L when the run starts)."""
        text = self.probes.value.strip()
        if not text:
            return ()
        try:
            sites = tuple(int(x) for x in re.split(r"[,\s]+", text) if x)
        except ValueError:
            raise SceneMessage(
                f"tracked sites: {text} is not a list of site numbers (e.g. 100, 200, 3000)"
            ) from None
        if len(sites) > MAX_PROBES:
            raise SceneMessage(f"tracked sites: at most {MAX_PROBES} (the panels (c)–(e))")
        return sites

    def _tracked_sites(self, info: Info, up: Updates, sim) -> None:
        """Panels (c)–(e): each tracked site's history against the wave computed at the
        measured V and w_B of the last tracked wave to pass it."""
        sites = list(np.asarray(getattr(sim, "probe_sites", []), int))
        self._probe_waves = []
        s = self.state
        for k in range(MAX_PROBES):
            fig = self.fig_probe[k]
            if k >= len(sites):
                up.set(fig, visible=False)
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
            up.set(fig, visible=True)
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
        c = compute.discrete_wave(s.law(), mode, w_plus, V, s.N, s.tol, stop=self.superseded)
        r = c.value
        info.time(f"wave at V = {V:.6g}", c)
        req = compute.WaveRequest(mode, w_plus, V, s.N, s.tol)
        return r, compute.wave_call(s.law(), req).code()

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
        c = compute.simulation(
            s.law(), req, stop=self.superseded, progress=self.stage_progress("simulation")
        )
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
            code += f"r = {compute.wave_call(self.state.law(), req.wave).code()}\n"
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
