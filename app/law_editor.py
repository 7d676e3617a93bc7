"""The sidebar's law editor: a preset (fpucore.law.presets), the cubic with its a, b sliders, or
an expression — a polynomial with one slider per coefficient, or a smooth law (exp, log, sqrt,
tanh, …) with named constants, ``w + b*w**2 - c*w**3*exp(w/d); b=10, c=1, d=50``, one slider
per constant.

* The trilinear preset (fpucore.law.TrilinearLaw) gets a slider for each of w1, w2, E1, E2, E3
  (:mod:`app.law_trilinear`); a combination outside the class is refused with fpucore's reason.
* A law outside the class is refused with its reason (:attr:`LawEditor.refused`) and never
  enters the state: the previous valid law stays on screen.

* A typed law (box or a choice) is built in a worker process within a time and memory budget
  (:func:`app.compute.laws.request_law`) and applied from its answer; never in a handler or
  the build.
  Meanwhile :attr:`LawEditor.checking` names it (the page says it is being checked).
* An expression (fpucore.law_from_expression, e.g. ``w + 10*w**2 - w**3 - 0.01*w**4``) gets one
  slider per coefficient; a coefficient slider rewrites the expression (exact reprs), so the text,
  the URL and "copy as Python" follow it.

Kept apart from the page (:mod:`app.explorer`): the editor talks to the
:class:`~app.state.ExplorerState` only through its parameters (reads a, b, expression and the law
they make; sets a, b, expression with ``param.update``), and the page only calls
:meth:`LawEditor.sync` (state → widgets, with the rest of the sidebar) and :meth:`LawEditor.apply`,
and watches :attr:`LawEditor.checking`.
"""

from __future__ import annotations

import contextlib
import logging
import math

import panel as pn
import param
from panel.io.state import set_curdoc

from fpucore.errors import ParameterError
from fpucore.law import PolynomialLaw, expression_of
from fpucore.law.presets import PRESETS

from . import compute
from .law_presets import HELP, PRESET_OPTIONS, preset_of, preset_text
from .law_trilinear import TrilinearSliders
from .slider_pool import SliderPool
from .state import A_RANGE, B_RANGE, ExplorerState
from .views.untrusted import LiteralAlert, LiteralMarkdown, md_literal
from .widgets import FloatSlider, Syncing, document_gone, put, user_action, widened

log = logging.getLogger("fpu-explorer")

#: at most this many coefficient sliders (a law of higher degree is edited as text only)
MAX_COEFF_SLIDERS = 8


