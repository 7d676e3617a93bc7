"""Composition of the dashboard: sidebar widgets ↔ state, lazy tabs, URL sync.

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
* A typed law (box or URL) is built in a worker process within a time and memory budget
  (:func:`app.compute.request_law`) and applied from its answer; never in a handler or the build.
* The law: the cubic with its a, b sliders, or an expression (fpucore.law_from_expression, e.g.
  ``w + 10*w**2 - w**3 - 0.01*w**4``) with one slider per coefficient; a coefficient slider
  rewrites the expression (exact reprs), so the text, the URL and "copy as Python" follow it.
* (a, b, law, w_plus, V, mode, tab, N, tol) live in the URL query string.  A URL is validated like
  any input (:func:`app.state.parse_url`): an invalid value is named with its valid range in
  the sidebar, every other value is kept, and the address bar is rewritten to what is shown.
* Slider and exact box always show the state's value: a value outside a slider's theoretical
  range (typed, or from a URL) widens the slider to include it, and the sidebar says why the
  scenes show a message.
"""

from __future__ import annotations

import logging
import math
import threading
import urllib.parse

import panel as pn
import param
from bokeh.core.property.descriptors import UnsetValueError
from panel.io.state import set_curdoc

from fpucore.errors import ParameterError
from fpucore.law import PolynomialLaw, expression_of

from . import compute
from .slider_marks import SliderMark
from .state import (
    A_RANGE,
    B_RANGE,
    N_RANGE,
    STATE_PARAMS,
    TABS,
    TOL_OPTIONS,
    URL_PARAMS,
    ExplorerState,
    state_from_url,
    url_query,
)
from .views import SCENES
from .views.untrusted import LITERAL_MD, md_literal

log = logging.getLogger("fpu-explorer")

#: at most this many coefficient sliders (a law of higher degree is edited as text only)
MAX_COEFF_SLIDERS = 8

CSS = """
.scene-status p { margin: 0.2em 0; font-size: 0.92em; }
"""


class _ThrottledInStep:
    """A widget whose browser-side ``value_throttled`` follows every value the server sets.

    With ``pn.extension(throttled=True)`` a slider or number box reaches the server only
    through ``value_throttled`` (its bare ``value`` events are dropped), and BokehJS sends a
    property only when it changes.  Panel never sends ``value_throttled`` to the browser, so
    the browser kept the user's last value: after the state moved the widget elsewhere (a
    typed V moves the V slider, a slider moves the V box), a user action that returned it to
    that last value changed nothing in the browser's ``value_throttled``, nothing was sent,
    and the widget showed a value the state, URL and plot did not have (the state walk: V = 5.2
    typed a second time kept V = 5.200694; a slider released where it was last released).
    Here each value sent to the browser carries the same ``value_throttled``."""

    def _update_model(self, events, msg, root, model, doc, comm) -> None:
        value = msg.get("value", _UNSET)
        super()._update_model(events, msg, root, model, doc, comm)
        if value is _UNSET or "value_throttled" not in model.properties():
            return
        try:
            old = model.value_throttled
        except UnsetValueError:  # a number box's, until the browser first sets it
            old = None
        if old == value:
            return
        ref = root.ref["id"]
        # marked as the server's own change, as Panel marks the properties it sets, so its
        # change handler does not take it for a browser event
        self._changing[ref] = pending = ["value_throttled"]
        try:
            model.lookup("value_throttled")._set(model, old, value)  # Readonly: no setattr
        finally:
            if self._changing.get(ref) is pending:
                del self._changing[ref]


_UNSET = object()


class FloatSlider(_ThrottledInStep, pn.widgets.FloatSlider):
    pass


class IntSlider(_ThrottledInStep, pn.widgets.IntSlider):
    pass


class FloatInput(_ThrottledInStep, pn.widgets.FloatInput):
    pass


class IntInput(_ThrottledInStep, pn.widgets.IntInput):
    pass


