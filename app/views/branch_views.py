"""The Diagrams scene's branch views (Figs. floquet_cubicSW, stabSW, floquet_SK, drawn as MatCont /
AUTO draw branches): a family's Floquet sweep through app.compute (on demand, or when cached),
each wave in its class's colour — the solitary family's discrete E_ren on panel (b), the superkink
family's amplitude |w₋ − w₊| on panel (d) (a superkink has no E_ren: it joins two different
states) — and a click on a point opens that wave.

A mixin of :class:`app.views.diagram.DiagramScene`, which builds the figures and sources these
methods fill (``fig_e``, ``fig_sk``, ``r_branch``, ``r_sk``, legends) and calls
:meth:`BranchViews._branch_view` from its render.
"""

from __future__ import annotations

from contextlib import nullcontext

import numpy as np
from bokeh.events import Tap
from panel.io.state import set_curdoc

from fpucore import qc
from fpucore.floquet import CLASSES

from .. import compute
from .bokeh_scene import Updates
from .class_style import CLASS_STYLE
from .report import Info


class BranchViews:
    """Panel (b)'s solitary branch and panel (d)'s superkink branch, with their clicks."""

    def _on_branch_tap(self, event: Tap) -> None:
        """A click on (b) near a classified wave opens it (state.pick(w₊, V)); elsewhere it
        does nothing.  Runs on the session's loop, like the existence diagram's click."""
        V = self.branch_point(event.x, event.y)
        if V is None:
            return
        doc = self._doc
        with set_curdoc(doc) if doc is not None else nullcontext():
            if self.state.mode != "solitary":  # the branch is the solitary family's
                self.state.mode = "solitary"
            self.state.pick(self._branch.w_plus, V)

    def _on_sk_tap(self, event: Tap) -> None:
        """A click on (d) near a classified superkink opens it: V, and w₊ = w₊(V) on the
        sweep's branch (the state keeps V = V_SK(w₊)).  Runs on the session's loop."""
        V = self.sk_point(event.x, event.y)
        if V is None:
            return
        lw, branch = self.state.law(), self._sk_branch[2]
        doc = self._doc
        with set_curdoc(doc) if doc is not None else nullcontext():
            if self.state.mode != "superkink":
                self.state.mode = "superkink"
            self.state.pick(qc.superkink_from_V(lw, V, branch=branch).w_plus, V)

    def sk_point(self, x, y) -> float | None:
        """V of the classified superkink nearest to (x, y) on (d), within 3 % of both spans."""
        if self._sk_branch is None or x is None or y is None:
            return None
        sw, amp, _ = self._sk_branch
        return _nearest(sw.V, amp, x, y, self.fig_sk)

    def branch_point(self, x, y) -> float | None:
        """V of the classified wave nearest to (x, y) on (b), if within 3 % of both axes' spans
        (a click, not anywhere on the panel); None otherwise."""
        sw = self._branch
        if sw is None or x is None or y is None:
            return None
        return _nearest(sw.V, sw.energy, x, y, self.fig_e)

    def _branch_view(self, info: Info, up: Updates, fam) -> None:
        """The family's Floquet sweep (on demand, or when cached) on (b), coloured by class;
        in superkink mode the button sweeps the superkinks instead, on (d)."""
        s = self.state
        lw = s.law()
        req = compute.SweepRequest("solitary", s.w_plus, self._velocities(fam), s.N, "lower")
        self._branch = None
        want = self._want_branch and s.mode == "solitary"
        if want or compute.is_cached(lw, req):
            # the request is the mode's own: a cached solitary sweep redrawn in superkink mode
            # leaves the button's request to the superkink sweep
            self._want_branch = self._want_branch and not want
            c = compute.run(lw, req, **self.job_hooks("Floquet sweep"))
            self._branch = c.value
            info.time(f"Floquet sweep ({len(req.V_values)} V)", c)
        sw = self._branch
        cls = np.array([c or "" for c in sw.classification]) if sw is not None else np.array([])
        for c, (r, src) in self.r_branch.items():
            if sw is None:
                sel = np.zeros(0, bool)
                up.data(src, x=[], y=[])
            else:
                E = np.asarray(sw.energy, float)
                sel = (cls == c) & np.isfinite(E)
                up.data(src, x=np.asarray(sw.V, float)[sel], y=E[sel])
            up.show(r, self.branch_legend[CLASSES.index(c)], bool(sel.any()))
        if sw is not None:
            words = _class_counts(info, cls, sw, "sweep")
            info.notes.append(f"branch view (N = {int(s.N)}): {words}; click a point to open it")
        self._superkink_branch(info, up)

    def _superkink_args(self):
        """The superkink sweep (law, SweepRequest), and the velocity interval: 2k midpoints of
        the superkink velocity interval (k = discrete points per interval, as for the solitary
        family's two intervals), on the branch of the current w₊."""
        s = self.state
        lw = s.law()
        branch = "lower" if s.w_plus < lw.w_star else "upper"
        lo, hi = qc.superkink_velocity_bounds(lw, branch)
        k = 2 * int(self.n_discrete.value)
        Vs = list(lo + (hi - lo) * (np.arange(k) + 0.5) / k)
        return (lw, compute.SweepRequest("superkink", None, Vs, s.N, branch)), (lo, hi)

    def _superkink_branch(self, info: Info, up: Updates) -> None:
        """(d): the superkink family's Floquet sweep (on demand in superkink mode, or when
        cached), each superkink's amplitude w₋ − w₊ in its class's colour."""
        s = self.state
        self._sk_branch = None
        try:
            args, (lo, hi) = self._superkink_args()
        except compute.ParameterError:
            args = None
        want = self._want_branch and s.mode == "superkink" and args is not None
        if args is not None and (want or compute.is_cached(*args)):
            self._want_branch = self._want_branch and not want
            lw, req = args
            c = compute.run(lw, req, **self.job_hooks("superkink sweep"))
            sw, branch = c.value, req.branch
            info.time(f"superkink Floquet sweep ({len(req.V_values)} V)", c)
            amp = np.array([_sk_amplitude(lw, v, branch) for v in sw.V])
            self._sk_branch = (sw, amp, branch)
            Vq = np.linspace(lo, hi, 202)[1:-1]
            up.data(self.sk_line[1], x=Vq, y=[_sk_amplitude(lw, v, branch) for v in Vq])
            up.range(self.fig_sk.x_range, lo, hi, pad=0.03)
            up.range(self.fig_sk.y_range, 0.0, float(np.nanmax(amp)) * 1.1 if amp.size else 1.0)
            up.set(self.sk_V, location=float(s.V), visible=s.mode == "superkink")
            up.set(
                self.fig_sk.title,
                text=f"(d) superkinks ({branch} branch, N = {int(s.N)}) by Floquet class — "
                "click a point to open it",
            )
        up.set(self.fig_sk, visible=self._sk_branch is not None)
        cls = (
            np.array([])
            if self._sk_branch is None
            else np.array([c or "" for c in self._sk_branch[0].classification])
        )
        for c, (r, src) in self.r_sk.items():
            sel = cls == c
            if self._sk_branch is None:
                up.data(src, x=[], y=[])
            else:
                sw, amp, _ = self._sk_branch
                up.data(src, x=np.asarray(sw.V, float)[sel], y=amp[sel])
            up.show(r, self.sk_legend[CLASSES.index(c)], bool(sel.any()))
        if self._sk_branch is not None:
            sw = self._sk_branch[0]
            words = _class_counts(info, cls, sw, "superkink sweep")
            info.notes.append(
                f"superkink branch view (N = {int(s.N)}, {len(sw.V)} V): {words}; a superkink "
                "has no E_ren (it joins two different states), so (d) draws its amplitude; "
                "click a point to open it"
            )
        self._want_branch = False  # a request neither view could serve (no valid family) ends


