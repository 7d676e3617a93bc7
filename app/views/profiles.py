"""Scene 3 — strain profiles (Figs. TWcubic, SWs_cubic, SWs_cubic_DvsQC).

The QC profile w(ξ) (solid, closed form eqs. SKsoln_cubic / SWsoln_cubic) with the discrete
traveling wave w_n(0) (circles, fixed point of eq. nonlin_map at N sites, tolerance tol)
overlaid.  Near V_SK a solitary wave is a kink–antikink bundle: the superkink fronts are drawn
(dashed) at the two boundary layers.  The QC curve is shown at once; the discrete solve follows.
"""

from __future__ import annotations

import time

import numpy as np
import panel as pn

from .. import compute
from ..compute.cache import exact
from ..state import N_RANGE
from .bokeh_scene import (
    BokehScene,
    Updates,
    add_legend,
    add_line,
    add_points,
    finite_extent,
    new_figure,
)
from .formatting import as_csv, fmt_num, provenance
from .held import Held, HeldCurves
from .python_code import python_preamble
from .report import Info, SceneMessage
from .scene import Scene
from .untrusted import md_literal


def n_advice(need: int, N: int) -> str:
    """What to do about N, in words, with an N the dashboard can set."""
    if need > N_RANGE[1]:
        return (
            f"This wave needs about N = {need} sites, more than the dashboard's {N_RANGE[1]}: "
            "move V away from the sonic limit c₊."
        )
    if need != N:
        return f"fpucore's own choice for this wave is N = {need}: set it in the accuracy card."
    return "Try a larger N (accuracy card) or move V away from V_SK."