class Explorer:
    """One browser session's dashboard (state + widgets + scenes)."""

    def __init__(
        self,
        state: ExplorerState | None = None,
        url_errors: list[str] | None = None,
        lazy: bool = False,
    ):
        """``lazy``: build only the visible scene now (a served page: the build runs on the
        server's event loop, and the seven scenes' figures were ~85 % of it); the others are
        built when their tab is opened (:meth:`scene`)."""
        self.state = state or ExplorerState()
        self._doc = pn.state.curdoc
        self._scene_lock = threading.RLock()
        self.by_key = {
            cls.key: cls(self.state) for cls in SCENES if not lazy or cls.key == self.state.tab
        }
        self._syncing = False
        self._build_widgets()
        self.url_errors = list(url_errors or [])
        self.url_alert = pn.pane.Alert(
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
        self.a = FloatSlider(
            label="a",
            start=A_RANGE[0],
            end=A_RANGE[1],
            step=0.01,
            value=st.a,
            css_classes=["w-a"],
            format="0.00",
            **mk,
        )
        self.b = FloatSlider(
            label="b",
            start=B_RANGE[0],
            end=B_RANGE[1],
            step=0.05,
            value=st.b,
            css_classes=["w-b"],
            format="0.00",
            **mk,
        )
        self._build_law_widgets()
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
        self.ranges = pn.pane.Markdown(
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
        for name in ("a", "b", "w_plus", "V", "N"):
            getattr(self, name).param.watch(
                lambda e, n=name: self._set(**{n: e.new}), "value_throttled"
            )
        self.tol.param.watch(lambda e: self._set(tol=float(e.new)), "value_throttled")
        self.w_plus_exact.param.watch(lambda e: self._typed("w_plus", e.new), "value")
        self.V_exact.param.watch(lambda e: self._typed("V", e.new), "value")
        self.N_exact.param.watch(self._on_typed_N, "value")

    def _on_typed_N(self, event) -> None:
        if self._syncing or event.new is None:
            return
        self.state.set_typed_N(event.new)
        if int(self.state.N) != event.new:  # evened or clamped: show what is used
            self._sync_widgets()

    def _build_law_widgets(self) -> None:
        """Law selector: cubic (a, b sliders) or an expression with its coefficient sliders."""
        st = self.state
        self.law_kind = pn.widgets.RadioButtonGroup(
            options={"cubic (a, b)": "cubic", "expression": "expression"},
            value="expression" if st.expression else "cubic",
            css_classes=["w-law-kind"],
        )
        self.law_text = pn.widgets.TextInput(
            label="f(w) = (polynomial in w, Enter to apply)",
            value=st.expression,
            placeholder="w + 10*w**2 - w**3 - 0.01*w**4",
            css_classes=["in-law"],
            sizing_mode="stretch_width",
        )
        self.coeff_box = pn.Column(sizing_mode="stretch_width", css_classes=["law-coeffs"])
        self.coeff_sliders: list = []
        self._coeff_anchor: tuple[float, ...] | None = None  # the coefficients the ranges follow
        self._last_expression = st.expression
        self._from_slider = False
        self.law_kind.param.watch(self._on_law_kind, "value")
        self._law_wanted = st.expression
        self.law_text.param.watch(lambda e: self._apply_expression(e.new), "value")

    def _on_law_kind(self, event) -> None:
        if self._syncing:
            return
        st = self.state
        if event.new == "cubic":
            self._last_expression = st.expression or self._last_expression
            self._set(expression="")
        elif not st.expression:
            # start from the last expression, else from the current cubic as a polynomial
            text = self._last_expression
            if not text:
                try:
                    text = compute.law(st.a, st.b).as_polynomial().expression
                except ParameterError:
                    text = "w + 10*w**2 - w**3 - 0.01*w**4"
                try:  # written by the app: bounded, built here at once
                    compute.trusted_expression_law(text)
                except ParameterError:
                    pass
            self._apply_expression(text)

    def _on_coeff(self, k: int, value) -> None:
        """Coefficient slider k (c_{k+1}) moved: the expression is rewritten from the sliders."""
        if self._syncing or value is None:
            return
        coeffs = [float(s.value) for s in self.coeff_sliders]
        coeffs[k] = float(f"{float(value):.6g}")  # no 10.059999999999999 from the slider step
        text = expression_of(coeffs)
        try:  # written by the app from ≤ MAX_COEFF_SLIDERS floats: bounded, built here at once
            compute.trusted_expression_law(text)
        except ParameterError:
            pass  # the state shows why
        self._law_wanted = text
        self._from_slider = True
        try:
            self._set(expression=text)
        finally:
            self._from_slider = False

    def _sync_law(self) -> None:
        """State → law widgets (called while syncing)."""
        st = self.state
        poly = bool(st.expression)
        self.law_kind.value = "expression" if poly else "cubic"
        self.a.visible = self.b.visible = not poly
        self.law_text.visible = poly
        self.law_text.value = st.expression
        lw = None
        if poly:
            try:
                lw = st.law()
            except ParameterError:
                lw = None
        if isinstance(lw, PolynomialLaw):
            coeffs = lw.coeffs
            if self._from_slider and self._coeff_anchor:  # c_n → 0 drops a degree: keep c_n
                coeffs += (0.0,) * (len(self._coeff_anchor) - len(coeffs))
            if self._coeff_anchor is None or len(coeffs) != len(self._coeff_anchor):
                self._anchor_sliders(coeffs)  # another degree: new sliders
            elif not self._from_slider and coeffs != tuple(s.value for s in self.coeff_sliders):
                self._coeff_anchor = tuple(coeffs)  # a typed law: ranges around it
            for sl, c, c0 in zip(self.coeff_sliders, coeffs, self._coeff_anchor):
                lo, hi = coeff_range(c0)
                self._put(sl, c, step=(hi - lo) / 1000, **widened(c, lo, hi))
            self.coeff_box.visible = True
        else:
            # an invalid law: the sliders stay only if they made it (so they can move back)
            made = bool(self.coeff_sliders) and st.expression == expression_of(
                [float(s.value) for s in self.coeff_sliders]
            )
            self.coeff_box.visible = poly and made

    def _apply_expression(self, text: str | None) -> None:
        """A law typed in the box (or chosen): applied once it is built.  A typed text is built
        in the law worker within its budgets (app.compute.request_law), never in this handler:
        a law not built yet is applied from the worker's answer (if it is still the one
        wanted), and the sidebar says it is being checked meanwhile."""
        if self._syncing or text is None:
            return
        text = text.strip()
        self._law_wanted = text
        if not text or compute.lookup_law(text) is not None:
            self._set(expression=text)
            return
        self.ranges.object = f"_checking the law {md_literal(text[:60])} …_"
        doc = pn.state.curdoc

        def built(_fut) -> None:  # in the law worker's watcher thread
            if self._law_wanted != text:
                return  # another law was typed meanwhile
            try:
                with set_curdoc(doc):
                    self._set(expression=text)
            except Exception:  # noqa: BLE001 - a session closed meanwhile
                log.exception("applying the law %r", text[:60])

        compute.request_law(text).add_done_callback(built)

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
            self._law_wanted = ""
            self._set(expression="")
            return
        self._sync_widgets()
        for s in self.scenes:
            s.stale = True
        self.active_scene().request()

    def _anchor_sliders(self, coeffs: tuple[float, ...]) -> None:
        """(Re)build the coefficient sliders with ranges around ``coeffs``."""
        self._coeff_anchor = tuple(coeffs)
        if len(coeffs) > MAX_COEFF_SLIDERS:
            self.coeff_sliders = []
            self.coeff_box.objects = [
                pn.pane.Markdown(f"_degree {len(coeffs)} > {MAX_COEFF_SLIDERS}: edit the text_")
            ]
            return
        sliders = []
        for k, c in enumerate(coeffs):
            lo, hi = coeff_range(c)
            sl = FloatSlider(
                label=f"c{k + 1} (w^{k + 1})" if k else "c1 (w) = f′(0)",
                start=lo,
                end=hi,
                step=(hi - lo) / 1000,
                value=c,
                css_classes=[f"w-c{k + 1}"],
                format="0.0[000]",
                sizing_mode="stretch_width",
                show_value=True,
            )
            sl.param.watch(lambda e, k=k: self._on_coeff(k, e.new), "value_throttled")
            sliders.append(sl)
        self.coeff_sliders = sliders
        self.coeff_box.objects = sliders

    def _typed(self, name: str, value) -> None:
        """A value typed in an exact box: a non-finite one (``1e309`` arrives as inf) is
        refused with a message and the box shows the state's value again."""
        if self._syncing or value is None:
            return
        if not math.isfinite(value):
            box = self.w_plus_exact if name == "w_plus" else self.V_exact
            self._syncing = True
            try:
                box.value = getattr(self.state, name)
            finally:
                self._syncing = False
            err = ParameterError(name, value, "a finite number")
            self.state.note = f"typed value ignored: {err}"
            return
        self._set(**{name: value})

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
        """State → widgets: ranges from the theory; the value shown is always the state's (a
        value outside the theoretical range widens the slider, and the sidebar says so)."""
        st = self.state
        self._syncing = True
        try:
            self.mode.value = st.mode
            self._put(self.a, st.a, **widened(st.a, *A_RANGE))
            self._put(self.b, st.b, **widened(st.b, *B_RANGE))
            self._sync_law()
            self._put(self.N, int(st.N), **widened(st.N, *N_RANGE))
            self.N_exact.value = int(st.N)
            self._put(self.tol, nearest_tol(st.tol))
            summ = st.summary()
            if "alpha" in summ:
                lo, hi = summ["w_lo"], summ["w_hi"]
                span = hi - lo
                lo, hi = lo + 1e-6 * span, hi - 1e-6 * span
                self._put(self.w_plus, st.w_plus, step=span / 2000, **widened(st.w_plus, lo, hi))
            self.w_plus_mark.show(summ.get("w_star"), self.w_plus.start, self.w_plus.end)
            try:
                lo, hi = st.V_range()
                self._put(self.V, st.V, step=(hi - lo) / 4000, **widened(st.V, lo, hi))
            except Exception:  # noqa: BLE001 - w_plus invalid: keep the V slider where it was
                pass
            self.V_mark.show(summ.get("V_SK"), self.V.start, self.V.end)
            self.w_plus_exact.value = st.w_plus
            self.V_exact.value = st.V
            self.ranges.object = self._ranges_text(summ)
        finally:
            self._syncing = False

    def _ranges_text(self, s: dict) -> str:
        st = self.state
        if "alpha" not in s:
            return f"**invalid law:** {md_literal(st.problem() or '')}"
        if (s["w_lo"], s["w_hi"]) == (s["alpha"], s["beta"]):
            where = f"w₊ ∈ (α, β) = ({s['alpha']:.5g}, {s['beta']:.5g})"
        else:  # another law: w₋ must stay inside (α, β) too
            where = (
                f"w₊ ∈ ({s['w_lo']:.5g}, {s['w_hi']:.5g}) (where w₋ stays inside (α, β) = "
                f"({s['alpha']:.5g}, {s['beta']:.5g}))"
            )
        lines = [f"{where}, **w\\* = {s['w_star']:.6g}** excluded"]
        if "V_SK" in s:
            lines.append(
                "solitary-wave velocities (tensile or compressive): "
                f"(c₊, V_SK) = ({s['c_plus']:.6g}, {s['V_SK']:.6g}) and "
                f"(V_SK, c₋) = ({s['V_SK']:.6g}, {s['c_minus']:.6g})"
            )
            lines.append(f"**V_SK = {s['V_SK']:.10g}** (superkink)")
            lines.append(f"superkink V bounds ({s['V_lo']:.6g}, {s['V_hi']:.6g})")
        kind = st.kind()
        lines.append(
            f"current: **{kind}**" if kind != "invalid" else f"⚠ {md_literal(st.problem())}"
        )
        if st.note:
            lines.append(f"_{md_literal(st.note)}_")
        return "\n\n".join(lines)

    # ------------------------------------------------------------------ events
    def _on_state(self, *events):
        names = {e.name for e in events}
        if names == {"note"}:
            self.ranges.object = self._ranges_text(self.state.summary())
            return
        names.discard("note")
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
            pn.pane.Markdown(
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
            pn.pane.Markdown("**force law**", margin=(0, 10)),
            self.law_kind,
            self.a,
            self.b,
            self.law_text,
            self.coeff_box,
            self.w_plus,
            self.w_plus_mark.pane,
            self.V,
            self.V_mark.pane,
            self.w_plus_exact,
            self.V_exact,
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


def placeholder(cls) -> pn.Column:
    """A deferred scene's tab until :meth:`Explorer.scene` builds it."""
    return pn.Column(
        pn.pane.Markdown("_preparing this view …_"),
        name=cls.title,
        css_classes=[f"scene-{cls.key}-pending"],
        sizing_mode="stretch_width",
    )


def nearest_tol(tol: float) -> float:
    """The tolerance option closest (in log) to tol."""
    t = float(tol) if math.isfinite(tol) and tol > 0 else 1e-10
    return min(TOL_OPTIONS, key=lambda o: abs(math.log10(o / t)))


def coeff_range(c0: float) -> tuple[float, float]:
    """Slider range of a law coefficient around the typed value c0: c0 ± 2|c0| (so its sign can
    change), [−1, 1] for a zero coefficient."""
    r = 2.0 * abs(c0) if c0 != 0.0 and math.isfinite(c0) else 1.0
    return c0 - r, c0 + r


def widened(x: float, lo: float, hi: float) -> dict:
    """Slider start/end: the theoretical range, widened to include x if x lies outside (so the
    slider shows the state's value, never a clipped one)."""
    if not math.isfinite(x):
        return {"start": lo, "end": hi}
    return {"start": min(lo, x), "end": max(hi, x)}


def session_query() -> dict[str, str]:
    """The page's URL query as {name: first value} (server sessions; empty otherwise)."""
    args = pn.state.session_args or {}
    out = {}
    for k, v in args.items():
        if k in URL_PARAMS and v:
            raw = v[0]
            out[k] = raw.decode("utf-8", "replace") if isinstance(raw, bytes) else str(raw)
    return out


def from_url(lazy: bool = True) -> Explorer:
    """The session's Explorer built from its validated URL (one state, no default-then-URL
    double render), with the URL rewritten to the state and kept in sync with it; ``lazy``:
    a hidden scene is built when its tab is opened (see Explorer)."""
    state, errors = state_from_url(session_query())
    text = state.expression
    # a law still being built (see parse_url_value): the page is built meanwhile, and once the
    # law's outcome is known (maybe during this build) the explorer shows it or names it
    pending = bool(text) and compute.lookup_law(text) is None
    explorer = Explorer(state, url_errors=errors, lazy=lazy)
    if pending:
        doc = pn.state.curdoc

        def built(fut) -> None:  # in the law worker's watcher thread (or here, if done)
            try:
                with set_curdoc(doc):
                    explorer.url_law_checked(text, fut.result())
            except Exception:  # noqa: BLE001 - a session closed meanwhile
                log.exception("applying the URL's law %r", text[:60])

        compute.request_law(text).add_done_callback(built)
    loc = pn.state.location
    if loc is not None:
        st = explorer.state

        def wanted() -> str:
            # the whole query is rewritten (not Location.update_query, which parses the old
            # query — and raises on a 5000-digit value)
            return "?" + urllib.parse.urlencode(url_query(st))

        def push(*_):
            loc.search = wanted()

        def reassert(event):
            # The browser's Location view reports its own (original) search once it starts;
            # under load that report can arrive after the onload push, and would leave the
            # address bar stale.  Any search that is not the state's is answered with the state's.
            if event.new != wanted():
                push()

        push()
        pn.state.onload(push)  # again once the browser's own location has been synced
        st.param.watch(push, list(STATE_PARAMS))
        loc.param.watch(reassert, ["search"])
    return explorer
