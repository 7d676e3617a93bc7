"""Sidebar widgets that stay in step with the server, and how the page moves them.

With ``pn.extension(throttled=True)`` a slider or number box reaches the server only through
``value_throttled``, which Panel never sends back to the browser; the subclasses here keep it in
step (see :class:`_ThrottledInStep`).  :func:`put` moves a widget and its ``value_throttled``
together, and :func:`widened` keeps a slider's range around the state's value.  Kept
apart from the page (:mod:`app.explorer`) and the law editor (:mod:`app.law_editor`), which both
use them: this is the one place that reaches below Panel's public API.
"""

from __future__ import annotations

import contextlib
import functools
import math
import threading

import panel as pn
import param
from bokeh.core.property.descriptors import UnsetValueError

from .state import TOL_OPTIONS


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


class Syncing:
    """True while the page moves its own widgets, and only in the thread that moves them
    (which holds the state's lock meanwhile: ``with syncing():``).

    Panel handles a session's browser events on its handler threads (``--num-threads 2``), two
    at once.  A single flag, set while one thread synced the sidebar, made the other thread
    drop a genuine event as if it were the sync's own echo: the state walk's third key press on
    the b slider (9.95) was lost, the URL and plot kept the second (9.999999999999998) while
    the slider showed 9.95.  Now the other thread waits for the lock and applies its event."""

    def __init__(self, lock) -> None:
        self._lock = lock
        self._local = threading.local()

    def __bool__(self) -> bool:
        return getattr(self._local, "depth", 0) > 0

    @contextlib.contextmanager
    def __call__(self):
        with self._lock:
            self._local.depth = getattr(self._local, "depth", 0) + 1
            try:
                yield
            finally:
                self._local.depth -= 1


def user_action(method):
    """A handler of a widget event (a method of an object with ``state`` and ``_syncing``):
    run under the state's lock, one handler thread at a time, and ignored when the event is the
    page's own sync of that widget (in this very thread)."""

    @functools.wraps(method)
    def run(self, *args, **kwargs):
        with self.state.lock:
            if self._syncing:
                return None
            return method(self, *args, **kwargs)

    return run


def put(widget, value, **bounds) -> None:
    """Programmatic widget update (its caller's watchers ignore it while the caller syncs) that
    keeps value_throttled in step, so a later drag back to the old value still registers."""
    widget.param.update(**bounds, value=value)
    if "value_throttled" in widget.param:
        with param.edit_constant(widget):
            widget.value_throttled = value


def widened(x: float, lo: float, hi: float) -> dict:
    """Slider start/end: the theoretical range, widened to include x if x lies outside (so the
    slider shows the state's value, never a clipped one)."""
    if not math.isfinite(x):
        return {"start": lo, "end": hi}
    return {"start": min(lo, x), "end": max(hi, x)}


def nearest_tol(tol: float) -> float:
    """The tolerance option closest (in log) to tol (the tolerance selector's value)."""
    t = float(tol) if math.isfinite(tol) and tol > 0 else 1e-10
    return min(TOL_OPTIONS, key=lambda o: abs(math.log10(o / t)))


def document_gone(doc) -> bool:
    """True once Bokeh has destroyed ``doc`` (its browser left and the session expired): a
    worker's answer that arrives later has nobody to show it to, and touching the document's
    models would raise (its callback tables are deleted)."""
    return doc is not None and doc.session_context is None