def _sk_amplitude(lw, V: float, branch: str) -> float:
    """|w₋ − w₊| of the superkink at V on ``branch`` (eq. wpm_cubic; the discrete superkink has
    the same limiting states: they follow from the conservation laws alone)."""
    sk = qc.superkink_from_V(lw, float(V), branch=branch)
    return abs(float(sk.w_minus - sk.w_plus))


def _nearest(xs_data, ys_data, x, y, fig) -> float | None:
    """The x of the data point nearest to the click (x, y) on ``fig``, if within 3 % of both
    axes' spans (a click on a point, not anywhere on the panel); None otherwise."""
    xs, ys = fig.x_range, fig.y_range
    dx = (np.asarray(xs_data, float) - x) / max(xs.end - xs.start, 1e-300)
    dy = (np.asarray(ys_data, float) - y) / max(ys.end - ys.start, 1e-300)
    d = np.where(np.isfinite(dx) & np.isfinite(dy), np.hypot(dx, dy), np.inf)
    k = int(np.argmin(d)) if d.size else -1
    return float(xs_data[k]) if k >= 0 and d[k] < 0.03 else None


def _class_counts(info: Info, cls: np.ndarray, sw, what: str) -> str:
    """ "2 stable, 2 not determined …" for the classes ``cls`` of the sweep ``sw``; its largest
    max|μ| error bar goes into the status's errors."""
    counts = {c: int((cls == c).sum()) for c in CLASSES if (cls == c).any()}
    err = np.asarray(sw.max_modulus_error, float)
    if np.isfinite(err).any():
        info.error(f"max |μ| error bound ({what})", float(np.nanmax(err)))
    return ", ".join(f"{n} {CLASS_STYLE[c][0].split(' (')[0]}" for c, n in counts.items())
