"""Scene base class: plot + "error / time" status + message, lazy and off the event loop.

A scene renders only when it is visible (the app calls :meth:`Scene.request` for the active
tab and marks the others stale).  Rendering runs in a per-scene worker thread that coalesces
requests (latest parameters win), so slider drags never queue up stale work and the Bokeh event
loop stays free; Panel schedules the resulting model updates on the session's loop.

Every outcome is shown in the scene: a plot with its error estimates and timings, or a message
(``ParameterError`` text or a one-line failure) — never a traceback.
"""

from __future__ import annotations

import io
import json
import logging
import math
import threading
import time
from dataclasses import dataclass, field

import holoviews as hv
import numpy as np
import panel as pn
from panel.io.state import set_curdoc

from fpucore.cli.common import jsonable
from fpucore.errors import ParameterError

from ..compute import Computed
from ..state import ExplorerState

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

    shown: str = ""
    errors: list[tuple[str, float]] = field(default_factory=list)
    timings: list[tuple[str, Computed | float]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warning: str | None = None  # shown above the plot (e.g. "current V out of range")

    def time(self, label: str, c: Computed | float) -> None:
        self.timings.append((label, c))

    def error(self, label: str, value) -> None:
        try:
            v = float(value)
        except (TypeError, ValueError):
            return
        if math.isfinite(v):
            self.errors.append((label, v))


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


class Scene:
    """Base class of the six scenes.  Subclasses set ``key``/``title`` and implement
    :meth:`render` (returning a HoloViews object — or, in ``BokehScene``, the in-place
    updates of a Bokeh figure built once — and filling ``info``), optionally
    :meth:`controls` (extra widgets) and :meth:`download_data`."""

    key = "scene"
    title = "Scene"
    #: state parameters whose change makes this scene stale
    depends: tuple[str, ...] = ("a", "b", "w_plus", "V", "mode", "N", "tol")
    plot_height = 460
    #: cheap enough (QC, cached) to render synchronously while the page is being built
    cheap = False

    def __init__(self, state: ExplorerState):
        self.state = state
        self.plot = self.make_plot()
        self.alert = pn.pane.Alert(
            "", alert_type="warning", visible=False, css_classes=["scene-message"]
        )
        self.status = pn.pane.Markdown(
            "", css_classes=["scene-status"], sizing_mode="stretch_width"
        )
        self.progress = pn.indicators.Progress(
            value=0, max=100, visible=False, sizing_mode="stretch_width", bar_color="info"
        )
        self.download = pn.widgets.FileDownload(
            callback=self._download,
            filename=f"{self.key}.csv",
            label="Download data",
            color="light",
            css_classes=["scene-download"],
        )
        self._extra = self.extra_panes()
        side = pn.Column(
            pn.pane.Markdown("#### Error and time", margin=(0, 5)),
            self.status,
            self.progress,
            *self.controls(),
            self.download,
            width=320,
        )
        self.panel = pn.Row(
            pn.Column(self.alert, self.plot, *self._extra, sizing_mode="stretch_width"),
            side,
            sizing_mode="stretch_width",
            name=self.title,
            css_classes=[f"scene-{self.key}"],
        )
        self.stale = True
        self.renders = 0
        self.last_info: Info | None = None
        self.last_message: str | None = None
        self._sig: tuple | None = None
        self._pipes: list = []
        self._dmaps: list = []
        # the session's document: worker threads render in its context, so Panel resolves
        # resources (server-relative, not CDN) and schedules model updates on its event loop
        self._doc = pn.state.curdoc
        self._lock = threading.Lock()
        self._pending = False
        self._running = False
        self._extra_watch()

    # ------------------------------------------------------------------ subclass API
    def make_plot(self):
        """The pane the plot is shown in (HoloViews here; raw Bokeh in BokehScene)."""
        return pn.pane.HoloViews(
            None, sizing_mode="stretch_width", min_height=self.plot_height, linked_axes=False
        )

    def controls(self) -> list:
        return []

    def extra_panes(self) -> list:
        """Further panes under the main plot (e.g. a clickable diagram)."""
        return []

    def _extra_watch(self) -> None:
        """Subclasses watch their own widgets here (call self.request() on change)."""

    def render(self, info: Info):  # pragma: no cover - abstract
        raise NotImplementedError

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

    def set_progress(self, done: int, total: int) -> None:
        self.progress.visible = True
        self.progress.value = int(100 * done / max(total, 1))

    # ------------------------------------------------------------------ in-place plot updates
    def publish(self, obj) -> None:
        """Show a HoloViews object.  If it has the same structure as the one on screen (same
        panels, same element types and labels), only the data are sent: each panel is a
        DynamicMap fed by a Pipe, so Bokeh updates its data sources in place instead of
        rebuilding the figure (tens of ms instead of hundreds).  Otherwise rebuild."""
        self.plot.visible = True
        for pane in self._extra:
            pane.visible = True
        panels = list(obj) if isinstance(obj, hv.Layout) else [obj]
        sig = tuple(_signature(p) for p in panels)
        if sig == self._sig and self._pipes:
            pipes = list(self._pipes)

            def send():
                for pipe, p in zip(pipes, panels):
                    pipe.send(p)

            doc = self._doc
            if doc is not None and doc.session_context is not None:
                # HoloViews plot updates belong on the session's event loop, after the
                # (also scheduled) build of the plot they update
                pn.state.execute(send, schedule=True)
            else:
                send()
            return
        self._pipes = [hv.streams.Pipe(data=p) for p in panels]
        dmaps = [hv.DynamicMap(_identity, streams=[pipe]) for pipe in self._pipes]
        if isinstance(obj, hv.Layout):
            out = hv.Layout(dmaps).cols(obj._max_cols).opts(shared_axes=False)
            dmaps = list(out)  # .opts() clones: streams must attach to what is displayed
        else:
            out = dmaps[0]
        self._dmaps = dmaps
        self.on_dmaps(dmaps)
        self._sig = sig
        self.plot.object = out

    def on_dmaps(self, dmaps: list) -> None:
        """Hook: attach streams (e.g. a Tap) to freshly built panels."""

    # ------------------------------------------------------------------ refresh machinery
    def request(self) -> None:
        """Render in the scene's worker thread (latest request wins; never blocks the caller)."""
        with self._lock:
            self._pending = True
            if self._running:
                return
            self._running = True
        threading.Thread(target=self._loop, name=f"scene-{self.key}", daemon=True).start()

    def _loop(self) -> None:
        with set_curdoc(self._doc):
            while True:
                with self._lock:
                    if not self._pending:
                        self._running = False
                        return
                    self._pending = False
                self.refresh()

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
        t0 = time.perf_counter()
        info = Info()
        self.stale = False
        stop_spinner = (lambda: None) if building else self._spinner()
        try:
            obj = self.render(info)
        except SceneMessage as exc:
            self._show_message(str(exc), exc.kind)
            return None
        except ParameterError as exc:
            self._show_message(str(exc), "warning")
            return None
        except Exception as exc:  # the server keeps serving; the log keeps the traceback
            log.exception("scene %s failed", self.key)
            self._show_message(
                f"computation failed: {type(exc).__name__}: {exc}".splitlines()[0], "danger"
            )
            return None
        finally:
            stop_spinner()
            self.progress.visible = False
        try:
            self.publish(obj)
        except Exception as exc:
            log.exception("scene %s: plot update failed", self.key)
            self._sig = None  # rebuild next time
            self._show_message(f"plot update failed: {type(exc).__name__}: {exc}", "danger")
            return None
        if info.warning:
            self.alert.alert_type = "warning"
            self.alert.object = info.warning
        self.alert.visible = bool(info.warning)
        self.last_message = None
        self.renders += 1
        self.last_info = info
        self._write_status(info, t0)
        return info

    def _spinner(self):
        """Show the plot's loading spinner only if the render takes longer than
        SPINNER_DELAY_S: toggling it costs tens of ms of model updates, more than a fast
        (QC, cached) render itself.  Returns the function that stops it."""
        lock = threading.Lock()
        flags = {"done": False, "on": False}
        doc = self._doc

        def on():
            with lock, set_curdoc(doc):
                if not flags["done"]:
                    flags["on"] = True
                    self.plot.loading = True

        timer = threading.Timer(SPINNER_DELAY_S, on)
        timer.daemon = True
        timer.start()

        def stop():
            timer.cancel()
            with lock:
                flags["done"] = True
                if flags["on"]:
                    self.plot.loading = False

        return stop

    def _show_message(self, text: str, kind: str) -> None:
        self.last_message = text
        self.last_info = None
        self.alert.alert_type = kind
        self.alert.object = text
        self.alert.visible = True
        self.plot.visible = False
        for pane in self._extra:
            pane.visible = False
        self.status.object = "_no plot: see the message_"

    def _write_status(self, info: Info, t0: float, partial: bool = False) -> None:
        lines = []
        if info.shown:
            lines.append(f"**Shown:** {info.shown}")
        if info.errors:
            errs = " · ".join(f"{k} {v:.2e}" for k, v in info.errors)
            lines.append(f"**Error:** {errs}")
        tparts = []
        for label, c in info.timings:
            if isinstance(c, Computed):
                tparts.append(
                    f"{label} {fmt_time(c.elapsed_s)}" + (" (cached)" if c.cached else "")
                )
            else:
                tparts.append(f"{label} {fmt_time(float(c))}")
        tparts.append(f"server {fmt_time(time.perf_counter() - t0)}")
        lines.append("**Time:** " + " · ".join(tparts))
        lines.extend(f"_{n}_" for n in info.notes)
        if partial:
            lines.append("_computing the rest ..._")
        self.status.object = "\n\n".join(lines)

    def _download(self):
        try:
            name, buf = self.download_data()
        except (SceneMessage, ParameterError) as exc:
            buf, name = io.StringIO(f"# {exc}\n"), f"{self.key}-unavailable.txt"
        self.download.filename = name
        return buf


def _identity(data):
    return data


def _signature(obj) -> tuple:
    """Structure of a panel: element types, groups and labels (what HoloViews matches on)."""
    items = list(obj) if isinstance(obj, hv.Overlay) else [obj]
    return tuple((type(e).__name__, e.group, e.label) for e in items)


hv.extension("bokeh", logo=False)
# axes follow the data when a DynamicMap panel is updated in place
hv.opts.defaults(
    *(
        getattr(hv.opts, n)(framewise=True)
        for n in ("Curve", "Scatter", "Area", "Contours", "QuadMesh", "ErrorBars", "Overlay")
    )
)
