"""The explorer's single state owner: parameters, slider ranges and validity.

``ExplorerState`` holds what a link must reproduce (law, w_plus, V, mode, tab, N, tol, held
curves, the paper figure) and derives from fpucore's QC functions the sliders' ranges: w_plus
where superkinks exist (w* excluded); V in (c_+, V_SK) ∪ (V_SK, c_-) (eq. wB), or V = V_SK(w_plus)
in superkink mode (eq. cubic_cond2), where moving one moves the other along the branch.
Parameters are unbounded (a URL may carry anything): ``problem()`` says in one sentence what is
wrong, and views show that sentence instead of a plot.
"""

from __future__ import annotations

import contextlib
import math
import threading

import param

from fpucore import qc
from fpucore.errors import ParameterError

from . import compute, paper_figures
from .held_wave import HeldWave
from .scene_registry import TABS
from .sim_url import format_sim, sc_inputs

MODES = ("solitary", "superkink")
#: what the sliders (and so the URL) may set; N even (fpucore's N_MIN = 64)
A_RANGE = (-5.0, -0.1)
B_RANGE = (1.0, 20.0)
N_RANGE = (64, 4000)
TOL_OPTIONS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13)
#: longest URL value read (a 5000-digit value is refused before any conversion; a law: below)
MAX_URL_VALUE = 40
MAX_URL_LAW = 200
#: longest wait of a page build for the URL's law (the server's event loop waits meanwhile)
URL_LAW_WAIT_S = 0.1
URL_PARAMS = (
    "a", "b", "law", "w_plus", "V", "mode", "tab", "N", "tol", "atlas", "hold", "fig", "sim", "run"
)  # fmt: skip
#: URL name → state parameter where they differ (``law()`` is the state's law object)
URL_ATTRS = {"law": "expression", "hold": "held", "fig": "figure", "sim": "simulation",
             "run": "sim_shown"}  # fmt: skip
#: curves held at once (Hold on Wave profiles and Phase plane; the oldest goes first)
MAX_HELD = 6
MAX_URL_HOLD = 400  #: longest ``hold`` value: MAX_HELD entries of two exact floats, and room
#: the state parameters a URL holds, in URL_PARAMS order
STATE_PARAMS = tuple(URL_ATTRS.get(n, n) for n in URL_PARAMS)
#: the state parameters a paper figure sets: a change of one of them leaves the figure
FIGURE_PARAMS = ("a", "b", "expression", "w_plus", "V", "mode", "N", "held")


