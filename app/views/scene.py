"""Scene base class: plot + "error / time" status + message, lazy and off the event loop.

A scene renders only when it is visible (the app calls :meth:`Scene.request` for the active
tab and marks the others stale).  Rendering runs in a per-scene worker thread that coalesces
requests (latest parameters win); heavy fpucore calls run in worker processes
(:func:`app.compute.workers.run_job`) and a newer request or the Cancel button makes the thread stop
waiting (the job is killed if nobody else waits for it), so slider drags never queue stale work.

Root-cause rules:

* the figures of a scene are Bokeh models built once (structure fixed); a render only changes
  their data, ranges and visibility (:mod:`.bokeh_scene`) — no model is ever replaced;
* every change of a served model goes through the session's event loop, and the worker thread
  catches everything: it can never die with its running flag set, and every scene recovers from
  any state (a message, a failure, a cancelled job) at the next request;
* every outcome is shown in the scene: a plot with its error estimates and timings, or a
  message (``ParameterError`` text or a one-line failure) — never a traceback.

Beside it: what a render reports (:mod:`.report`), the files a user takes away
(:mod:`.scene_files`), "Copy as Python" (:mod:`.python_code`), formatting (:mod:`.formatting`)
and untrusted text (:mod:`.untrusted`).
"""

from __future__ import annotations

import io
import logging
import threading
import time

import panel as pn
from panel.io.state import set_curdoc

from fpucore.errors import ParameterError

from .. import compute
from ..data_dir import hide_server_paths
from ..state import ExplorerState
from .formatting import state_stamp
from .python_code import code_box, python_preamble
from .report import Info, SceneMessage, status_markdown
from .scene_files import SceneFiles
from .scene_progress import SceneProgress
from .untrusted import LITERAL_MD, LiteralAlert, LiteralMarkdown, md_literal
from .wait_line import WaitLine

log = logging.getLogger("fpu-explorer")


