"""Scene base class: plot + "error / time" status + message, lazy and off the event loop.

A scene renders only when it is visible (the app calls :meth:`Scene.request` for the active
tab and marks the others stale).  Rendering runs in a per-scene worker thread that coalesces
requests (latest parameters win); heavy fpucore calls run in worker processes
(:func:`app.compute.run_job`) and a newer request or the Cancel button makes the thread stop
waiting (the job is killed if nobody else waits for it), so slider drags never queue stale work.

Root-cause rules:

* the figures of a scene are Bokeh models built once (structure fixed); a render only changes
  their data, ranges and visibility (:mod:`.bokeh_scene`) — no model is ever replaced;
* every change of a served model goes through the session's event loop, and the worker thread
  catches everything: it can never die with its running flag set, and every scene recovers from
  any state (a message, a failure, a cancelled job) at the next request;
* every outcome is shown in the scene: a plot with its error estimates and timings, or a
  message (``ParameterError`` text or a one-line failure) — never a traceback.
"""

from __future__ import annotations

import io
import json
import logging
import math
import re
import threading
import time
from dataclasses import dataclass, field

import numpy as np
import panel as pn
from panel.io.state import set_curdoc

import fpucore
from fpucore.errors import ParameterError
from fpucore.result import jsonable

from .. import compute
from ..compute import Computed
from ..state import URL_PARAMS, ExplorerState
from ..url_state import url_query
from . import export

log = logging.getLogger("fpu-explorer")

#: renders faster than this show no loading spinner (s)
SPINNER_DELAY_S = 0.25


class SceneMessage(Exception):
    """Shown in the scene instead of a plot (an invalid combination, a missing module ...)."""

    def __init__(self, text: str, kind: str = "warning"):
        super().__init__(text)
        self.kind = kind


