"""Thin adapter between the dashboard and fpucore: cached, thread-safe, timed.

The app computes nothing itself: every number shown comes from fpucore's public API through the
functions below.  They add three things the views need:

* a process-wide cache keyed by *rounded* parameters (12 significant digits), shared by all
  scenes and all browser sessions, with in-flight de-duplication (two sessions asking for the
  same discrete wave wait for one solve instead of running two);
* wall time of the underlying computation (``Computed.elapsed_s``) and whether it was cached;

Bad parameters surface as ``fpucore.errors.ParameterError`` exactly as fpucore raises them.
"""

from __future__ import annotations

import math
import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any

import numpy as np

from fpucore import floquet as fq
from fpucore import qc, wave
from fpucore import simulate as sim
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.qc import diagram, phase

__all__ = ["Computed", "ParameterError", "CACHE", "law"]


def rnd(x: float, digits: int = 12) -> float:
    """Round to ``digits`` significant digits: the cache key of a float parameter."""
    x = float(x)
    if not math.isfinite(x) or x == 0.0:
        return x
    return float(f"{x:.{digits}g}")


# --------------------------------------------------------------------------- cache
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
            elapsed = time.perf_counter() - t0
            with self._lock:
                self.misses += 1
                self._data[key] = (value, elapsed)
                while len(self._data) > self.max_items:
                    self._data.popitem(last=False)
            return Computed(value, elapsed, False)
        finally:
            with self._lock:
                self._inflight.pop(key, None)
            ev.set()

    def peek(self, key: Hashable):
        with self._lock:
            item = self._data.get(key)
        return None if item is None else item[0]

    def items_like(self, prefix: tuple) -> list[tuple[Hashable, Any]]:
        """Cached (key, value) pairs whose key starts with ``prefix`` (for continuation)."""
        with self._lock:
            return [(k, v[0]) for k, v in self._data.items() if k[: len(prefix)] == prefix]

    def clear(self) -> None:
        with self._lock:
            self._data.clear()


CACHE = ResultCache()


# --------------------------------------------------------------------------- QC (cheap)
def law(a: float, b: float) -> CubicLaw:
    """The cubic law f(w) = a w³ + b w² + w (raises ParameterError for a ≥ 0 or b ≤ 0)."""
    return CubicLaw(a=float(a), b=float(b))


def qc_wave(a: float, b: float, mode: str, w_plus: float, V: float) -> Computed:
    """QC superkink (mode "superkink": from w_plus) or solitary wave (mode "solitary")."""
    lw = law(a, b)
    if mode == "superkink":
        return CACHE.get(
            ("qc_sk", rnd(a), rnd(b), rnd(w_plus)), lambda: qc.superkink_from_w_plus(lw, w_plus)
        )
    return CACHE.get(
        ("qc_sw", rnd(a), rnd(b), rnd(w_plus), rnd(V)), lambda: qc.solitary(lw, w_plus, V)
    )


def qc_family(a: float, b: float, w_plus: float, n: int = 160) -> Computed:
    """fpucore.qc.diagram.solitary_family: amplitude (eq. SWQC_amp) and E_ren (eq. Eren_QC)
    of the QC solitary waves along both velocity intervals for fixed w_plus."""
    fn = diagram.solitary_family
    lw = law(a, b)
    return CACHE.get(("qc_family", rnd(a), rnd(b), rnd(w_plus), n), lambda: fn(lw, w_plus, n=n))


def phase_plane(a: float, b: float, w_plus: float, V: float, n_grid: int = 241) -> Computed:
    """fpucore.qc.phase.phase_plane for the current parameters."""
    fn = phase.phase_plane
    lw = law(a, b)
    return CACHE.get(
        ("phase", rnd(a), rnd(b), rnd(w_plus), rnd(V), n_grid),
        lambda: fn(lw, w_plus, V, n_grid=n_grid),
    )


def existence_diagram(a: float, b: float, n: int = 400) -> Computed:
    """fpucore.qc.diagram.existence_diagram: arrays w_plus, c_plus, V_SK, c_minus."""
    fn = diagram.existence_diagram
    lw = law(a, b)
    return CACHE.get(("diagram", rnd(a), rnd(b), n), lambda: fn(lw, n=n))


# --------------------------------------------------------------------------- discrete (costly)
def _discrete_call(a: float, b: float, mode: str, w_plus: float, V: float, N, tol: float):
    """(cache key, solver, args, kwargs) of a discrete wave (raises ParameterError)."""
    lw = law(a, b)
    N = None if N is None else int(N)
    if mode == "superkink":
        sk = qc.superkink_from_w_plus(lw, w_plus)  # validates w_plus, gives V_SK and branch
        key = ("wave_sk", rnd(a), rnd(b), sk.branch, N, rnd(tol, 3), rnd(sk.V))
        return key, wave.solve_superkink, (lw, sk.V), dict(branch=sk.branch, N=N, tol=tol)
    key = ("wave_sw", rnd(a), rnd(b), rnd(w_plus), N, rnd(tol, 3), rnd(V))
    return key, wave.solve_solitary, (lw, w_plus, V), dict(N=N, tol=tol)


