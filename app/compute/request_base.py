"""What every request of :mod:`app.compute.requests` is: a frozen dataclass with an exact key
(:class:`Request`), whose job runs an fpucore function with its arguments (:class:`Call`, also
the "Copy as Python" text of that call)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any, ClassVar

from .cache import exact

__all__ = ["Call", "Request", "LocalRequest", "key_of", "fraction"]


def key_of(value) -> Any:
    """Exact key form of a request's value: floats by repr, nested requests by their key."""
    if isinstance(value, float):
        return exact(value)
    if isinstance(value, tuple):
        return tuple(key_of(v) for v in value)
    if hasattr(value, "key"):
        return value.key()
    return value


def fraction(progress):
    """fpucore's family callbacks ``progress(i, n, ...)`` → the execution layer's
    ``progress(fraction)``."""
    if progress is None:
        return None
    return lambda i, n, *rest: progress(i / max(n, 1))


class Request:
    """What every request has: its exact key (the class name and each field's exact value),
    the key of its result under a law, and the job a worker runs."""

    #: where :func:`app.compute.run` computes the job: in a worker process (False) or, for a
    #: cheap one (closed forms, quadratures, fits: milliseconds), in this process (True)
    local: ClassVar[bool] = False

    def key(self) -> tuple:
        items = ((f.name, key_of(getattr(self, f.name))) for f in fields(self))
        return (type(self).__name__, *items)

    def job_key(self, lw) -> tuple:
        """The exact key of the job's result under the law ``lw`` (without the law's own key,
        which app.compute adds)."""
        return self.key()

    def job(self, lw, progress=None):  # pragma: no cover - abstract
        """The computation (run in a worker process); ``progress(fraction)`` if given."""
        raise NotImplementedError

    def _set(self, name: str, value) -> None:  # a frozen dataclass normalises its own fields
        object.__setattr__(self, name, value)


class LocalRequest(Request):
    """A cheap request computed in the server process (no worker round trip), cached exactly
    like a worker's: its job is its fpucore call on the law.  A request that reads another
    request's cached result (a field ``source``) is computed from that value
    (:meth:`from_source`) and never recomputes it: no value while the source is not cached."""

    local = True

    def call(self) -> Call:  # pragma: no cover - abstract
        raise NotImplementedError

    def job(self, lw, progress=None):
        return self.call().run(lw)

    def from_source(self, lw, value):  # pragma: no cover - only requests with a source
        """The result computed from the source request's cached ``value``."""
        raise NotImplementedError


@dataclass(frozen=True)
class Call:
    """``fn(first, *args, **kwargs)``: an fpucore function and its arguments after the first
    (the law, or a wave for a seeded simulation).  ``module`` is the name the code shown to the
    user imports it under (``from fpucore import wave``)."""

    module: str
    fn: Callable
    args: tuple = ()
    kwargs: tuple = ()  # (name, value) pairs in call order (a dict is not hashable)

    @property
    def name(self) -> str:
        return self.fn.__name__

    def run(self, first, **extra):
        return self.fn(first, *self.args, **dict(self.kwargs), **extra)

    def key(self) -> tuple:
        return (self.module, self.name, key_of(self.args), key_of(self.kwargs))

    def code(self, first: str = "law") -> str:
        """The call as Python (every float by repr, so it runs on the very same inputs)."""
        parts = [first, *(repr(x) for x in self.args)]
        parts += [f"{k}={v!r}" for k, v in self.kwargs]
        return f"{self.module}.{self.name}({', '.join(parts)})"