class ProfilesScene(BokehScene):
    title = "Wave profiles"
    caption = (
        "_Strain profile of the traveling wave: quasicontinuum closed form (line) and the "
        "discrete chain's wave at N sites (circles). Paper: Figs. 5, 7 and 8 (SWs_cubic, "
        "TWcubic, SWs_cubic_DvsQC)._"
    )
    depends = (*Scene.depends, "held")

    def controls(self):
        self.show_discrete = pn.widgets.Checkbox(label="discrete wave (N, tol)", value=True)
        self.show_fronts = pn.widgets.Checkbox(label="kink/antikink fronts near V_SK", value=True)
        self.held = HeldCurves(self.state, self.request, "profiles")
        self.held.set_source(lambda: self.last_info is not None and bool(getattr(self, "_cols", 0)))
        return [self.show_discrete, self.show_fronts, *self.held.widgets()]

    def __init__(self, state):
        super().__init__(state)
        for w in (self.show_discrete, self.show_fronts):
            w.param.watch(lambda e: self.request(), "value")

    def build(self):
        fig = new_figure(
            "Strain profile: quasicontinuum (line) and discrete chain (circles)",
            "ξ",
            "w",
            sizing_mode="stretch_width",
            height=self.plot_height,
        )
        self.fig = fig
        self.r_qc = add_line(fig, "#1f77b4", 2.5)
        self.r_fronts = [add_line(fig, "#d62728", 1.5, "dashed") for _ in range(2)]
        self.r_dots = add_points(
            fig, "circle", 6, fill_color="white", line_color="black", line_width=1
        )
        self.r_qc[1].name, self.r_dots[1].name = "profile-qc", "profile-discrete"
        held = self.held.build(fig, "profile-held")
        self.legend = add_legend(
            fig,
            "right",
            [
                ("QC", [self.r_qc[0]]),
                ("kink / antikink fronts", [r for r, _ in self.r_fronts]),
                ("discrete", [self.r_dots[0]]),
                *held,
            ],
        )
        self.held_items = self.legend[3:]
        return fig

    def _half(self, qcw, mode: str) -> float:
        """Half-width of the ξ window that shows the wave ``qcw`` (and of its discrete sites)."""
        half = max((8.0 if mode == "superkink" else 14.0) * qcw.width, 25.0)
        return min(half, 0.5 * self.state.N) if self.show_discrete.value else half

    def _held_curve(self, wave, dots: bool) -> Held:
        """A held wave's QC profile on its own window and, with ``dots``, its discrete wave at
        the current N and tol (both through app.compute, cached)."""
        s = self.state
        lw = s.law()
        q = compute.run(lw, compute.QCWaveRequest(wave.mode, wave.w_plus, wave.V)).value
        wp = float(wave.w_plus)
        if wave.mode == "superkink":
            qcall = f"qc.superkink_from_w_plus(law, {wp!r})"
        else:
            qcall = f"qc.solitary(law, {wp!r}, {float(wave.V)!r})"
        half = self._half(q, wave.mode)
        xi = np.linspace(-half, half, 1601)
        px = py = np.empty(0)
        dcall = "None"
        if dots:
            try:
                req = compute.WaveRequest(wave.mode, wp, q.V, s.N, s.tol)
                r = compute.run(lw, req, **self.job_hooks())
            except compute.ParameterError:  # N too small for its tails: no points (noted)
                r = None
            if r is not None and r.value.converged:
                r = r.value
                dcall = req.call(lw).code("law")
                sel = np.abs(r.n) <= half
                px, py = r.n[sel].astype(float), r.w[sel]
        code = f"held.append(({qcall}, {dcall}))"
        return Held(wave.label(q.V), xi, q.profile(xi), px, py, code)

    def _held_dots_cached(self) -> bool:
        """Whether every held wave's discrete wave is in the cache (no solve to wait for)."""
        s = self.state
        lw = s.law()

        def cached(h) -> bool:
            try:
                V = compute.run(lw, compute.QCWaveRequest(h.mode, h.w_plus, h.V)).value.V
            except compute.ParameterError:
                return True  # no wave under this law: nothing to solve (the notes say why)
            try:
                return compute.is_cached(lw, compute.WaveRequest(h.mode, h.w_plus, V, s.N, s.tol))
            except compute.ParameterError:
                return False  # not a request: the render solves (and refuses) it

        return all(cached(h) for h in s.held)

    def _qc_part(self, info: Info, up: Updates):
        s = self.state
        lw = s.law()
        c = compute.run(lw, compute.QCWaveRequest(s.mode, s.w_plus, s.V))
        qcw = c.value
        info.time(f"QC {compute.laws.qc_method(lw)}", c)
        if s.mode == "superkink":
            info.error("QC Rayleigh residual", qcw.rayleigh_residual)
            what = (
                f"superkink V = {fmt_num(qcw.V)}, w₊ = {fmt_num(qcw.w_plus)}, "
                f"w₋ = {fmt_num(qcw.w_minus)}"
            )
        else:
            info.error("QC first-integral residual", qcw.first_integral_residual)
            what = (
                f"{qcw.kind} solitary wave V = {fmt_num(qcw.V)}, w_B = {fmt_num(qcw.w_B)}, "
                f"amplitude {fmt_num(qcw.amplitude)}"
            )
        half = self._half(qcw, s.mode)
        self._half_shown = half
        xi = np.linspace(-half, half, 1601)
        wq = qcw.profile(xi)
        key = (s.mode, compute.laws.law_key(lw), exact(s.w_plus), exact(s.V), exact(half))
        up.data(self.r_qc[1], key, x=xi, y=wq)
        self._cols = {"xi": xi, "w_qc": wq}
        fronts = []
        if s.mode == "solitary" and self.show_fronts.value:
            fronts = self._fronts(qcw, xi, info)
        for k, (_, src) in enumerate(self.r_fronts):
            y = fronts[k] if fronts else np.empty(0)
            up.data(src, key + (bool(fronts),), x=xi if fronts else np.empty(0), y=y)
        up.show(self.r_fronts[0][0], self.legend[1], bool(fronts))
        up.show(self.r_fronts[1][0], None, bool(fronts))
        return what, half, xi, [wq, *fronts]

    def _fronts(self, sw, xi, info: Info) -> list[np.ndarray]:
        """Kink and antikink (QC superkinks of the same w₊) placed at the bundle's layers,
        shown when the solitary wave has a plateau (amplitude within 5% of |w₋ − w₊|)."""
        s = self.state
        sk = compute.run(s.law(), compute.QCWaveRequest("superkink", s.w_plus, s.V)).value
        if abs(sw.amplitude - sk.amplitude) > 0.05 * sk.amplitude:
            return []
        w = sw.profile(xi)
        right = xi > 0
        mid = 0.5 * (sw.w_B + sw.w_M)
        k = np.flatnonzero(np.diff(np.sign(w[right] - mid)))
        if k.size == 0:
            return []
        x0 = float(xi[right][k[0]])
        sigma = 1.0 if sw.interval == "below" else -1.0  # right front ends at the background
        kr = sk.profile(sigma * (xi - x0))
        kl = sk.profile(sigma * (-xi - x0))
        info.notes.append(f"kink–antikink bundle: fronts at ξ = ±{x0:.4g}")
        self._cols.update(front_right=kr, front_left=kl)
        return [kr, kl]

    def _frame(self, up: Updates, half: float, ys: list, n=None, w=None) -> Updates:
        """Discrete dots (none if n is None) and the axis ranges."""
        if n is None:
            n = w = np.empty(0)
        up.data(self.r_dots[1], x=n, y=w)
        up.show(self.r_dots[0], self.legend[2], len(n) > 0)
        held = self.held.update(up, self.held_items)
        up.range(self.fig.x_range, -half, half)
        up.range(self.fig.y_range, *finite_extent(*ys, w, *held), pad=0.06)
        return up

    def render(self, info: Info):
        s = self.state
        self.require_valid()
        up = Updates()
        what, half, xi, ys = self._qc_part(info, up)
        info.shown = what
        self._discrete = None
        self.held.compute(lambda w: self._held_curve(w, dots=False), info)  # QC: cheap
        if not self.show_discrete.value:
            info.notes.append("discrete wave off: QC only")
            return self._frame(up, half, ys)
        lw = s.law()
        try:
            req = compute.WaveRequest(s.mode, s.w_plus, s.V, s.N, s.tol)
        except compute.ParameterError:
            req = None  # refused below, where the solve was asked for
        if not (req is not None and compute.is_cached(lw, req) and self._held_dots_cached()):
            # the QC curves now, the dots when the solves are done
            self.show_intermediate(self._frame(up, half, ys), info)
            up = Updates()
        try:
            c = compute.run(
                lw,
                compute.WaveRequest(s.mode, s.w_plus, s.V, s.N, s.tol),
                **self.job_hooks("discrete wave"),
            )
        except compute.ParameterError as exc:
            if exc.name != "N":
                raise
            # N too small for the wave's tails (near c₊): keep the QC curve, advise an N
            need = compute.QCWaveRequest(s.mode, s.w_plus, s.V).n_needed(lw, s.tol)
            info.warning = (
                f"No discrete wave at N = {s.N}: the wave's tails need {exc.valid}. "
                + n_advice(need, s.N)
            )
            info.notes.append("discrete wave: none (see the message); QC curve only")
            return self._frame(up, half, ys)
        r = c.value
        info.time(f"discrete N={r.N}", c)
        info.error("residual", r.residual)
        info.error("dropped eq.", r.dropped_residual)
        info.error("tail", r.tail_error)
        info.difference("max |discrete − QC|", r.qc_max_deviation)
        info.error("profile error bound", r.profile_error)
        if s.mode != "superkink":  # a superkink's amplitude is exact (said beside it)
            info.error("amplitude error bound", r.amplitude_error)
        if not r.converged:
            # an unconverged profile is never drawn as if it were a wave
            need = compute.QCWaveRequest(s.mode, s.w_plus, s.V).n_needed(lw, s.tol)
            info.warning = (
                f"The discrete solve did not converge at N = {r.N}, so its points are not drawn. "
                f"{n_advice(need, r.N)} (fpucore: {r.message.split(':')[0]})"
            )
            info.notes.append(f"discrete solve did not converge: {md_literal(r.message)}")
            return self._frame(up, half, ys)
        self._discrete = r
        sel = np.abs(r.n) <= half
        if s.mode == "superkink":  # |w₋ − w₊|: both plateau states are fixed by eq. Rline
            amp = f"amplitude |w₋ − w₊| = {fmt_num(r.amplitude)} (exact by construction)"
        else:
            amp = f"amplitude {fmt_num(r.amplitude)} ± {r.amplitude_error:.1e}"
        info.shown = what + f"; discrete {amp}"
        if s.held:
            self.set_stage(f"discrete waves of {len(s.held)} held curve(s)")
            t0 = time.perf_counter()
            # the QC pass named the held waves this law has not (Info(): not twice)
            self.held.compute(lambda w: self._held_curve(w, dots=True), Info())
            info.time(f"{len(s.held)} held (discrete)", time.perf_counter() - t0)
            missing = [h.label for h in self.held.items if len(h.px) == 0]
            if missing:
                info.notes.append(
                    "held without discrete points (no converged wave at this N): "
                    + "; ".join(missing)
                )
        return self._frame(up, half, ys, r.n[sel].astype(float), r.w[sel])

    def notebook_plot(self) -> str:
        half = getattr(self, "_half_shown", 25.0)
        code = (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            f"xi = np.linspace({-half!r}, {half!r}, 1601)\n"
            "fig, ax = plt.subplots(figsize=(9, 4.5))\n"
            "ax.plot(xi, q.profile(xi), lw=2.5, label='QC')\n"
        )
        if self.show_discrete.value and getattr(self, "_discrete", None) is not None:
            code += "ax.plot(r.n, r.w, 'o', mfc='white', mec='black', label='discrete')\n"
        if self.held.items:
            code += (
                "for k, (hq, hr) in enumerate(held):\n"
                "    ax.plot(xi, hq.profile(xi), '--', label=f'held {k}: V = {hq.V:.6g}')\n"
                "    if hr is not None:\n"
                "        ax.plot(hr.n, hr.w, '.', color=ax.lines[-1].get_color())\n"
            )
        return code + (
            f"ax.set(xlim=({-half!r}, {half!r}), xlabel='ξ', ylabel='w', title='strain profile')\n"
            "ax.legend()\n"
        )

    def python_code(self) -> str:
        s = self.state
        code = python_preamble(s)
        what = "QC superkink" if s.mode == "superkink" else "QC wave"
        code += f"q = {compute.QCWaveRequest(s.mode, s.w_plus, s.V).call().code()}  # {what}\n"
        code += "print(q.V, q.amplitude)\n"
        if self.show_discrete.value:
            req = compute.WaveRequest(s.mode, s.w_plus, s.V, s.N, s.tol)
            code += (
                f"r = {req.call(s.law()).code()}\n"
                "print(r.converged, r.residual, r.amplitude)\n"
                "w_qc = q.profile(r.n)  # the QC curve at the sites\n"
            )
        return code + self.held.code()

    def download_data(self):
        r = getattr(self, "_discrete", None)
        if r is not None:
            s = self.state
            qcw = compute.run(s.law(), compute.QCWaveRequest(s.mode, s.w_plus, s.V)).value
            hdr = provenance(
                self.state,
                f"discrete {r.kind} wave w_n(0), wdot_n(0) (fixed ends w_left={r.w_left!r}, "
                f"w_right={r.w_right!r}) and the QC profile w_qc at the same sites",
                residual=float(r.residual),
                converged=bool(r.converged),
            )
            cols = {"n": r.n, "w": r.w, "wdot": r.wdot, "w_qc": qcw.profile(r.n.astype(float))}
            cols |= self.held.columns()
            return "profile_discrete.csv", as_csv(cols, hdr + "\n" + self.python_code())
        if getattr(self, "_cols", None):
            hdr = provenance(self.state, "QC profile w(xi)")
            cols = self._cols | self.held.columns()
            return "profile_qc.csv", as_csv(cols, hdr + "\n" + self.python_code())
        raise SceneMessage("nothing shown yet")
