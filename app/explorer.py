"""The dashboard page: sidebar widgets ↔ state, lazy tabs, the template.

* Sliders are throttled (they act on release) and keyboard-accessible; each sits next to an
  exact numeric input.  Their ranges follow the theory and are updated from the state: w₊ over
  (α, β) without w*, V over (c₊, c₋) (solitary mode) or over the superkink bounds of eq.
  V_bounds_cubic (superkink mode, where V and w₊ are tied); w* and V_SK are marked under their
  sliders by panes of their own (app/slider_marks.py: the slider models are never touched).
* Only the visible scene renders; a parameter change marks the others stale and they render
  when their tab is opened.  A served page is built with the visible scene only (the build runs
  on the server's event loop, which ten sessions' builds held for up to 20 s); a hidden scene
  is built when its tab is opened, and is in the browser before it first renders (its tab's
  models are queued before its render's updates; Panel's own lazy tabs, Tabs(dynamic=True),
  created them concurrently with the render's updates, which were lost).
* Slider and exact box always show the state's value: a value outside a slider's theoretical
  range (typed, or from a URL) widens the slider to include it, and the sidebar says why the
  scenes show a message.

Beside it: the law editor (:mod:`app.law_editor`), the widgets kept in step with the server
(:mod:`app.widgets`) and the URL (:mod:`app.url_sync`, which builds a served session's page).
"""

from __future__ import annotations

import math

import panel as pn
from panel.io.state import set_curdoc

from fpucore.errors import ParameterError

from .law_editor import LawEditor
from .scene_registry import TABS
from .slider_marks import SliderMark
from .state import N_RANGE, STATE_PARAMS, TOL_OPTIONS, ExplorerState
from .views import SCENES
from .views.formatting import ranges_markdown
from .views.untrusted import LITERAL_MD, LiteralAlert, LiteralMarkdown, md_literal
from .widgets import (
    FloatInput,
    FloatSlider,
    IntInput,
    IntSlider,
    Syncing,
    nearest_tol,
    put,
    user_action,
    widened,
)

CSS = """
.scene-status p { margin: 0.2em 0; font-size: 0.92em; }
"""