class Scene(SceneFiles, SceneProgress, pn.viewable.Viewer):
    """Base class of the scenes (a Panel Viewer: ``__panel__`` is the scene's layout).

    Subclasses set ``title``/``caption`` and implement :meth:`make_plot`,
    :meth:`render` (filling ``info``, returning what :meth:`publish` applies),
    :meth:`python_code` and :meth:`download_data`; optionally :meth:`controls`.  The busy
    indicators come from :class:`SceneProgress`, the download buttons from :class:`SceneFiles`.
    A scene is registered once, in app/scene_registry.py, which gives it its ``key``.  A
    subclass sets up its own state and widget watchers in its ``__init__``, after
    ``super().__init__`` has built the widgets and figures."""

    #: the tab's name in URLs and CSS, set from the scene's registry entry (app/views/__init__)
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
    #: "Copy as Python" stays off after a render (set by the page while a refused law is shown:
    #: a render of the previous law that ends after the refusal must not turn it back on)
    copy_blocked = False

    def __init__(self, state: ExplorerState, **params):
        super().__init__(**params)
        self.state = state
        self.plot = self.make_plot()
        self.alert = LiteralAlert(
            "",
            alert_type="warning",
            visible=False,
            css_classes=["scene-message"],
            **LITERAL_MD,
        )
        self.status = LiteralMarkdown(
            "", css_classes=["scene-status"], sizing_mode="stretch_width", **LITERAL_MD
        )
        self._make_progress_widgets()
        self.wait = WaitLine()
        # the first request not yet answered by a published render (the scene's construction
        # counts: a lazy scene is built by the click that opened its tab)
        self._unanswered_since: float | None = time.perf_counter()
        self._make_file_widgets()
        self.code, self.copy_btn, self.code_card = code_box()
        self._extra = self.extra_panes()
        side = pn.Column(
            LiteralMarkdown("#### Error and time", margin=(0, 5)),
            self.status,
            self.wait.line,
            self.wait.probe,
            self.wait.token,
            *self.busy_widgets(),
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
            LiteralMarkdown(self.caption, css_classes=["scene-caption"]),
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
        if self._served:
            pn.state.onload(self.wait.arm)
        self._connected = False  # a browser has had this session open (see session_closed)
        self._lock = threading.Lock()
        self._pending = False
        self._running = False
        self._cancel = False
        self._stamp = state_stamp(state)
        self._render_stamp = self._stamp

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
        self._stamp = info.stamp or self._render_stamp
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
        # The browser left: Bokeh destroys the session only when unused for 15 s (checked every
        # 17 s), and a job ran on for nobody.  A served page never reconnects to its session
        # (a reload opens a new one), so once connected, no connection means gone.
        session = getattr(ctx, "_session", None)
        n = getattr(session, "connection_count", None)
        if n is None:
            return False
        if n > 0:
            self._connected = True
            return False
        return self._connected

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
            if self._unanswered_since is None:  # the server's part of the wait starts here
                self._unanswered_since = time.perf_counter()
            if prepare is not None:
                prepare()
            if self._running:
                return
            self._running = True
        threading.Thread(target=self._loop, name=f"scene-{self.key}", daemon=True).start()

    def request_if_stale(self) -> None:
        """:meth:`request` if the scene is stale and no request waits already."""
        with self._lock:
            if not self.stale or self._pending:
                return
        self.request()

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
        # the stamp on screen changes only with the result it describes (published below);
        # the request in flight names its own parameters beside the spinner
        self._render_stamp = state_stamp(self.state)
        self._computing = self._render_stamp
        try:
            stop_busy = (lambda: None) if building else self._busy()
            try:
                obj = self.render(info)
            finally:
                stop_busy()
        except compute.Superseded:
            if self._cancel:
                self._stamp = info.stamp or self._render_stamp
                self._show_message(
                    "Cancelled. Change a parameter or press the button again to recompute.",
                    "info",
                )
            return None  # else a newer request is pending: the loop renders it next
        except SceneMessage as exc:
            if self._moved_on():
                return None
            self._stamp = info.stamp or self._render_stamp
            self._show_message(str(exc), exc.kind)
            return None
        except ParameterError as exc:
            if self._moved_on():
                return None
            self._stamp = info.stamp or self._render_stamp
            self._show_message(str(exc), "warning")
            return None
        except compute.CancelledError:
            # the worker pool was shut down under the job (the server is stopping; run_job
            # cancels nothing a caller still waits for): not a failure of the app
            if not self.session_closed:
                self._stamp = info.stamp or self._render_stamp
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
            self._stamp = info.stamp or self._render_stamp
            said = f"computation failed: {type(exc).__name__}: {hide_server_paths(exc)}"
            self._show_message(said.splitlines()[0], "danger")
            return None
        if self.session_closed or self._moved_on():
            return None
        try:
            self._stamp = info.stamp or self._render_stamp
            self.publish(obj)
            if info.warning:
                self.alert.param.update(alert_type="warning", object=md_literal(info.warning))
            self.alert.visible = bool(info.warning)
            self.last_message = None
            self.renders += 1
            self.last_info = info
            self._write_status(info, t0)
            now = time.perf_counter()
            since = self._unanswered_since if self._unanswered_since is not None else t0
            self._unanswered_since = None
            parts = (now - min(since, t0), now - t0)
            if building and self._served:
                # a render while a tab is built reaches the browser inside the new models, where
                # no change can be timed: the token changes on the next tick, after them
                self._doc.add_next_tick_callback(lambda: self.wait.served(*parts))
            else:
                self.wait.served(*parts)
            self.code.value = self.python_code()
            self.download.disabled = False
            self.copy_btn.disabled = self.copy_blocked
            for w in self.exporters:
                w.disabled = False
        except Exception as exc:
            if self.session_closed:
                return None
            log.exception("scene %s: plot update failed", self.key)
            said = f"plot update failed: {type(exc).__name__}: {hide_server_paths(exc)}"
            self._show_message(said, "danger")
            return None
        return info

    def _moved_on(self) -> bool:
        """True if the state's parameters changed while this render read them and a render of
        the new ones will follow (a request pending, or the scene marked stale): the render
        may have drawn some values of the new state under the old one's stamp (the diagram's
        current point read after the stamp was taken), so nothing of it is shown."""
        return (self._pending or self.stale) and state_stamp(self.state) != self._render_stamp

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
            self.copy_btn.disabled = True  # nor code that reproduces nothing (a refused law)
            for w in self.exporters:
                w.disabled = True
        except Exception:  # noqa: BLE001
            log.exception("scene %s: showing the message failed", self.key)

    def hide_plot(self) -> None:
        self.plot.visible = False
        for pane in self._extra:
            pane.visible = False

    def _write_status(self, info: Info, t0: float, partial: bool = False) -> None:
        self.status.object = status_markdown(
            info, time.perf_counter() - t0, self._stamp, partial=partial
        )