class ExplorerState(param.Parameterized):
    """Single source of truth for the dashboard (synced with the URL query string)."""

    a = param.Number(-1.0, doc="cubic coefficient a < 0 of f(w) = a w^3 + b w^2 + w")
    b = param.Number(10.0, doc="quadratic coefficient b > 0")
    expression = param.String(
        "", doc="the law as text for fpucore.law_from_expression; empty: the cubic (a, b)"
    )
    w_plus = param.Number(1.0, doc="strain w_+ ahead of the superkink")
    V = param.Number(5.0, doc="velocity V > 0")
    mode = param.Selector(default="solitary", objects=list(MODES))
    tab = param.Selector(default=TABS[0], objects=list(TABS))
    N = param.Integer(500, doc="number of lattice sites of the discrete solve (even)")
    tol = param.Number(1e-10, doc="Newton tolerance of the discrete solve")
    atlas = param.String("", doc="the Atlas scene's store, relative to ATLAS_ROOT; empty: none")
    held = param.List([], item_type=HeldWave, doc="held curves (oldest first), at most MAX_HELD")
    figure = param.String("", doc="the paper figure the view was opened from, while it is its")
    #: what the Simulation scene is told to show (a figure's FIGURE_SCENARIO, a link's sim=)
    scenario = param.Dict(None, allow_None=True)
    simulation = param.String("", doc="the Simulation scene's inputs, app.sim_url (URL sim=)")
    sim_shown = param.Boolean(False, doc="their run is on screen (URL run=1: a link reruns it)")
    figure_shown = param.Event(doc="show_figure has set the state (its steps rendered nothing)")
    #: what the state changed by itself (e.g. V moved with w_plus), shown in the sidebar
    note = param.String("")

    def __init__(self, **params):
        super().__init__(**params)
        #: handler threads and law answers change the state one at a time (app.widgets)
        self.lock = threading.RLock()
        self._tying = False
        self._in_tie = False
        self.showing_figure = False  # while show_figure sets the state in its steps
        self._solitary_V = self.V if self.mode == "solitary" else None
        self.param.watch(self._tie, ["w_plus", "V", "mode", "a", "b", "expression"])
        self.param.watch(self._leave_figure, [*FIGURE_PARAMS, "simulation"])
        if self.mode == "superkink":
            self._tie_superkink(from_V=False)

    # ------------------------------------------------------------------ derived quantities
    def law(self):
        """CubicLaw(a, b), or the PolynomialLaw of ``expression`` when it is set; raises
        ParameterError for invalid a, b or an expression outside the law class."""
        return compute.laws.make_law(self.a, self.b, self.expression)

    def law_key(self) -> tuple:
        return compute.laws.law_key(self.law())  # the exact cache-key form of the law

    def w_plus_range(self) -> tuple[float, float, float]:
        """(lo, w*, hi): w_plus ranges over (lo, hi) without w*, where superkinks of either
        branch exist ((alpha, beta) for the cubic, eq. cubic_more; else w₋ stays in (alpha,
        beta)); an infinite end gets a finite window, as in qc.diagram.existence_diagram."""
        lw = self.law()
        lo = qc.superkink_w_plus_range(lw, "lower")[0]
        hi = qc.superkink_w_plus_range(lw, "upper")[1]
        if not math.isfinite(lo):
            lo = lw.w_star - 4.0 * (hi - lw.w_star)
        if not math.isfinite(hi):
            hi = lw.w_star + 4.0 * (lw.w_star - lo)
        return lo, lw.w_star, hi

    def speeds(self) -> tuple[float, float, float]:
        """(c_+, V_SK, c_-) for the current w_plus (eqs. cplus, cubic_cond2, cminus_cubic)."""
        return qc.sound_speeds(self.law(), self.w_plus)

    def V_range(self) -> tuple[float, float]:
        """Slider range of V: (c_+, c_-) in solitary mode, the superkink bounds otherwise."""
        if self.mode == "superkink":
            return qc.superkink_velocity_bounds(self.law())
        cp, _, cm = self.speeds()
        return cp, cm

    def problem(self) -> str | None:
        """None if (a, b, w_plus, V, mode) defines a wave, else a one-sentence explanation."""
        try:
            lw = self.law()
            if self.mode == "superkink":
                sk = qc.superkink_from_w_plus(lw, self.w_plus)
                if abs(self.V - sk.V) > 1e-9 * sk.V:
                    qc.superkink_from_V(lw, self.V)  # raises with the superkink V interval
                    return f"in superkink mode V = V_SK(w_plus) = {sk.V:.10g}, not {self.V:.10g}"
            else:
                qc.solitary_intervals(lw, self.w_plus)
                cp, vsk, cm = qc.sound_speeds(lw, self.w_plus)
                if self.V == vsk:
                    return (
                        f"V = V_SK = {vsk:.10g} is the superkink itself: switch the mode to "
                        "'superkink' or move V into (c+, V_SK) or (V_SK, c-)."
                    )
                # its refusals without its profile (near a sonic end a profile took ~0.8 s)
                qc.solitary_kind(lw, self.w_plus, self.V)
        except ParameterError as exc:
            return str(exc)
        return None

    def summary(self) -> dict:
        """The numbers the sidebar shows (NaN-free: invalid parts are left out)."""
        out: dict = {}
        try:
            lw = self.law()
            lo, ws, hi = self.w_plus_range()
            out.update(alpha=lw.alpha, w_star=ws, beta=lw.beta, w_lo=lo, w_hi=hi)
            if (hard := getattr(lw, "hard_regime", None)) is not None:
                out["hard"] = hard  # a piecewise-linear law: [w₁, w₂] in place of w*
            cp, vsk, cm = self.speeds()
            out.update(c_plus=cp, V_SK=vsk, c_minus=cm)
        except ParameterError:
            return out
        with contextlib.suppress(ParameterError):
            out["V_lo"], out["V_hi"] = qc.superkink_velocity_bounds(self.law())
        return out

    def kind(self) -> str:
        """What the current parameters describe: superkink / tensile / compressive / invalid."""
        if self.problem() is not None:
            return "invalid"
        if self.mode == "superkink":
            return "superkink"
        return qc.solitary_kind(self.law(), self.w_plus, self.V)

    def set_typed_N(self, value) -> None:
        """N typed into the box beside the slider: an odd N goes to the even N below it and one
        outside N_RANGE to the nearest end; ``note`` says so (never silently)."""
        if value is None:
            return
        N = int(value)
        fixed = min(max(N - N % 2, N_RANGE[0]), N_RANGE[1])
        self.N = fixed
        if fixed != N:
            why = "odd" if N_RANGE[0] <= N <= N_RANGE[1] else "outside the range"
            self.note = (
                f"N = {N} is {why}: using N = {fixed} (an even integer in "
                f"[{N_RANGE[0]}, {N_RANGE[1]}])"
            )

    # ------------------------------------------------------------------ coupling
    @contextlib.contextmanager
    def _untied(self):
        """Updates made by the coupling itself: :meth:`_tie` ignores them (no re-entry)."""
        self._tying = True
        try:
            yield
        finally:
            self._tying = False

    @property
    def adjusting(self) -> bool:
        """True while the coupling updates the state inside another change's watchers."""
        return self._in_tie

    def _tie(self, *events):
        if self._tying:
            return
        self._in_tie = True
        try:
            self._tie_events(events)
        finally:
            self._in_tie = False

    def _tie_events(self, events) -> None:
        names = {e.name for e in events}
        self.note = ""
        if "expression" in names and not names & {"w_plus", "V"}:
            self._fit_to_law()
        if "mode" in names and self.mode == "solitary":
            self._back_to_solitary()
        if self.mode == "superkink":
            if "mode" in names:
                old = [e.old for e in events if e.name == "V"]
                self._solitary_V = old[0] if old else self.V
            self._tie_superkink(from_V=names == {"V"})
        elif "w_plus" in names and "V" not in names and len(events) == 1:
            self._remap_V(events[0].old)

    def _fit_to_law(self) -> None:
        """A new law: a w_plus outside its w_plus range (or at w*) moves into the middle of the
        lower branch's range, and a solitary V outside the new intervals to the middle of
        (c₊, V_SK); ``note`` says so.  (The superkink tie then follows in _tie.)"""
        try:
            lo, ws, hi = self.w_plus_range()
        except ParameterError:
            return  # an invalid law: problem() explains it
        moved = []
        new: dict = {}
        at_w_star = abs(self.w_plus - ws) <= 1e-9 * max(1.0, abs(ws))
        if not (lo < self.w_plus < hi) or at_w_star or self._in_hard_regime(self.w_plus):
            new["w_plus"] = self._lower_middle(lo, ws)
            moved.append(f"w₊ from {self.w_plus:.8g} to {new['w_plus']:.8g}")
        wp = new.get("w_plus", self.w_plus)
        if self.mode == "solitary":
            try:
                (cp, vsk), (_, cm) = qc.solitary_intervals(self.law(), wp)
            except ParameterError:
                cp = vsk = cm = math.nan
            if math.isfinite(vsk) and not (cp < self.V < vsk or vsk < self.V < cm):
                new["V"] = 0.5 * (cp + vsk)
                moved.append(f"V from {self.V:.8g} to {new['V']:.8g}")
        if not new:
            return
        with self._untied():
            self.param.update(**new)
        self.note = "new law: " + " and ".join(moved) + " (outside the new law's ranges)"

    def _in_hard_regime(self, w_plus: float) -> bool:
        """A piecewise-linear law's hard regime [w₁, w₂] (its w*: no wave from there)."""
        hard = getattr(self.law(), "hard_regime", None)
        return hard is not None and hard[0] <= w_plus <= hard[1]

    def _lower_middle(self, lo: float, ws: float) -> float:
        """A new law's w₊: the middle of its lower branch (lo, w*); for a piecewise-linear law
        that of its soft regime's part (max(lo, 0), w₁) ((lo, w*) contains [w₁, w*])."""
        hard = getattr(self.law(), "hard_regime", None)
        if hard is None:
            return lo + 0.5 * (ws - lo)
        a = max(lo, 0.0) if hard[0] > 0.0 else lo
        return a + 0.5 * (hard[0] - a)

    def _back_to_solitary(self) -> None:
        """Superkink → solitary: V = V_SK is no solitary wave.  Return to the solitary V used
        before if it is valid for the current w_plus, else to the middle of (c₊, V_SK)."""
        try:
            lw = self.law()
            (cp, vsk), (_, cm) = qc.solitary_intervals(lw, self.w_plus)
        except ParameterError:
            return
        V0 = self._solitary_V
        if V0 is not None and (cp < V0 < vsk or vsk < V0 < cm):
            newV = V0
        elif cp < self.V < vsk or vsk < self.V < cm:
            return
        else:
            newV = 0.5 * (cp + vsk)
        with self._untied():
            self.V = newV

    def _tie_superkink(self, from_V: bool) -> None:
        """Keep V = V_SK(w_plus) (or w_plus = w_+(V) on the same branch) in superkink mode."""
        try:
            lw = self.law()
            if from_V:
                branch = "lower" if self.w_plus < lw.w_star else "upper"
                new = {"w_plus": qc.superkink_from_V(lw, self.V, branch=branch).w_plus}
            else:
                new = {"V": qc.superkink_from_w_plus(lw, self.w_plus).V}
        except ParameterError:
            return  # leave the invalid value in place: problem() explains it
        with self._untied():
            self.param.update(**new)

    def _remap_V(self, old_w_plus: float) -> None:
        """Solitary mode: when w_plus moves, V stays where it is if it is still valid; only if
        it left the new intervals is it moved to the same relative position inside the same
        interval (below/above V_SK) — and ``note`` says so (never silently)."""
        try:
            lw = self.law()
            (cp0, vsk0), (_, cm0) = qc.solitary_intervals(lw, old_w_plus)
            (cp1, vsk1), (_, cm1) = qc.solitary_intervals(lw, self.w_plus)
        except ParameterError:
            return
        V = self.V
        if cp1 < V < vsk1 or vsk1 < V < cm1:
            return
        if cp0 < V < vsk0:
            s, (lo, hi) = (V - cp0) / (vsk0 - cp0), (cp1, vsk1)
        elif vsk0 < V < cm0:
            s, (lo, hi) = (V - vsk0) / (cm0 - vsk0), (vsk1, cm1)
        else:
            return
        newV = lo + s * (hi - lo)
        if math.isfinite(newV) and lo < newV < hi:
            with self._untied():
                self.V = newV
            self.note = (
                f"V moved from {V:.8g} to {newV:.8g}: {V:.8g} is outside ({lo:.8g}, {hi:.8g}) "
                f"at w₊ = {self.w_plus:.8g}"
            )

    # ------------------------------------------------------------------ held curves, figures
    def hold(self, wave: HeldWave) -> None:
        """Hold ``wave`` (again: it moves to the end); past MAX_HELD the oldest goes, and
        ``note`` says which."""
        new = [*(h for h in self.held if h != wave), wave]
        if len(new) > MAX_HELD:
            gone = ", ".join(h.label() for h in new[:-MAX_HELD])
            self.note = f"at most {MAX_HELD} held curves: {gone} let go"
        self.held = new[-MAX_HELD:]

    def current_wave(self) -> HeldWave | None:
        """The current wave as a held curve (None while the parameters show no wave)."""
        if self.problem() is not None:
            return None
        if self.mode == "superkink":
            return HeldWave("superkink", float(self.w_plus))
        return HeldWave("solitary", float(self.w_plus), float(self.V))

    def show_figure(self, label: str) -> None:
        """The state of paper figure ``label`` (app.paper_figures): in steps — the tab first,
        alone, so that a scene not built yet is built and sent to the browser exactly as on a
        tab click, before any render of it (built in the same update as the parameters, its
        render's patches named models the browser did not have); then the law and mode (the
        tie of V to w₊ acts on the new mode); then w₊, N and V; then the held curves, the
        figure and the Simulation scene's initial data; then ``figure_shown`` (the views render
        once, not at each step).  ParameterError for an unknown label."""
        if label not in paper_figures.FIGURE_STATE:
            raise ParameterError("fig", label, "one of " + ", ".join(paper_figures.FIGURE_STATE))
        tab, mode, w_plus, V, N = paper_figures.FIGURE_STATE[label]
        self.showing_figure = True
        try:
            self.tab = tab
            self.param.update(a=-1.0, b=10.0, expression="", mode=mode)
            tol = paper_figures.FIGURE_TOL.get(label, self.param.tol.default)
            new = {"w_plus": w_plus, "N": N, "tol": tol}
            if V is not None:
                new["V"] = V
            self.param.update(**new)
            held = [HeldWave(*h) for h in paper_figures.FIGURE_HELD.get(label, ())]
            self.param.update(held=held, figure=label)
            sc = paper_figures.FIGURE_SCENARIO.get(label)
            if sc is not None:  # the widgets' values, whether the click starts the run, the URL
                sc = {k: v for k, v in sc.items() if k != "run_s"}
                sc["run"] = paper_figures.scenario_runs(label)
                self.param.update(simulation=format_sim(**sc_inputs(sc)), sim_shown=False)
            if sc is not None and sc == self.scenario:
                self.param.trigger("scenario")  # the same figure again: its widgets again
            else:
                self.scenario = sc
        finally:
            self.showing_figure = False
            self.param.trigger("figure_shown")  # the views render the figure's state once
        self.note = paper_figures.FIGURE_NOTE.get(label, "")

    def _leave_figure(self, *events) -> None:
        """A change the figure did not make: the view is no longer the figure's (the URL drops
        its ``fig``), and a Simulation scene built later keeps its own initial data."""
        if self.showing_figure or not self.figure:
            return
        self.figure = ""
        self.scenario = None

    # ------------------------------------------------------------------ actions
    def pick(self, w_plus: float, V: float, N: int | None = None) -> None:
        """Set (w_plus, V) at once (and N, when given), e.g. from a click on the existence
        diagram or an atlas cell; V < 0 clicks (the diagram is symmetric) are mirrored to V > 0."""
        with self.lock:
            with self._untied():
                extra = {} if N is None else {"N": int(N)}
                self.param.update(w_plus=float(w_plus), V=abs(float(V)), **extra)
            if self.mode == "superkink":
                self._tie_superkink(from_V=False)