class LawEditor(pn.viewable.Viewer):
    """Law selector: cubic (a, b sliders) or an expression with its coefficient sliders."""

    checking = param.String(
        "", doc="a typed law being built in the law worker (set again for every new one)"
    )
    refused = param.String(
        "", doc="why the last law offered was refused (it never entered the state); empty: none"
    )

    def __init__(self, state: ExplorerState, **params):
        super().__init__(**params)
        self.state = st = state
        self._syncing = Syncing(st.lock)
        self.law_kind = pn.widgets.RadioButtonGroup(
            options={"cubic (a, b)": "cubic", "expression": "expression"},
            value="expression" if st.expression else "cubic",
            css_classes=["w-law-kind"],
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
        self.law_text = pn.widgets.TextInput(
            label="f(w) = (expression in w; constants as name=value after ';', Enter)",
            value=st.expression,
            placeholder="w + 10*w**2 - w**3 - 0.01*w**4",
            css_classes=["in-law"],
            sizing_mode="stretch_width",
        )
        self._coeff_pool = SliderPool(self._on_pool_coeff, "law-coeff-sliders")
        self._too_many = LiteralMarkdown("", visible=False)
        self.coeff_box = pn.Column(
            self._coeff_pool.box, self._too_many, sizing_mode="stretch_width",
            css_classes=["law-coeffs"],
        )  # fmt: skip
        self.preset = pn.widgets.Select(
            label="preset", options=PRESET_OPTIONS, value="", css_classes=["w-law-preset"],
            sizing_mode="stretch_width",
        )  # fmt: skip
        self.preset.param.watch(self._on_preset, "value")
        self._const_pool = SliderPool(self._on_pool_const, "law-constants")
        self.const_box = self._const_pool.box
        self.trilinear = TrilinearSliders(self._on_trilinear)
        self.const_sliders: dict = {}
        self._const_anchor: tuple | None = None  # (expression, names, values) the ranges follow
        self.refusal = LiteralAlert(
            "", alert_type="danger", visible=False, css_classes=["law-refusal"],
            sizing_mode="stretch_width",
        )  # fmt: skip
        self.help = pn.Card(
            LiteralMarkdown(HELP, css_classes=["law-help"]), title="which laws are accepted",
            collapsed=True, sizing_mode="stretch_width",
        )  # fmt: skip
        self.coeff_sliders: list = []
        self._coeff_anchor: tuple[float, ...] | None = None  # the coefficients the ranges follow
        self._last_expression = st.expression
        self._from_slider = False
        self._law_wanted = st.expression
        for name in ("a", "b"):
            getattr(self, name).param.watch(
                lambda e, n=name: self._set(**{n: e.new}), "value_throttled"
            )
        self.law_kind.param.watch(self._on_law_kind, "value")
        self.law_text.param.watch(lambda e: self.apply(e.new), "value")
        self._layout = pn.Column(
            LiteralMarkdown("**force law**", margin=(0, 10)),
            self.preset,
            self.law_kind,
            self.a,
            self.b,
            self.law_text,
            self.coeff_box,
            self.const_box,
            self.trilinear.box,
            self.refusal,
            self.help,
            sizing_mode="stretch_width",
            margin=0,
        )

    def __panel__(self):
        return self._layout

    # ------------------------------------------------------------------ user → state
    @user_action
    def _set(self, **kw) -> None:
        if any(v is None for v in kw.values()):
            return
        self.state.param.update(**kw)

    def _offer(self, text: str, outcome=None) -> None:
        """A law built (or refused) for ``text``: a refusal is shown and the state keeps its
        law; a law enters the state."""
        outcome = compute.laws.lookup_law(text) if outcome is None and text else outcome
        if isinstance(outcome, ParameterError):
            self.refused = f"{outcome}"
            self.refusal.param.update(
                object=f"**law refused:** {md_literal(str(outcome))} — the previous law stays "
                "on screen", visible=True)  # fmt: skip
            return
        self.refusal.visible = False
        self.refused = ""
        self._set(expression=text)

    @user_action
    def _on_preset(self, event) -> None:
        if not event.new:
            return
        if event.new == "cubic":  # the paper's cubic: closed forms, a and b sliders
            self.refusal.visible = False
            self.refused = ""
            self._law_wanted = ""
            self._set(expression="", **PRESETS["cubic"].constants_dict)
            return
        self.apply(preset_text(event.new))  # built at the server's warm-up (app.warmup)

    @user_action
    def _on_const(self, name: str, value) -> None:
        """Constant slider ``name`` moved: the law text is rewritten with the new value and
        rebuilt in the law worker (as a typed law)."""
        if value is None or self._const_anchor is None:
            return
        consts = {n: float(s.value) for n, s in self.const_sliders.items()}
        consts[name] = float(f"{float(value):.6g}")
        self.apply(compute.laws.join_law(self._const_anchor[0], consts))

    def _on_pool_coeff(self, slider, value) -> None:
        k = next((k for k, s in enumerate(self.coeff_sliders) if s is slider), None)
        if k is not None:
            self._on_coeff(k, value)

    def _on_pool_const(self, slider, value) -> None:
        name = next((n for n, s in self.const_sliders.items() if s is slider), None)
        if name is not None:
            self._on_const(name, value)

    @user_action
    def _on_trilinear(self, text: str) -> None:
        """A trilinear slider moved: its law text (5 numbers, parse only) is built here at once
        and applied, or refused with fpucore's reason while the previous law stays."""
        try:
            compute.laws.trusted_expression_law(text)
        except ParameterError:
            pass  # remembered: _offer shows the refusal
        self._law_wanted = text
        self._offer(text)

    @user_action
    def _on_law_kind(self, event) -> None:
        st = self.state
        if event.new == "cubic":
            self._last_expression = st.expression or self._last_expression
            self.refusal.visible = False
            self.refused = ""
            self._set(expression="")
        elif not st.expression:
            # start from the last expression, else from the current cubic as a polynomial
            text = self._last_expression
            if not text:
                try:
                    text = compute.laws.law(st.a, st.b).as_polynomial().expression
                except ParameterError:
                    text = "w + 10*w**2 - w**3 - 0.01*w**4"
                try:  # written by the app: bounded, built here at once
                    compute.laws.trusted_expression_law(text)
                except ParameterError:
                    pass
            self.apply(text)

    @user_action
    def _on_coeff(self, k: int, value) -> None:
        """Coefficient slider k (c_{k+1}) moved: the expression is rewritten from the sliders."""
        if value is None:
            return
        coeffs = [float(s.value) for s in self.coeff_sliders]
        coeffs[k] = float(f"{float(value):.6g}")  # no 10.059999999999999 from the slider step
        text = expression_of(coeffs)
        try:  # written by the app from ≤ MAX_COEFF_SLIDERS floats: bounded, built here at once
            compute.laws.trusted_expression_law(text)
        except ParameterError:
            pass  # the state shows why
        self._law_wanted = text
        self._from_slider = True
        try:
            self._offer(text)
        finally:
            self._from_slider = False

    @user_action
    def apply(self, text: str | None) -> None:
        """A law typed in the box (or chosen; "" for the cubic): applied once it is built.  A
        typed text is built in the law worker within its budgets (app.compute.laws.request_law),
        never in this handler: a law not built yet is applied from the worker's answer (if it is
        still the one wanted), and :attr:`checking` names it meanwhile."""
        if text is None:
            return
        text = text.strip()
        self._law_wanted = text
        if not text or compute.laws.lookup_law(text) is not None:
            self._offer(text)
            return
        self.checking = text
        doc = pn.state.curdoc

        def built(fut) -> None:  # in the law worker's watcher thread
            if self._law_wanted != text or document_gone(doc):
                return  # another law was typed meanwhile, or the browser left
            try:
                with set_curdoc(doc):
                    self._offer(text, fut.result())
            except Exception:  # noqa: BLE001 - the session may have closed meanwhile
                if not document_gone(doc):
                    log.exception("applying the law %r", text[:60])

        compute.laws.request_law(text).add_done_callback(built)

    # ------------------------------------------------------------------ state → widgets
    @contextlib.contextmanager
    def muted(self):
        """The editor ignores its own widgets' events meanwhile (the page holds it muted for its
        whole sync); an event handled by another thread waits for the sync to end (the state's
        lock) and is then applied — neither dropped nor applied under a sync that then writes
        the older state."""
        # per thread, under the state's lock (app.widgets.Syncing): a session's other handler
        # thread waits for the sync to end and then applies its event, never drops it
        with self._syncing():
            yield

    def sync(self) -> None:
        """State → law widgets: a, b (their ranges widened to the state's values), the kind,
        the text and the coefficient sliders.  The editor's watchers ignore these changes."""
        st = self.state
        with self.muted():
            put(self.a, st.a, **widened(st.a, *A_RANGE))
            put(self.b, st.b, **widened(st.b, *B_RANGE))
            poly = bool(st.expression)
            self.law_kind.value = "expression" if poly else "cubic"
            self.a.visible = self.b.visible = not poly
            self.law_text.visible = poly
            self.law_text.value = st.expression
            self._sync_constants()
            pl = self.trilinear.sync(st.expression)
            self._sync_coefficients(poly and not self.const_box.visible and not pl)
            self.preset.value = self._preset_of(st.expression)

    def _preset_of(self, text: str) -> str:
        if not text:
            return "cubic" if (self.state.a, self.state.b) == (-1.0, 10.0) else ""
        return preset_of(text)

    def _sync_constants(self) -> None:
        """One slider per named constant of the state's law (none for a law without)."""
        try:
            expr, consts = compute.laws.split_law(self.state.expression)
        except ParameterError:
            expr, consts = "", {}
        if not consts:
            self.const_box.visible = False
            self._const_anchor = None
            return
        anchor = self._const_anchor
        if anchor is None or anchor[0] != expr or anchor[1] != tuple(consts):
            self._const_anchor = (expr, tuple(consts), dict(consts))
            # the page's pooled sliders re-labelled, not new ones (app.slider_pool)
            taken = self._const_pool.take(list(consts), [f"w-const-{n}" for n in consts])
            self.const_sliders = dict(zip(consts, taken))
        for name, v in consts.items():
            lo, hi = coeff_range(self._const_anchor[2][name])
            put(self.const_sliders[name], v, step=(hi - lo) / 1000, **widened(v, lo, hi))
        self.const_box.visible = True

    def _sync_coefficients(self, poly: bool) -> None:
        st = self.state
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
                put(sl, c, step=(hi - lo) / 1000, **widened(c, lo, hi))
            self.coeff_box.visible = True
        elif self.const_box.visible:
            self.coeff_box.visible = False
        else:
            # an invalid law: the sliders stay only if they made it (so they can move back)
            made = bool(self.coeff_sliders) and st.expression == expression_of(
                [float(s.value) for s in self.coeff_sliders]
            )
            self.coeff_box.visible = poly and made

    def _anchor_sliders(self, coeffs: tuple[float, ...]) -> None:
        """(Re)build the coefficient sliders with ranges around ``coeffs``."""
        self._coeff_anchor = tuple(coeffs)
        if len(coeffs) > MAX_COEFF_SLIDERS:
            self.coeff_sliders = []
            self._coeff_pool.box.visible = False
            self._too_many.param.update(
                object=f"_degree {len(coeffs)} > {MAX_COEFF_SLIDERS}: edit the text_", visible=True
            )
            return
        labels = [f"c{k + 1} (w^{k + 1})" if k else "c1 (w) = f′(0)" for k in range(len(coeffs))]
        # the page's pooled sliders re-labelled, not new ones (app.slider_pool)
        sliders = self._coeff_pool.take(labels, [f"w-c{k + 1}" for k in range(len(coeffs))])
        for sl, c in zip(sliders, coeffs):  # (called in sync: the editor is muted)
            lo, hi = coeff_range(c)
            put(sl, c, start=lo, end=hi, step=(hi - lo) / 1000)
        self.coeff_sliders = sliders
        self._coeff_pool.box.visible = True
        self._too_many.visible = False


def coeff_range(c0: float) -> tuple[float, float]:
    """Slider range of a law coefficient around the typed value c0: c0 ± 2|c0| (so its sign can
    change), [−1, 1] for a zero coefficient."""
    r = 2.0 * abs(c0) if c0 != 0.0 and math.isfinite(c0) else 1.0
    return c0 - r, c0 + r
