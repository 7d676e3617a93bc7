"""What a user sees while a scene renders: a spinner, a progress bar with the running job's
stage, percentage and time left, and the Cancel button — shown only if the render takes longer
than :data:`SPINNER_DELAY_S`.

:class:`SceneProgress` is mixed into :class:`.scene.Scene`, which owns the render loop (its
``cancel``, ``plot`` and session document).  Kept apart from that loop: these indicators live
only while a render runs, fed by the job's progress callbacks, and the spinner is switched on by
a timer thread of its own.
"""

from __future__ import annotations

import logging
import threading
import time

import panel as pn
from panel.io.state import set_curdoc

from .formatting import fmt_time

log = logging.getLogger("fpu-explorer")

#: renders faster than this show no loading spinner (s)
SPINNER_DELAY_S = 0.25


class SceneProgress:
    """The scene's busy indicators and progress reporting (a mixin of Scene)."""

    def _make_progress_widgets(self) -> None:
        self.progress = pn.indicators.Progress(
            value=-1, max=100, visible=False, sizing_mode="stretch_width", bar_color="info"
        )
        # the running job's stage, its percentage and the time left (plain text: no markup)
        self.progress_text = pn.pane.Str(
            "", visible=False, css_classes=["scene-progress"], margin=(0, 10)
        )
        self._stage = ("", 0.0, 0.0)  # (name, start of the stage, last text update)
        # the request in flight, by its own parameters: the status above keeps the last result
        # and the parameters it was computed with until the new result replaces both
        self.computing_text = pn.pane.Str(
            "", visible=False, css_classes=["scene-computing"], margin=(0, 10)
        )
        self._computing = ""
        self.cancel_btn = pn.widgets.Button(
            label="Cancel", color="warning", visible=False, css_classes=["scene-cancel"]
        )
        self.cancel_btn.on_click(lambda _: self.cancel())

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

    def computing_for(self, stamp: str) -> None:
        """The parameters of the request in flight (shown with the spinner): a render that
        learns them late (the Simulation scene's run) names them here."""
        self._computing = stamp
        if self.computing_text.visible:
            self.computing_text.object = f"computing … for {stamp}"

    def set_stage(self, stage: str) -> None:
        """A new stage of the running job, before it reports a fraction."""
        self._stage = (stage, time.perf_counter(), time.perf_counter())
        self.progress.value = -1
        self.progress_text.object = f"{stage} …"

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
                        self.computing_text.param.update(
                            object=f"computing … for {self._computing}", visible=True
                        )
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
                    self.computing_text.visible = False
                    self.progress.visible = False
                    self.progress_text.visible = False
                    self.cancel_btn.visible = False
                self._stage = ("", 0.0, 0.0)

        return stop
