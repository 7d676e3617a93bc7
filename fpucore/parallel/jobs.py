"""A submitted job as the caller sees it (:class:`Job`), and the exceptions of the layer.

A Job is filled exactly once by its backend (value or exception); ``progress`` holds the latest
fraction the function reported.  Backends give the Job a ``cancel_hook`` that does the
backend-specific part of a cancel (drop from a queue, terminate a worker).
"""

from __future__ import annotations

import inspect
import threading
from collections.abc import Callable
from concurrent.futures import CancelledError
from typing import Any


class Cancelled(CancelledError):
    """The job was cancelled (``Job.cancel()`` or ``Executor.shutdown()``) before it finished."""


class WorkerDied(RuntimeError):
    """The process running the job ended without returning (killed, out of memory, crashed)."""


class RemoteError(RuntimeError):
    """A worker's exception that could not be sent back as itself (not picklable); its message
    holds the original class name, message and the worker's traceback."""


def accepts_progress(fn: Callable) -> bool:
    """True if ``fn`` has a parameter named ``progress`` (the layer then passes a callable)."""
    try:
        return "progress" in inspect.signature(fn).parameters
    except (TypeError, ValueError, OverflowError):
        return False


class Job:
    """Handle of one submitted call.  ``result(timeout)`` returns the value or re-raises the
    worker's exception; ``cancel()`` drops a queued job or stops a running one; ``progress`` is
    the latest fraction in [0, 1] reported by the function, or None."""

    def __init__(self, index: int = 0):
        self.index = index
        self.progress: float | None = None
        self.state = "pending"  # pending | running | done | failed | cancelled
        self.worker: Any = None  # backend's name of the worker running it (pid or address)
        self.cancel_hook: Callable[[Job], None] | None = None
        self._event = threading.Event()
        self._lock = threading.Lock()
        self._value: Any = None
        self._exc: BaseException | None = None
        self._callbacks: list[Callable[[Job], None]] = []

    # -- filled by the backend ------------------------------------------------------------------
    def set_result(self, value: Any) -> bool:
        return self._finish("done", value, None)

    def set_exception(self, exc: BaseException) -> bool:
        return self._finish("cancelled" if isinstance(exc, Cancelled) else "failed", None, exc)

    def set_progress(self, frac: float) -> None:
        if not self._event.is_set():
            self.progress = min(1.0, max(0.0, float(frac)))

    def _finish(self, state: str, value: Any, exc: BaseException | None) -> bool:
        with self._lock:
            if self._event.is_set():
                return False  # first outcome wins (a late result after a cancel is dropped)
            self.state, self._value, self._exc = state, value, exc
            if state == "done":
                self.progress = 1.0
            self._event.set()
            callbacks, self._callbacks = self._callbacks, []
        for cb in callbacks:
            cb(self)
        return True

    # -- the caller's side ----------------------------------------------------------------------
    def done(self) -> bool:
        """True once the job has a value, an exception or was cancelled."""
        return self._event.is_set()

    def result(self, timeout: float | None = None) -> Any:
        """The function's value; re-raises its exception (class kept), Cancelled, WorkerDied.
        Raises TimeoutError if not done within ``timeout`` seconds."""
        if not self._event.wait(timeout):
            raise TimeoutError(f"job {self.index} not done within {timeout} s")
        if self._exc is not None:
            raise self._exc
        return self._value

    def exception(self, timeout: float | None = None) -> BaseException | None:
        """The job's exception (None if it returned a value)."""
        if not self._event.wait(timeout):
            raise TimeoutError(f"job {self.index} not done within {timeout} s")
        return self._exc

    def cancel(self) -> bool:
        """Cancel: a queued job is dropped; a running one has its worker process terminated (and
        replaced).  Returns False if the job had already finished.  ``result()`` then raises
        :class:`Cancelled`."""
        if self.done():
            return False
        won = self.set_exception(Cancelled(f"job {self.index} cancelled"))
        if won and self.cancel_hook is not None:
            self.cancel_hook(self)
        return won

    def add_done_callback(self, cb: Callable[[Job], None]) -> None:
        """Call ``cb(job)`` when the job finishes (at once if it already has)."""
        with self._lock:
            if not self._event.is_set():
                self._callbacks.append(cb)
                return
        cb(self)

    def __repr__(self) -> str:
        return f"Job({self.index}, {self.state}, progress={self.progress})"
