"""The process-wide result cache of the dashboard, keyed on the **exact** inputs.

One cache is shared by all scenes and sessions.  Keys are tuples of the exact inputs (``repr``
of each float via :func:`exact`, the law's coefficients, N, tol): a cached result is only ever
returned for the very same inputs (two waves 1e-13 apart on either side of V_SK are two
entries).  Each entry keeps the wall time of its computation, so a cached result still shows
what it cost (:class:`Computed`).
"""

from __future__ import annotations

import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any

__all__ = ["exact", "Computed", "ResultCache", "CACHE"]


def exact(x: float) -> str:
    """Cache-key form of a float: its repr, which round-trips exactly (no rounding)."""
    return repr(float(x))


@dataclass(frozen=True)
class Computed:
    """A value from fpucore with the wall time of its computation (s) and whether it was cached."""

    value: Any
    elapsed_s: float
    cached: bool


class ResultCache:
    """Thread-safe LRU cache with in-flight de-duplication (one computation per key)."""

    def __init__(self, max_items: int = 400):
        self.max_items = max_items
        self._data: OrderedDict[Hashable, tuple[Any, float]] = OrderedDict()
        self._inflight: dict[Hashable, threading.Event] = {}
        self._lock = threading.Lock()
        self.hits = 0
        self.misses = 0

    def get(self, key: Hashable, fn: Callable[[], Any]) -> Computed:
        while True:
            with self._lock:
                if key in self._data:
                    self._data.move_to_end(key)
                    self.hits += 1
                    value, elapsed = self._data[key]
                    return Computed(value, elapsed, True)
                ev = self._inflight.get(key)
                if ev is None:
                    ev = self._inflight[key] = threading.Event()
                    break
            ev.wait(600.0)  # another thread computes this key; then re-check the cache
        try:
            t0 = time.perf_counter()
            value = fn()
            self.put(key, value, time.perf_counter() - t0)
            return Computed(value, time.perf_counter() - t0, False)
        finally:
            with self._lock:
                self._inflight.pop(key, None)
            ev.set()

    def put(self, key: Hashable, value: Any, elapsed: float) -> None:
        with self._lock:
            self.misses += 1
            self._data[key] = (value, elapsed)
            while len(self._data) > self.max_items:
                self._data.popitem(last=False)

    def lookup(self, key: Hashable) -> Computed | None:
        """The cached entry as a Computed (cached=True), or None."""
        with self._lock:
            item = self._data.get(key)
            if item is None:
                return None
            self._data.move_to_end(key)
            self.hits += 1
        return Computed(item[0], item[1], True)

    def peek(self, key: Hashable):
        with self._lock:
            item = self._data.get(key)
        return None if item is None else item[0]

    def clear(self) -> None:
        with self._lock:
            self._data.clear()


CACHE = ResultCache()
