"""The Simulation scene's inputs: the initial-data widgets, the run they ask for (a typed
request of app.compute), their form in the URL (``sim=``, app.sim_url) and a paper figure's
initial data (``state.scenario``, app.paper_figures).

A mixin of :class:`app.views.simulation.SimulationScene`, which wires the widgets to these
methods when it is built.
"""

from __future__ import annotations

import re

import panel as pn

from .. import compute, sim_url
from .report import SceneMessage
from .simulation_table import MAX_PROBES


class SimulationInputs:
    """The widgets, the request they make and their URL form."""

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

    def _inputs(self) -> dict | None:
        """The widgets' run inputs (app.sim_url's keywords); None while the sites are not a
        list of numbers (the run names the problem)."""
        try:
            probes = self._probe_sites()
        except SceneMessage:
            return None
        data = {
            "w_left": self.w_l.value,
            "w_right": self.w_r.value,
            "w_B": self.w_B.value,
            "A": self.A.value,
        }
        return dict(
            kind=self.kind.value,
            L=self.L.value,
            t_end=self.t_end.value,
            guard=self.guard.value,
            probes=probes,
            **data,
        )

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
        widgets = {
            "L": self.L,
            "t_end": self.t_end,
            "guard": self.guard,
            "w_left": self.w_l,
            "w_right": self.w_r,
            "w_B": self.w_B,
            "A": self.A,
        }
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

    def _job(self) -> compute.SimulationRequest:
        """The run the widgets ask for (ParameterError for a value it cannot take)."""
        s = self.state
        kind = self.kind.value
        run = dict(
            L=int(self.L.value),
            t_end=float(self.t_end.value),
            guard=self.guard.value,
            probes=self._probe_sites(),
        )
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

    def _on_scenario(self, event) -> None:
        """A paper figure set this scene's initial data: shown now, and run if it asks."""
        if not event.new:
            return
        if self.state.tab != self.key:
            self.show_scenario(**event.new)  # run (if asked) when the tab is opened
            return
        self.request(prepare=lambda: self.show_scenario(**event.new))