def discrete_wave(
    a: float, b: float, mode: str, w_plus: float, V: float, N: int | None, tol: float
) -> Computed:
    """Discrete traveling wave (fixed point of eq. nonlin_map) via fpucore.wave.

    Superkink: ``wave.solve_superkink(law, V, branch)`` with the branch of w_plus; solitary:
    ``wave.solve_solitary(law, w_plus, V)``.  Families (sweeps) use fpucore.wave.continuation,
    which seeds each solve from its neighbour.
    """
    key, solve, args, kwargs = _discrete_call(a, b, mode, w_plus, V, N, tol)
    return CACHE.get(key, lambda: solve(*args, **kwargs))


def discrete_wave_cached(
    a: float, b: float, mode: str, w_plus: float, V: float, N: int | None, tol: float
) -> bool:
    """Whether :func:`discrete_wave` would answer from the cache (no solve)."""
    try:
        key = _discrete_call(a, b, mode, w_plus, V, N, tol)[0]
    except ParameterError:
        return False
    return CACHE.peek(key) is not None


def floquet_spectrum(
    a: float, b: float, mode: str, w_plus: float, V: float, N: int | None, tol: float
) -> tuple[Computed, Computed]:
    """(discrete wave, Floquet spectrum of it) — the wave comes from the shared cache."""
    r = discrete_wave(a, b, mode, w_plus, V, N, tol)
    key = ("floquet", rnd(a), rnd(b), mode, rnd(w_plus), rnd(V), N, rnd(tol, 3))
    return r, CACHE.get(key, lambda: fq.spectrum(r.value))


def floquet_sweep(
    a: float,
    b: float,
    kind: str,
    w_plus: float | None,
    V_values,
    N: int,
    branch: str = "lower",
    progress=None,
) -> Computed:
    """max |μ| against V for the family (fpucore.floquet.sweep; progress(i, n, ...))."""
    lw = law(a, b)
    Vs = tuple(rnd(v) for v in V_values)
    wp = None if w_plus is None else rnd(w_plus)
    return CACHE.get(
        ("fsweep", rnd(a), rnd(b), kind, wp, Vs, int(N), branch),
        lambda: fq.sweep(
            lw,
            kind=kind,
            V_values=np.array(Vs),
            w_plus=w_plus,
            N=int(N),
            branch=branch,
            progress=progress,
        ),
    )


def discrete_family(
    a: float, b: float, w_plus: float, V_values, N: int | None, tol: float, progress=None
) -> Computed:
    """Discrete solitary waves at the given velocities (amplitude/energy dots of Figs.
    SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC) via fpucore.wave.family.solitary_family, which
    continues each solve from its neighbour.  Returns the list of wave results."""
    lw = law(a, b)
    Vs = tuple(rnd(v) for v in V_values)

    def run():
        cb = None if progress is None else (lambda i, n, *rest: progress(i, n))
        fam = wave.solitary_family(lw, w_plus, np.array(Vs), N=N, tol=tol, progress=cb)
        return list(fam.results)

    return CACHE.get(("dfamily", rnd(a), rnd(b), rnd(w_plus), Vs, N, rnd(tol, 3)), run)


# --------------------------------------------------------------------------- simulation
def simulation(kind: str, a: float, b: float, params: dict, progress=None) -> Computed:
    """Direct simulation via fpucore.simulate: kind "riemann" | "gaussian" | "seeded".

    ``params`` holds the keyword arguments of the fpucore function (for "seeded" also
    mode/w_plus/V/N/tol of the seeding wave, which comes from the shared cache).
    """
    lw = law(a, b)
    p = dict(params)
    key = ("sim", kind, rnd(a), rnd(b), tuple(sorted((k, str(v)) for k, v in p.items())))
    extra = {} if progress is None else {"progress": progress}

    def call(fn, *args, **kw):
        return fn(*args, **kw, **extra)

    if kind == "riemann":
        fn = sim.riemann
        return CACHE.get(key, lambda: call(fn, lw, p.pop("w_left"), p.pop("w_right"), **p))
    if kind == "gaussian":
        fn = sim.gaussian
        return CACHE.get(key, lambda: call(fn, lw, p.pop("w_B"), p.pop("A"), **p))
    if kind == "seeded":
        fn = sim.seeded
        wave_args = [p.pop(k) for k in ("mode", "w_plus", "V", "N", "tol")]

        def run():
            r = discrete_wave(a, b, *wave_args).value
            if not getattr(r, "converged", True):
                raise ParameterError(
                    "V",
                    wave_args[2],
                    "a converged traveling wave",
                    f"the seeding wave did not converge: {r.message}",
                )
            return call(fn, r, **p)

        return CACHE.get(key, run)
    raise ParameterError("kind", kind, "'riemann', 'gaussian' or 'seeded'")