@dataclass
class Info:
    """What a render reports next to its plot."""

    #: Markdown: user-supplied parts (a path, an exception's text) go through md_literal
    shown: str = ""
    errors: list[tuple[str, float]] = field(default_factory=list)
    #: differences between two models (e.g. max |discrete − QC|): physics, not numerical error
    differences: list[tuple[str, float]] = field(default_factory=list)
    timings: list[tuple[str, Computed | float]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warning: str | None = None  # shown above the plot (e.g. "current V out of range")

    def time(self, label: str, c: Computed | float) -> None:
        self.timings.append((label, c))

    def error(self, label: str, value) -> None:
        _append_finite(self.errors, label, value)

    def difference(self, label: str, value) -> None:
        """A model difference (shown on its own line, never under "Error")."""
        _append_finite(self.differences, label, value)


def _append_finite(rows: list[tuple[str, float]], label: str, value) -> None:
    try:
        v = float(value)
    except (TypeError, ValueError):
        return
    if math.isfinite(v):
        rows.append((label, v))


def fmt_timing(label: str, c: Computed | float) -> str:
    """'discrete N=500 1.20 s'; a cached result keeps the cost of its computation:
    'discrete N=500 1.20 s (computed earlier, now from the cache)'."""
    if isinstance(c, Computed):
        return f"{label} {fmt_time(c.elapsed_s)}" + (
            " (computed earlier, now from the cache)" if c.cached else ""
        )
    return f"{label} {fmt_time(float(c))}"


#: the code box: monospace, no soft wrap (a long call scrolls instead of breaking)
CODE_CSS = (
    "textarea { font-family: ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; "
    "font-size: 12px; white-space: pre; overflow-wrap: normal; overflow: auto; }"
)

#: "Copy as Python": the Clipboard API where the page has it (https or localhost); else (plain
#: http on another host: navigator.clipboard is undefined) a hidden textarea and the legacy copy
#: command; if that fails too, the code card opens so the user can select the code.  The button
#: says which happened for two seconds.
COPY_JS = """
const say = (text) => {
  btn.label = text;
  setTimeout(() => { btn.label = "Copy as Python"; }, 2000);
};
const legacy = () => {
  const ta = document.createElement("textarea");
  ta.value = code.value;
  ta.setAttribute("readonly", "");
  ta.style.position = "fixed";
  ta.style.opacity = "0";
  document.body.appendChild(ta);
  ta.select();
  let ok = false;
  try { ok = document.execCommand("copy"); } catch (e) { ok = false; }
  document.body.removeChild(ta);
  if (ok) { say("Copied ✓"); } else { card.collapsed = false; say("Select the code below"); }
};
if (navigator.clipboard && window.isSecureContext) {
  navigator.clipboard.writeText(code.value).then(() => say("Copied ✓"), legacy);
} else {
  legacy();
}
"""


def fmt_time(s: float) -> str:
    return f"{s * 1e3:.1f} ms" if s < 1.0 else f"{s:.2f} s"


def fmt_num(x: float, digits: int = 6) -> str:
    return f"{x:.{digits}g}"


def as_csv(columns: dict[str, np.ndarray], header: str = "") -> io.StringIO:
    """CSV text of equal-length columns (header lines start with '#')."""
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    n = max((len(a) for a in arrays), default=0)
    buf = io.StringIO()
    for line in header.splitlines():
        buf.write(f"# {line}\n")
    buf.write(",".join(names) + "\n")
    for i in range(n):
        row = []
        for a in arrays:
            if i < len(a):
                v = a[i]
                row.append(repr(float(v)) if np.isrealobj(v) else str(v))
            else:
                row.append("")
        buf.write(",".join(row) + "\n")
    buf.seek(0)
    return buf


def as_json(obj) -> io.StringIO:
    buf = io.StringIO(json.dumps(jsonable(obj), indent=1))
    buf.seek(0)
    return buf


def law_line(state: ExplorerState) -> str:
    """The law in a data file's header: the cubic's a, b or the expression (exactly as given to
    fpucore.law_from_expression) with its coefficients c_1, c_2, ... (f = Σ c_k w^k)."""
    if not state.expression:
        return f"law: f(w) = a w^3 + b w^2 + w with a={state.a!r}, b={state.b!r}"
    line = f"law: f(w) = {state.expression} (law={state.expression!r}"
    try:
        line += f", coefficients c_1...={state.law().coeffs!r}"
    except ParameterError as exc:
        line += f", invalid: {exc}"
    return line + ")"


def provenance(state: ExplorerState, what: str, **extra) -> str:
    """Header of a data file: what it holds and everything needed to reproduce it."""
    lines = [
        what,
        f"fpu-explorer / fpucore {fpucore.__version__}",
        law_line(state),
        f"mode={state.mode} w_plus={state.w_plus!r} V={state.V!r} N={state.N} tol={state.tol!r}",
    ]
    lines += [f"{k}={v!r}" for k, v in extra.items()]
    return "\n".join(lines)


def state_stamp(state: ExplorerState) -> str:
    """The parameters a render used, exactly as in the URL (shown under every status, so a
    reader — and the browser tests — can tell which state is on screen)."""
    rest = f"w_plus={state.w_plus!r} V={state.V!r} N={state.N} tol={state.tol!r} mode={state.mode}"
    # an expression law replaces a, b (which it does not use); last, as it has spaces
    if state.expression:
        return f"{rest} law={state.expression}"
    return f"a={state.a!r} b={state.b!r} {rest}"


#: characters that start inline Markdown anywhere in a line (emphasis, code, links, strike,
#: math, table cells): backslash-escaped (CommonMark escapes any ASCII punctuation)
_MD_INLINE = frozenset("\\`*_[]~$|")
#: characters that would open or close HTML (and attribute values): written as entities
_HTML_CHARS = {"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#x27;"}
#: block markup, only at a line's start: a heading, a list item (-, +, 1.), a setext underline
_MD_BLOCK = re.compile(r"(?m)^([ \t]*)([#+=-])")
_MD_NUMBERED = re.compile(r"(?m)^([ \t]*\d+)([.)])")


#: the options of a Markdown pane that shows md_literal text: no math and no linkify (which
#: turned "evil.com", "//host" or "a@b.co" in a URL value, and "x.py" in a store path, into links)
LITERAL_MD = {"disable_math": True, "renderer_options": {"linkify": False}}


def md_literal(text) -> str:
    """``text`` for a Markdown pane, shown exactly as typed and never as markup.

    User-supplied text (a URL value, a typed law, an exception message repeating them) reaches
    the page through Markdown panes whose renderer passes raw HTML through: ``<img onerror=…>``
    in a URL ran script in the page.  One pass writes the HTML characters as entities and
    backslash-escapes inline Markdown (one pass, so an entity's ``#`` is not escaped again);
    then block markup at a line's start is escaped.  ``__import__('os')`` and ``w**2`` show
    literally, ``[x](…)`` is no link, ``$…$`` no math, and the source stays readable."""
    out = []
    for ch in str(text):
        if ch in _HTML_CHARS:
            out.append(_HTML_CHARS[ch])
        elif ch in _MD_INLINE:
            out.append("\\" + ch)
        else:
            out.append(ch)

    escaped = _MD_BLOCK.sub(r"\1\\\2", "".join(out))
    return _MD_NUMBERED.sub(r"\1\\\2", escaped)  # "1." → "1\." (no list item)


def law_source(state: ExplorerState) -> str:
    """The fpucore call that makes the state's law (as in "Copy as Python")."""
    if state.expression:
        return f"fpucore.law_from_expression({state.expression!r})"
    return f"CubicLaw(a={float(state.a)!r}, b={float(state.b)!r})"


def python_preamble(state: ExplorerState) -> str:
    """First lines of every scene's "copy as Python" code: the imports and ``law``, built by the
    same fpucore call as the app's (CubicLaw, or fpucore.law_from_expression of the text)."""
    make = f"law = {law_source(state)}\n"
    return (
        f"# reproduces the fpu-explorer view; generated with fpucore {fpucore.__version__}\n"
        "import fpucore\n"
        "from fpucore import floquet, qc, simulate, wave\n"
        "from fpucore.law import CubicLaw\n\n"
        f"print(fpucore.__version__)  # {fpucore.__version__!r} when generated\n" + make
    )


class Scene(pn.viewable.Viewer):
    """Base class of the scenes (a Panel Viewer: ``__panel__`` is the scene's layout).

    Subclasses set ``key``/``title``/``caption`` and implement :meth:`make_plot`,
    :meth:`render` (filling ``info``, returning what :meth:`publish` applies),
    :meth:`python_code` and :meth:`download_data`; optionally :meth:`controls`."""

    key = "scene"
    title = "Scene"
    #: one line under the plot: what it shows in words and the paper's figure
    caption = ""
    #: state parameters whose change makes this scene stale
    depends: tuple[str, ...] = ("a", "b", "expression", "w_plus", "V", "mode", "N", "tol")
    plot_height = 560
    #: cheap enough (QC, cached) to render synchronously while the page is being built
    cheap = False
    #: the scene draws figures: "Download figure" (SVG, PNG) and "Download notebook"
    exports = True

    def __init__(self, state: ExplorerState, **params):
        super().__init__(**params)
        self.state = state
        self.plot = self.make_plot()
        self.alert = pn.pane.Alert(
            "",
            alert_type="warning",
            visible=False,
            css_classes=["scene-message"],
            **LITERAL_MD,
        )
        self.status = pn.pane.Markdown(
            "", css_classes=["scene-status"], sizing_mode="stretch_width", **LITERAL_MD
        )
        self.progress = pn.indicators.Progress(
            value=-1, max=100, visible=False, sizing_mode="stretch_width", bar_color="info"
        )
        # the running job's stage, its percentage and the time left (plain text: no markup)
        self.progress_text = pn.pane.Str(
            "", visible=False, css_classes=["scene-progress"], margin=(0, 10)
        )
        self._stage = ("", 0.0, 0.0)  # (name, start of the stage, last text update)
        self.cancel_btn = pn.widgets.Button(
            label="Cancel", color="warning", visible=False, css_classes=["scene-cancel"]
        )
        self.cancel_btn.on_click(lambda _: self.cancel())
        self.download = pn.widgets.FileDownload(
            callback=self._download,
            filename=f"{self.key}.csv",
            label="Download data",
            color="light",
            css_classes=["scene-download"],
        )
        # the scene as drawn (its last render, nothing recomputed) and a notebook of its code
        self.exporters = []
        if self.exports:
            self.fig_svg, self.fig_png, self.notebook = (
                pn.widgets.FileDownload(
                    callback=lambda kind=kind: self._export(kind),
                    filename=f"{self.key}.{ext}",
                    label=label,
                    color="light",
                    css_classes=[f"scene-export-{kind}"],
                )
                for kind, ext, label in (
                    ("svg", "svg", "Figure SVG"),
                    ("png", "png", "Figure PNG"),
                    ("notebook", "ipynb", "Notebook"),
                )
            )
            self.exporters = [self.fig_svg, self.fig_png, self.notebook]
        self.code = pn.widgets.TextAreaInput(
            value="",
            height=220,
            sizing_mode="stretch_width",
            css_classes=["scene-code"],
            stylesheets=[CODE_CSS],
        )
        self.copy_btn = pn.widgets.Button(
            label="Copy as Python", color="light", css_classes=["scene-copy"]
        )
        self.code_card = pn.Card(
            self.code, title="Python", collapsed=True, sizing_mode="stretch_width", margin=2
        )
        self.copy_btn.js_on_click(
            args={"code": self.code, "btn": self.copy_btn, "card": self.code_card},
            code=COPY_JS,
        )
        self._extra = self.extra_panes()
        side = pn.Column(
            pn.pane.Markdown("#### Error and time", margin=(0, 5)),
            self.status,
            self.progress,
            self.progress_text,
            self.cancel_btn,
            *self.controls(),
            pn.Row(self.download, self.copy_btn),
            *([pn.Row(*self.exporters)] if self.exporters else []),
            self.code_card,
            width=330,
        )
        main = pn.Column(
            self.alert,
            self.plot,
            *self._extra,
            pn.pane.Markdown(self.caption, css_classes=["scene-caption"]),
            sizing_mode="stretch_width",
        )
        self.panel = pn.Row(
            main,
            side,
            sizing_mode="stretch_width",
            name=self.title,
            css_classes=[f"scene-{self.key}"],
        )
        self.stale = True
        self.renders = 0
        self.last_info: Info | None = None
        self.last_message: str | None = None
        # the session's document: worker threads render in its context, so Panel resolves
        # resources (server-relative, not CDN) and schedules model updates on its event loop
        self._doc = pn.state.curdoc
        self._served = self._doc is not None and self._doc.session_context is not None
        self._connected = False  # a browser has had this session open (see session_closed)
        self._lock = threading.Lock()
        self._pending = False
        self._running = False
        self._cancel = False
        self._stamp = state_stamp(state)
        self._extra_watch()
        if hasattr(self, "show_scenario"):  # a paper figure's initial data (state.scenario)
            if state.scenario:
                self.show_scenario(**state.scenario)  # run (if asked) at the first render
            state.param.watch(self._on_scenario, "scenario")

    def _on_scenario(self, event) -> None:
        """A paper figure set this scene's initial data: shown now, and run if it asks."""
        if not event.new:
            return
        if self.state.tab != self.key:
            self.show_scenario(**event.new)  # run (if asked) when the tab is opened
            return
        self.request(prepare=lambda: self.show_scenario(**event.new))

    def __panel__(self):
        return self.panel

    # ------------------------------------------------------------------ subclass API
    def make_plot(self):  # pragma: no cover - abstract
        raise NotImplementedError

    def controls(self) -> list:
        return []

    def extra_panes(self) -> list:
        """Further panes under the main plot (e.g. a clickable diagram)."""
        return []

    def _extra_watch(self) -> None:
        """Subclasses watch their own widgets here (call self.request() on change)."""

    def render(self, info: Info):  # pragma: no cover - abstract
        raise NotImplementedError

    def publish(self, obj) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    def python_code(self) -> str:
        """fpucore calls that reproduce what is shown (after a successful render)."""
        return python_preamble(self.state)

    def download_data(self) -> tuple[str, io.StringIO]:
        raise SceneMessage("nothing to download yet")

    # ------------------------------------------------------------------ helpers for subclasses
    def require_valid(self) -> None:
        """Raise SceneMessage with the state's explanation if the parameters are invalid."""
        problem = self.state.problem()
        if problem is not None:
            raise SceneMessage(problem)

    def show_intermediate(self, obj, info: Info) -> None:
        """Publish a first (cheap) result while a costlier part is still computing."""
        self.publish(obj)
        self._write_status(info, time.perf_counter(), partial=True)

    def superseded(self) -> bool:
        """True once the running render is no longer wanted (a newer request, Cancel, or the
        browser closed the session)."""
        return self._pending or self._cancel or self.session_closed

    @property
    def session_closed(self) -> bool:
        """True once Bokeh has destroyed the served session's document (the browser left).
        Bokeh then clears every model's properties, so they read as class defaults (a figure's
        Range1d becomes a DataRange1d, a renderer loses its glyph): a render still running for
        that session must neither read nor write them, and nobody is left to see a message."""
        if not self._served:
            return False
        ctx = self._doc.session_context
        if ctx is None:
            return True
        # The browser left: its websocket closed, but Bokeh destroys the session only when it
        # has been unused for --unused-session-lifetime (15 s, checked every 17 s), and a job
        # ran on for up to half a minute for nobody.  A served page never reconnects to its
        # session (a reload opens a new one), so once connected, no connection means gone.
        session = getattr(ctx, "_session", None)
        n = getattr(session, "connection_count", None)
        if n is None:
            return False
        if n > 0:
            self._connected = True
            return False
        return self._connected

    def cancel(self) -> None:
        """The Cancel button: stop waiting for the running job (killed if nobody else waits)."""
        self._cancel = True

    def set_progress(self, done: float, total: float | None = None, stage: str = "") -> None:
        """Progress of the running job: the fraction ``done`` (or done / total) of ``stage``;
        a new stage restarts the time-left estimate (elapsed × (1 − x) / x, once 2 % are done
        and half a second has passed).  The text changes at most four times a second (each
        change is a model update sent to the browser)."""
        x = float(done) if total is None else float(done) / max(float(total), 1.0)
        x = min(max(x, 0.0), 1.0)
        now = time.perf_counter()
        name, t0, last = self._stage
        if stage and stage != name:
            name, t0, last = stage, now, 0.0
        self.progress.value = int(100 * x)
        if now - last < 0.25 and x < 1.0:
            self._stage = (name, t0, last)
            return
        text = f"{name}: {100 * x:.0f} %" if name else f"{100 * x:.0f} %"
        if 0.02 <= x < 1.0 and now - t0 >= 0.5:
            text += f" · about {fmt_time((now - t0) * (1.0 - x) / x)} left"
        self._stage = (name, t0, now)
        self.progress_text.object = text

    def stage_progress(self, stage: str):
        """The progress callback (a fraction in [0, 1]) of one named stage."""
        return lambda x: self.set_progress(x, stage=stage)

    def set_stage(self, stage: str) -> None:
        """A new stage of the running job, before it reports a fraction."""
        self._stage = (stage, time.perf_counter(), time.perf_counter())
        self.progress.value = -1
        self.progress_text.object = f"{stage} …"

    # ------------------------------------------------------------------ refresh machinery
    def request(self, prepare=None) -> None:
        """Render in the scene's worker thread (latest request wins; never blocks the caller).
        ``prepare()`` runs under the same lock, after the request is marked: a render still
        looping (earlier requests) that reads what ``prepare`` set is already superseded, and
        submits no job (run_job) — a paper figure's run was submitted by the render in flight,
        cancelled by this very request (its worker killed) and resubmitted to a cold worker:
        10 s instead of 2 s."""
        with self._lock:
            self._pending = True
            if prepare is not None:
                prepare()
            if self._running:
                return
            self._running = True
        threading.Thread(target=self._loop, name=f"scene-{self.key}", daemon=True).start()

    def _loop(self) -> None:
        """Worker thread: render until no request is pending.  Catches everything, so the
        running flag is always cleared and the next request starts a new thread."""
        try:
            with set_curdoc(self._doc):
                while True:
                    with self._lock:
                        if not self._pending or self.session_closed:
                            self._running = self._pending = False
                            return
                        self._pending = False
                        self._cancel = False
                    try:
                        self.refresh()
                    except BaseException:  # noqa: BLE001 - logged; the loop goes on
                        log.exception("scene %s: render loop", self.key)
        finally:
            with self._lock:
                self._running = False

    def wait_idle(self, timeout: float = 60.0) -> bool:
        """For tests: wait until the worker has nothing left to do."""
        t_end = time.monotonic() + timeout
        while time.monotonic() < t_end:
            with self._lock:
                if not self._running and not self._pending:
                    return True
            time.sleep(0.01)
        return False

    def refresh(self, building: bool = False) -> Info | None:
        """Render now (synchronously) and update plot, status and message.

        ``building``: called while the page itself is being built (on the session's thread,
        before the models reach the browser) — no spinner timer runs then (a timer thread could
        switch the spinner on after this render has finished and leave it on)."""
        if self.session_closed:
            return None
        t0 = time.perf_counter()
        info = Info()
        self.stale = False
        self._stamp = state_stamp(self.state)
        try:
            stop_busy = (lambda: None) if building else self._busy()
            try:
                obj = self.render(info)
            finally:
                stop_busy()
        except compute.Superseded:
            if self._cancel:
                self._show_message(
                    "Cancelled. Change a parameter or press the button again to recompute.",
                    "info",
                )
            return None  # else a newer request is pending: the loop renders it next
        except SceneMessage as exc:
            self._show_message(str(exc), exc.kind)
            return None
        except ParameterError as exc:
            self._show_message(str(exc), "warning")
            return None
        except compute.CancelledError:
            # the worker pool was shut down under the job (the server is stopping; run_job
            # cancels nothing a caller still waits for): not a failure of the app
            if not self.session_closed:
                self._show_message(
                    "Stopped: the server's worker processes were shut down. Press the button or "
                    "change a parameter to compute again.",
                    "info",
                )
            return None
        except Exception as exc:  # the server keeps serving; the log keeps the traceback
            if self.session_closed:  # the models were emptied under the render: not a failure
                return None
            log.exception("scene %s failed", self.key)
            self._show_message(
                f"computation failed: {type(exc).__name__}: {exc}".splitlines()[0], "danger"
            )
            return None
        if self.session_closed:
            return None
        try:
            self.publish(obj)
            if info.warning:
                self.alert.param.update(alert_type="warning", object=md_literal(info.warning))
            self.alert.visible = bool(info.warning)
            self.last_message = None
            self.renders += 1
            self.last_info = info
            self._write_status(info, t0)
            self.code.value = self.python_code()
            self.download.disabled = False
            for w in self.exporters:
                w.disabled = False
        except Exception as exc:
            if self.session_closed:
                return None
            log.exception("scene %s: plot update failed", self.key)
            self._show_message(f"plot update failed: {type(exc).__name__}: {exc}", "danger")
            return None
        return info

    def _busy(self):
        """Spinner, progress bar and Cancel button, shown only if the render takes longer than
        SPINNER_DELAY_S: toggling them costs tens of ms of model updates, more than a fast
        (QC, cached) render itself.  Returns the function that stops them."""
        lock = threading.Lock()
        flags = {"done": False, "on": False}
        doc = self._doc

        def on():
            with lock, set_curdoc(doc):
                if not flags["done"]:
                    flags["on"] = True
                    try:
                        self.plot.loading = True
                        self.progress.param.update(value=-1, visible=True)
                        self.progress_text.visible = True
                        self.cancel_btn.visible = True
                    except Exception:  # noqa: BLE001 - cosmetic; never kill the timer's caller
                        log.exception("scene %s: busy indicator", self.key)

        timer = threading.Timer(SPINNER_DELAY_S, on)
        timer.daemon = True
        timer.start()

        def stop():
            timer.cancel()
            with lock:
                flags["done"] = True
                if flags["on"]:
                    self.plot.loading = False
                    self.progress.visible = False
                    self.progress_text.visible = False
                    self.cancel_btn.visible = False
                self._stage = ("", 0.0, 0.0)

        return stop

    def _show_message(self, text: str, kind: str) -> None:
        """The message instead of the plot.  Never raises (the worker thread must survive)."""
        self.last_message = text
        self.last_info = None
        try:
            self.alert.param.update(alert_type=kind, object=md_literal(text), visible=True)
            self.hide_plot()
            stamp = md_literal(self._stamp)
            self.status.object = f"_no plot: see the message_\n\n<small>Parameters: {stamp}</small>"
            # every line a comment: a message repeats user text, which may hold line breaks
            # (a store path from a link), and the code is meant to be pasted and run
            said = "".join(f"# {line}\n" for line in f"nothing shown: {text}".splitlines())
            self.code.value = python_preamble(self.state) + said
            self.download.disabled = True  # nothing to download until a plot is shown
            for w in self.exporters:
                w.disabled = True
        except Exception:  # noqa: BLE001
            log.exception("scene %s: showing the message failed", self.key)

    def hide_plot(self) -> None:
        self.plot.visible = False
        for pane in self._extra:
            pane.visible = False

    def _write_status(self, info: Info, t0: float, partial: bool = False) -> None:
        lines = []
        if info.shown:
            lines.append(f"**Shown:** {info.shown}")
        if info.errors:
            errs = " · ".join(f"{k} {v:.2e}" for k, v in info.errors)
            lines.append(f"**Error:** {errs}")
        if info.differences:
            diffs = " · ".join(f"{k} {v:.2e}" for k, v in info.differences)
            lines.append(f"**Model difference:** {diffs}")
        tparts = [fmt_timing(label, c) for label, c in info.timings]
        tparts.append(f"server {fmt_time(time.perf_counter() - t0)}")
        lines.append("**Time:** " + " · ".join(tparts))
        lines.extend(f"_{n}_" for n in info.notes)
        if partial:
            lines.append("_computing the rest ..._")
        lines.append(f"<small>Parameters: {md_literal(self._stamp)}</small>")
        self.status.object = "\n\n".join(lines)

    def _download(self):
        try:
            name, buf = self.download_data()
        except (SceneMessage, ParameterError) as exc:
            said = "".join(f"# {line}\n" for line in str(exc).splitlines())
            buf, name = io.StringIO(said), f"{self.key}-unavailable.txt"
        self.download.filename = name
        return buf

    # ------------------------------------------------------------------ export
    def figure_models(self) -> list:
        """The Bokeh models the scene draws (BokehScene: its figures); [] for none."""
        return []

    def notebook_plot(self) -> str:
        """The notebook's last cell: Matplotlib code drawing what the code cells computed."""
        return ""

    def url_query(self) -> str:
        """The state as the URL's query string (what a link to this view carries)."""
        q = url_query(self.state) | {"tab": self.key}
        return "&".join(f"{name}={q[name]}" for name in URL_PARAMS if name in q)

    def export_figure(self, fmt: str) -> bytes:
        """The scene's figures as drawn (the models of the last render), SVG or PNG bytes."""
        if self.last_info is None:
            raise SceneMessage("nothing drawn yet")
        try:
            return export.figure_bytes(
                self.figure_models(), fmt, f"fpu-explorer {self.title}: {self._stamp}"
            )
        except LookupError as exc:
            raise SceneMessage(f"no figure: {exc}") from None

    def export_notebook(self) -> str:
        """A notebook of the current view: the state, the code of "Copy as Python" (one cell
        per computation) and a plot cell (JSON text)."""
        if self.last_info is None:
            raise SceneMessage("nothing shown yet")
        shown = self.status.object.split("<small>")[0].strip()
        intro = (
            f"{self.caption}\n\nThe fpu-explorer view **{self.title}** with `?{self.url_query()}`"
            f" (fpucore {fpucore.__version__}). On screen when exported:\n\n{shown}\n\n"
            "Run all cells: they compute the same numbers with fpucore and draw them."
        )
        return export.notebook_json(
            f"fpu-explorer: {self.title}", intro, self.python_code(), self.notebook_plot()
        )

    def _export(self, kind: str):
        widget = {"svg": self.fig_svg, "png": self.fig_png, "notebook": self.notebook}[kind]
        try:
            if kind == "notebook":
                buf, name = io.StringIO(self.export_notebook()), f"{self.key}.ipynb"
            else:
                buf, name = io.BytesIO(self.export_figure(kind)), f"{self.key}.{kind}"
        except (SceneMessage, ParameterError) as exc:
            said = "".join(f"# {line}\n" for line in str(exc).splitlines())
            buf, name = io.StringIO(said), f"{self.key}-unavailable.txt"
        except Exception as exc:  # the server keeps serving; the log keeps the traceback
            log.exception("scene %s: export %s failed", self.key, kind)
            text = f"export failed: {type(exc).__name__}: {exc}"
            buf = io.StringIO("".join(f"# {line}\n" for line in text.splitlines()))
            name = f"{self.key}-unavailable.txt"
        widget.filename = name
        return buf
