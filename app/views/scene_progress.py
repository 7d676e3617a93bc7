"""What a user sees while a scene renders: the request's parameters, a progress bar with the
running job's stage, percentage and time left, and the Cancel button — shown only if the render
takes longer than :data:`SPINNER_DELAY_S`.

They sit in a box of fixed size and are shown and hidden by style (``visibility``), never by
their models' ``visible`` nor a size change: BokehJS answers each change of a model's
visibility, CSS classes or size by laying out the whole tab again, which redraws every figure
in it — 0.3–1.2 s each in the browser beside the Simulation scene's figures, and a Paper click
into a simulation made ten such changes for these indicators and the plot's loading spinner
(measured with a hook on BokehJS's ``invalidate_layout``).  The place stays empty when idle.

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

#: renders faster than this show no busy indicators (s)
SPINNER_DELAY_S = 0.25
#: the busy indicators' styles: hidden keeps their place (no layout change in the browser);
#: opacity too, since a text pane makes its inner box visible by a style of its own
HIDDEN = {"visibility": "hidden", "opacity": "0"}
SHOWN = {"visibility": "visible", "opacity": "1"}


class SceneProgress:
    """The scene's busy indicators and progress reporting (a mixin of Scene)."""

    def _make_progress_widgets(self) -> None:
        fixed = {"styles": HIDDEN, "height": 20, "sizing_mode": "stretch_width"}
        clip = {**HIDDEN, "overflow": "hidden"}  # a long line is cut, the box keeps its size
        self.progress = pn.indicators.Progress(value=-1, max=100, bar_color="info", **fixed)
        # the running job's stage, its percentage and the time left (plain text: no markup)
        self.progress_text = pn.pane.Str(
            "", css_classes=["scene-progress"], margin=(0, 10), **{**fixed, "styles": clip}
        )
        self._stage = ("", 0.0, 0.0)  # (name, start of the stage, last text update)
        # the request in flight, by its own parameters: the status above keeps the last result
        # and the parameters it was computed with until the new result replaces both
        self.computing_text = pn.pane.Str(
            "",
            css_classes=["scene-computing"],
            margin=(0, 10),
            **{
                **fixed,
                "height": 48,
                "styles": {**clip, "overflow-y": "auto"},
            },  # three lines, the rest scrolled
            stylesheets=["pre { white-space: pre-wrap; margin: 0; }"],
        )
        self._computing = ""
        self.cancel_btn = pn.widgets.Button(
            label="Cancel",
            color="warning",
            css_classes=["scene-cancel"],
            styles=HIDDEN,
            height=32,
        )
        self.cancel_btn.on_click(lambda _: self.cancel())
        #: the indicators are shown (by style; see the module docstring)
        self.busy_shown = False

    def busy_widgets(self) -> list:
        """The indicators, in the order the scene's side column shows them."""
        return [self.computing_text, self.progress, self.progress_text, self.cancel_btn]

    def _show_busy(self, on: bool) -> None:
        """Show or hide the indicators by style (no layout change; see the module docstring)."""
        self.busy_shown = on
        for w in self.busy_widgets():
            w.styles = {**w.styles, **(SHOWN if on else HIDDEN)}

    def cancel(self) -> None:
        """The Cancel button: the render stops waiting for its job (killed if nobody else waits,
        within the job's 50 ms poll).  The page says so at once, from the click's handler, before
        the render's cleanup: one text change, no layout change (the cleanup's message follows;
        at load 9 it came 7.3 s after the click, behind the indicators' layout changes)."""
        self._cancel = True
        if self.busy_shown:
            self.computing_text.object = "cancelled: stopping the job …"

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

    def note_queue(self, ahead: int) -> None:
        """The job waits for a free worker behind ``ahead`` earlier jobs (any session's runs;
        the pool has one worker per core): said before it starts, cleared when it starts."""
        if ahead > 0:
            jobs = "job" if ahead == 1 else "jobs"
            self.progress_text.object = (
                f"waiting for a free worker: {ahead} {jobs} ahead (other runs on this server)"
            )
        elif self.progress_text.object.startswith("waiting for a free worker"):
            self.progress_text.object = "started …"

    def job_hooks(self, stage: str = "", progress=None) -> dict:
        """The keywords of ``compute.run`` for this scene's heavy job: Cancel and newer requests
        (``stop``), the queue note, and ``progress`` (or a named stage's progress)."""
        if progress is None and stage:
            progress = self.stage_progress(stage)
        return {"stop": self.superseded, "queued": self.note_queue, "progress": progress}

    def stage_progress(self, stage: str):
        """The progress callback (a fraction in [0, 1]) of one named stage."""
        return lambda x: self.set_progress(x, stage=stage)

    def computing_for(self, stamp: str) -> None:
        """The parameters of the request in flight (shown with the spinner): a render that
        learns them late (the Simulation scene's run) names them here."""
        self._computing = stamp
        if self.busy_shown:
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
                        self.computing_text.object = f"computing … for {self._computing}"
                        self.progress.value = -1
                        self._show_busy(True)
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
                    self._show_busy(False)
                self._stage = ("", 0.0, 0.0)

        return stop