class Explorer(pn.viewable.Viewer):
    """One browser session's dashboard (state + widgets + scenes); ``__panel__`` is the page
    (a BootstrapTemplate: sidebar and tabs)."""

    def __init__(
        self,
        state: ExplorerState | None = None,
        url_errors: list[str] | None = None,
        lazy: bool = False,
        **params,
    ):
        """``lazy``: build only the visible scene now (a served page: the build runs on the
        server's event loop, and the seven scenes' figures were ~85 % of it); the others are
        built when their tab is opened (:meth:`scene`)."""
        super().__init__(**params)
        self.state = state or ExplorerState()
        self._doc = pn.state.curdoc
        # the state's lock: a scene is built (and its tab set) by a state change's watcher, which
        # holds that lock; a second lock taken in the other order by a scene built on another
        # thread (a tab click) could deadlock the two handler threads
        self._scene_lock = self.state.lock
        self.by_key = {
            cls.key: cls(self.state) for cls in SCENES if not lazy or cls.key == self.state.tab
        }
        self._syncing = Syncing(self.state.lock)
        self._page = None  # the template, built by __panel__
        self._build_widgets()
        self.url_errors = list(url_errors or [])
        self.url_alert = LiteralAlert(
            "\n\n".join(md_literal(e) for e in self.url_errors),
            alert_type="warning",
            visible=bool(url_errors),
            css_classes=["url-message"],
            **LITERAL_MD,
            sizing_mode="stretch_width",
        )
        self.tabs = pn.Tabs(
            *[(cls.title, self.by_key.get(cls.key) or placeholder(cls)) for cls in SCENES],
            dynamic=False,  # all figures in the browser at once (see the module docstring)
            sizing_mode="stretch_width",
            css_classes=["scene-tabs"],
        )
        self.tabs.active = TABS.index(self.state.tab)
        self.tabs.param.watch(self._on_tab, "active")
        self.state.param.watch(self._on_state, list(STATE_PARAMS) + ["note"])
        self.state.param.watch(self._on_figure_shown, "figure_shown")
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
        self.law_editor = LawEditor(st)
        self.law_editor.param.watch(self._on_checking, "checking", onlychanged=False)
        self.law_editor.param.watch(self._on_refused, "refused", onlychanged=False)
        self.w_plus = FloatSlider(
            label="w₊",
            start=0.0,
            end=1.0,
            step=0.001,
            value=0.5,
            css_classes=["w-wplus"],
            format="0.0000",
            **mk,
        )
        self.V = FloatSlider(
            label="V",
            start=0.0,
            end=1.0,
            step=0.0001,
            value=0.5,
            css_classes=["w-V"],
            format="0.00000",
            **mk,
        )
        # V_SK under the V slider, w* under the w₊ slider: panes of their own (slider_marks)
        self.w_plus_mark = SliderMark("w*", "mark-wplus")
        self.V_mark = SliderMark("V_SK", "mark-V")
        # one per row, full sidebar width: room for a float's 17 significant digits
        self.w_plus_exact = FloatInput(
            label="w₊ (exact)", value=st.w_plus, css_classes=["in-wplus"],
            sizing_mode="stretch_width",
        )  # fmt: skip
        self.V_exact = FloatInput(
            label="V (exact)", value=st.V, css_classes=["in-V"], sizing_mode="stretch_width"
        )
        self.ranges = LiteralMarkdown(
            "", css_classes=["ranges"], sizing_mode="stretch_width", **LITERAL_MD
        )
        self.N = IntSlider(
            label="N (sites, even)",
            start=N_RANGE[0],
            end=N_RANGE[1],
            step=2,
            value=st.N,
            css_classes=["w-N"],
            **mk,
        )
        # N typed exactly (the slider's step at 4000 sites is coarse); the state evens it
        self.N_exact = IntInput(
            label="N (type)", value=int(st.N), step=2, css_classes=["in-N"], width=110
        )
        self.tol = pn.widgets.DiscreteSlider(
            label="tolerance",
            options=list(TOL_OPTIONS),
            value=nearest_tol(st.tol),
            css_classes=["w-tol"],
            sizing_mode="stretch_width",
        )
        self.mode.param.watch(lambda e: self._set(mode=e.new), "value")
        for name in ("w_plus", "V", "N"):
            getattr(self, name).param.watch(
                lambda e, n=name: self._set(**{n: e.new}), "value_throttled"
            )
        self.tol.param.watch(lambda e: self._set(tol=float(e.new)), "value_throttled")
        self.w_plus_exact.param.watch(lambda e: self._typed("w_plus", e.new), "value")
        self.V_exact.param.watch(lambda e: self._typed("V", e.new), "value")
        self.N_exact.param.watch(self._on_typed_N, "value")

    @user_action
    def _on_typed_N(self, event) -> None:
        if event.new is None:
            return
        self.state.set_typed_N(event.new)
        if int(self.state.N) != event.new:  # evened or clamped: show what is used
            self._sync_widgets()

    def _on_checking(self, event) -> None:
        """The law editor has a typed law built in the law worker: the sidebar says so."""
        self.ranges.object = f"_checking the law {md_literal(event.new[:60])} …_"

    def _on_refused(self, event) -> None:
        """A law refused by the law editor never entered the state: the sidebar shows the
        state's law again (not "checking …"), and "Copy as Python" is off while it is shown."""
        for s in self.scenes:
            s.copy_blocked = s.copy_btn.disabled = bool(event.new)
        self._sync_widgets()

    def url_law_checked(self, text: str, outcome) -> None:
        """The URL's law, still being built when the page was (app.state.URL_LAW_WAIT_S), is
        built or refused: show it, or name it in the URL message and fall back to the cubic."""
        if self.state.expression != text:
            return  # the user changed the law meanwhile
        if isinstance(outcome, ParameterError):
            err = ParameterError("law", outcome.value, outcome.valid, outcome.reason)
            self.url_errors.append(f"URL value ignored: {err}")
            self.url_alert.param.update(
                object="\n\n".join(md_literal(e) for e in self.url_errors), visible=True
            )
            self.law_editor.apply("")
            return
        self._sync_widgets()
        for s in self.scenes:
            s.stale = True
        self.active_scene().request()

    @user_action
    def _typed(self, name: str, value) -> None:
        """A value typed in an exact box: a non-finite one (``1e309`` arrives as inf) is
        refused with a message and the box shows the state's value again."""
        if value is None:
            return
        if not math.isfinite(value):
            box = self.w_plus_exact if name == "w_plus" else self.V_exact
            with self._syncing(), self.law_editor.muted():
                box.value = getattr(self.state, name)
            err = ParameterError(name, value, "a finite number")
            self.state.note = f"typed value ignored: {err}"
            return
        self._set(**{name: value})

    @user_action
    def _set(self, **kw):
        if any(v is None for v in kw.values()):
            return
        self.state.param.update(**kw)

    def _sync_widgets(self):
        """State → widgets: ranges from the theory; the value shown is always the state's (a
        value outside the theoretical range widens the slider, and the sidebar says so)."""
        st = self.state
        with self._syncing():
            with self.law_editor.muted():
                self.mode.value = st.mode
                self.law_editor.sync()
                put(self.N, int(st.N), **widened(st.N, *N_RANGE))
                self.N_exact.value = int(st.N)
                put(self.tol, nearest_tol(st.tol))
                summ = st.summary()
                if "alpha" in summ:
                    lo, hi = summ["w_lo"], summ["w_hi"]
                    span = hi - lo
                    lo, hi = lo + 1e-6 * span, hi - 1e-6 * span
                    put(self.w_plus, st.w_plus, step=span / 2000, **widened(st.w_plus, lo, hi))
                self.w_plus_mark.show(summ.get("w_star"), self.w_plus.start, self.w_plus.end)
                try:
                    lo, hi = st.V_range()
                    put(self.V, st.V, step=(hi - lo) / 4000, **widened(st.V, lo, hi))
                except Exception:  # noqa: BLE001 - w_plus invalid: keep the V slider where it was
                    pass
                self.V_mark.show(summ.get("V_SK"), self.V.start, self.V.end)
                self.w_plus_exact.value = st.w_plus
                self.V_exact.value = st.V
                self.ranges.object = ranges_markdown(self.state, summ)

    # ------------------------------------------------------------------ events
    def _on_state(self, *events):
        names = {e.name for e in events}
        if names == {"note"}:
            self.ranges.object = ranges_markdown(self.state, self.state.summary())
            return
        names.discard("note")
        if self.state.adjusting and not names & {"tab"}:
            # the coupling's update inside another change's watchers (ExplorerState._tie runs
            # first): that change's call here follows and syncs and renders once for both —
            # a law change rendered the force law twice
            for s in self.scenes:
                if names & set(s.depends):
                    s.stale = True
            return
        if names - {"tab"}:
            self._sync_widgets()
            for s in self.scenes:
                if names & set(s.depends):
                    s.stale = True
            # only a change the scene depends on renders it (the URL's own sim_shown, set by the
            # Simulation scene's render, rendered it again and re-sent its image), and none of
            # a paper figure's steps (a render of half its state was shown, then replaced)
            scene = self.active_scene()
            if scene.stale and not self.state.showing_figure:
                scene.request()
        if "tab" in names:
            idx = TABS.index(self.state.tab)
            if self.tabs.active != idx:
                self.tabs.active = idx
            scene = self.active_scene()
            if scene.stale and not self.state.showing_figure:
                scene.request()

    def _on_figure_shown(self, _event) -> None:
        """A paper figure's state is set: its scene renders once, unless a request of its own
        (the Simulation scene's run) is already on its way."""
        self.active_scene().request_if_stale()

    def _on_tab(self, event):
        key = TABS[event.new]
        if self.state.tab != key:
            self.state.tab = key  # → _on_state renders it if stale

    @property
    def scenes(self) -> list:
        """The scenes built so far, in tab order."""
        return [self.by_key[cls.key] for cls in SCENES if cls.key in self.by_key]

    def scene(self, key: str):
        """The scene of tab ``key``, built now (and put into its tab) if it was deferred."""
        with self._scene_lock:
            sc = self.by_key.get(key)
            if sc is not None:
                return sc
            i, cls = next((i, c) for i, c in enumerate(SCENES) if c.key == key)
            with set_curdoc(self._doc):
                sc = cls(self.state)
                sc.copy_blocked = bool(self.law_editor.refused)
                self.by_key[key] = sc
                objects = list(self.tabs.objects)
                objects[i] = sc.panel
                self.tabs.objects = objects  # the tab's models are made on the session's loop
            return sc

    def active_scene(self):
        return self.scene(self.state.tab)

    def first_render(self) -> None:
        """While the page is built: render the visible scene now if it is cheap (QC, cached),
        so it arrives with the page; costlier scenes start once the page has loaded."""
        scene = self.active_scene()
        if scene.cheap:
            scene.refresh(building=True)

    def start(self):
        """Called once the page has loaded: render the visible scene if still needed.  (The
        deferred scenes are built when their tab is opened: built in the background right
        after the load, ten sessions' builds kept Panel's two handler threads and the event
        loop busy — /liveness p95 3.7 s instead of 0.3 s.)"""
        scene = self.active_scene()
        if scene.stale:
            scene.request()

    # ------------------------------------------------------------------ layout
    def sidebar(self) -> list:
        accuracy = pn.Card(
            pn.Row(self.N, self.N_exact, sizing_mode="stretch_width"),
            self.tol,
            LiteralMarkdown(
                "_Smaller N / looser tolerance: faster, less accurate — see the "
                "error and time next to each plot._"
            ),
            title="accuracy",
            collapsed=False,
            sizing_mode="stretch_width",
        )
        return [
            self.url_alert,
            self.mode,
            self.law_editor,
            self.w_plus,
            self.w_plus_mark.pane,
            self.V,
            self.V_mark.pane,
            self.w_plus_exact,
            self.V_exact,
            self.ranges,
            accuracy,
        ]

    def __panel__(self):
        if self._page is None:
            self._page = self.template()
        return self._page

    def template(self):
        pn.config.raw_css.append(CSS) if CSS not in pn.config.raw_css else None
        return pn.template.BootstrapTemplate(
            title="fpu-explorer — superkinks and solitary waves in the FPU chain",
            sidebar=self.sidebar(),
            main=[self.tabs],
            sidebar_width=340,
        )


def placeholder(cls) -> pn.Column:
    """A deferred scene's tab until :meth:`Explorer.scene` builds it."""
    return pn.Column(
        LiteralMarkdown("_preparing this view …_"),
        name=cls.title,
        css_classes=[f"scene-{cls.key}-pending"],
        sizing_mode="stretch_width",
    )
