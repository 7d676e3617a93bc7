"""Composition of the dashboard: sidebar widgets ↔ state, lazy tabs, URL sync.

* Sliders are throttled (they act on release) and keyboard-accessible; each sits next to an
  exact numeric input.  Their ranges follow the theory and are updated from the state: w₊ over
  (α, β) with w* marked, V over (c₊, c₋) with V_SK marked (solitary mode) or over the superkink
  bounds of eq. V_bounds_cubic (superkink mode, where V and w₊ are tied).
* Only the visible scene renders; a parameter change marks the others stale and they render
  when their tab is opened (Tabs(dynamic=True) also keeps hidden tabs out of the browser).
* (a, b, w_plus, V, mode, tab, N, tol) live in the URL query string.
"""

from __future__ import annotations

import math

import panel as pn
import param

from .state import TABS, ExplorerState
from .views import SCENES

URL_PARAMS = {
    "a": "a",
    "b": "b",
    "w_plus": "w_plus",
    "V": "V",
    "mode": "mode",
    "tab": "tab",
    "N": "N",
    "tol": "tol",
}
TOL_OPTIONS = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13]

CSS = """
.scene-status p { margin: 0.2em 0; font-size: 0.92em; }
"""


def _clip(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi) if math.isfinite(x) else lo


class Explorer:
    """One browser session's dashboard (state + widgets + scenes)."""

    def __init__(self, state: ExplorerState | None = None):
        self.state = state or ExplorerState()
        self.scenes = [cls(self.state) for cls in SCENES]
        self.by_key = {s.key: s for s in self.scenes}
        self._syncing = False
        self._build_widgets()
        self.tabs = pn.Tabs(
            *[(s.title, s.panel) for s in self.scenes],
            dynamic=True,
            sizing_mode="stretch_width",
            css_classes=["scene-tabs"],
        )
        self.tabs.active = TABS.index(self.state.tab)
        self.tabs.param.watch(self._on_tab, "active")
        self.state.param.watch(self._on_state, list(URL_PARAMS))
        self._sync_widgets()

    # ------------------------------------------------------------------ widgets
    def _build_widgets(self):
        st = self.state
        self.mode = pn.widgets.RadioButtonGroup(
            label="mode",
            options={"solitary wave": "solitary", "superkink": "superkink"},
            value=st.mode,
            color="primary",
            css_classes=["w-mode"],
        )
        mk = dict(sizing_mode="stretch_width", show_value=True)
        self.a = pn.widgets.FloatSlider(
            label="a",
            start=-5.0,
            end=-0.1,
            step=0.01,
            value=st.a,
            css_classes=["w-a"],
            format="0.00",
            **mk,
        )
        self.b = pn.widgets.FloatSlider(
            label="b",
            start=1.0,
            end=20.0,
            step=0.05,
            value=st.b,
            css_classes=["w-b"],
            format="0.00",
            **mk,
        )
        self.w_plus = pn.widgets.FloatSlider(
            label="w₊",
            start=0.0,
            end=1.0,
            step=0.001,
            value=0.5,
            css_classes=["w-wplus"],
            format="0.0000",
            **mk,
        )
        self.V = pn.widgets.FloatSlider(
            label="V",
            start=0.0,
            end=1.0,
            step=0.0001,
            value=0.5,
            css_classes=["w-V"],
            format="0.00000",
            **mk,
        )
        self.w_plus_exact = pn.widgets.FloatInput(
            label="w₊ (exact)", value=st.w_plus, css_classes=["in-wplus"], width=130
        )
        self.V_exact = pn.widgets.FloatInput(
            label="V (exact)", value=st.V, css_classes=["in-V"], width=130
        )
        self.ranges = pn.pane.Markdown("", css_classes=["ranges"], sizing_mode="stretch_width")
        self.N = pn.widgets.IntSlider(
            label="N (sites)", start=50, end=2000, step=10, value=st.N, css_classes=["w-N"], **mk
        )
        self.tol = pn.widgets.DiscreteSlider(
            label="tolerance",
            options=TOL_OPTIONS,
            value=min(TOL_OPTIONS, key=lambda t: abs(math.log10(t) - math.log10(st.tol))),
            css_classes=["w-tol"],
            sizing_mode="stretch_width",
        )
        self.mode.param.watch(lambda e: self._set(mode=e.new), "value")
        for name in ("a", "b", "w_plus", "V", "N"):
            getattr(self, name).param.watch(
                lambda e, n=name: self._set(**{n: e.new}), "value_throttled"
            )
        self.tol.param.watch(lambda e: self._set(tol=float(e.new)), "value_throttled")
        self.w_plus_exact.param.watch(lambda e: self._set(w_plus=e.new), "value")
        self.V_exact.param.watch(lambda e: self._set(V=e.new), "value")

    def _set(self, **kw):
        if self._syncing or any(v is None for v in kw.values()):
            return
        self.state.param.update(**kw)

    def _put(self, widget, value, **bounds):
        """Programmatic widget update that the watchers ignore (and that keeps value_throttled
        in step, so a later drag back to the old value still registers)."""
        widget.param.update(**bounds, value=value)
        if "value_throttled" in widget.param:
            with param.edit_constant(widget):
                widget.value_throttled = value

    def _sync_widgets(self):
        """State → widgets: ranges from the theory, values clipped into them."""
        st = self.state
        self._syncing = True
        try:
            self.mode.value = st.mode
            self._put(self.a, _clip(st.a, self.a.start, self.a.end))
            self._put(self.b, _clip(st.b, self.b.start, self.b.end))
            self._put(self.N, int(_clip(st.N, self.N.start, self.N.end)))
            self._put(self.tol, min(TOL_OPTIONS, key=lambda t: abs(math.log10(t / st.tol))))
            summ = st.summary()
            if "alpha" in summ:
                lo, hi = summ["alpha"], summ["beta"]
                span = hi - lo
                self._put(
                    self.w_plus,
                    _clip(st.w_plus, lo + 1e-9 * span, hi - 1e-9 * span),
                    start=lo + 1e-6 * span,
                    end=hi - 1e-6 * span,
                    step=span / 2000,
                )
            try:
                lo, hi = st.V_range()
                self._put(self.V, _clip(st.V, lo, hi), start=lo, end=hi, step=(hi - lo) / 4000)
            except Exception:  # w_plus invalid: keep the V slider where it was
                pass
            self.w_plus_exact.value = st.w_plus
            self.V_exact.value = st.V
            self.ranges.object = self._ranges_text(summ)
            self.V.disabled = False
        finally:
            self._syncing = False

    def _ranges_text(self, s: dict) -> str:
        st = self.state
        if "alpha" not in s:
            return f"**invalid law:** {st.problem()}"
        lines = [
            f"w₊ ∈ (α, β) = ({s['alpha']:.5g}, {s['beta']:.5g}), "
            f"**w\\* = {s['w_star']:.6g}** excluded"
        ]
        if "V_SK" in s:
            lines.append(
                f"TSW/CSW: (c₊, V_SK) = ({s['c_plus']:.6g}, {s['V_SK']:.6g}) and "
                f"(V_SK, c₋) = ({s['V_SK']:.6g}, {s['c_minus']:.6g})"
            )
            lines.append(f"**V_SK = {s['V_SK']:.10g}** (superkink)")
            lines.append(f"superkink V bounds ({s['V_lo']:.6g}, {s['V_hi']:.6g})")
        kind = st.kind()
        lines.append(f"current: **{kind}**" if kind != "invalid" else f"⚠ {st.problem()}")
        return "\n\n".join(lines)

    # ------------------------------------------------------------------ events
    def _on_state(self, *events):
        names = {e.name for e in events}
        if names - {"tab"}:
            self._sync_widgets()
            for s in self.scenes:
                if names & set(s.depends):
                    s.stale = True
            self.active_scene().request()
        if "tab" in names:
            idx = TABS.index(self.state.tab)
            if self.tabs.active != idx:
                self.tabs.active = idx
            scene = self.active_scene()
            if scene.stale:
                scene.request()

    def _on_tab(self, event):
        key = TABS[event.new]
        if self.state.tab != key:
            self.state.tab = key  # → _on_state renders it if stale

    def active_scene(self):
        return self.by_key[self.state.tab]

    def first_render(self) -> None:
        """While the page is built: render the visible scene now if it is cheap (QC, cached),
        so it arrives with the page; costlier scenes start once the page has loaded."""
        scene = self.active_scene()
        if scene.cheap:
            scene.refresh(building=True)

    def start(self):
        """Called once the page has loaded: render the visible scene if still needed."""
        scene = self.active_scene()
        if scene.stale:
            scene.request()

    # ------------------------------------------------------------------ layout
    def sidebar(self) -> list:
        accuracy = pn.Card(
            self.N,
            self.tol,
            pn.pane.Markdown(
                "_Smaller N / looser tolerance: faster, less accurate — see the "
                "error and time next to each plot._"
            ),
            title="accuracy",
            collapsed=False,
            sizing_mode="stretch_width",
        )
        return [
            self.mode,
            self.a,
            self.b,
            self.w_plus,
            self.V,
            pn.Row(self.w_plus_exact, self.V_exact),
            self.ranges,
            accuracy,
        ]

    def template(self):
        pn.config.raw_css.append(CSS) if CSS not in pn.config.raw_css else None
        return pn.template.BootstrapTemplate(
            title="fpu-explorer — superkinks and solitary waves in the FPU chain",
            sidebar=self.sidebar(),
            main=[self.tabs],
            sidebar_width=340,
        )


def sync_url(explorer: Explorer) -> None:
    """Two-way sync of the state with the URL query string (server sessions only)."""
    if pn.state.location is not None:
        pn.state.location.sync(explorer.state, URL_PARAMS)
