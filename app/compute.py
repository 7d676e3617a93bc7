"""Thin adapter between the dashboard and fpucore: cached, exact, off the server process.

The app computes nothing itself: every number shown comes from fpucore's public API through the
functions below.  They add what the views need:

* a process-wide cache shared by all scenes and sessions, keyed on the **exact** inputs
  (``repr`` of each float, the law's coefficients, N, tol): a cached result is only ever
  returned for the very same inputs (two waves 1e-13 apart on either side of V_SK are two
  entries).  Keys are built here only; views ask ``*_cached(...)`` instead of rebuilding them;
* heavy computations (discrete waves, Floquet spectra, sweeps, discrete families, simulations)
  run in worker processes (the project's execution layer, :mod:`fpucore.parallel`) through
  :func:`run_job`: progress is forwarded, a caller that no longer wants the result (a newer
  slider value, the Cancel button) leaves, and the job is killed once nobody waits for it;
  two sessions asking for the same key share one job;
* wall time of the computation (``Computed.elapsed_s``) and whether it was cached.

The ``*_job`` functions are module-level and take plain parameters (picklable) and return the
fpucore result.  Bad parameters surface as ``fpucore.errors.ParameterError``.
"""

from __future__ import annotations

import functools
import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Hashable
from concurrent.futures import CancelledError
from dataclasses import dataclass
from typing import Any

import numpy as np

from fpucore import floquet as fq
from fpucore import qc, wave
from fpucore import simulate as sim
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw, HardeningSofteningLaw, PolynomialLaw, law_from_expression
from fpucore.parallel import Executor
from fpucore.qc import diagram, phase
from fpucore.warm import warm_all

__all__ = [
    "Computed",
    "ParameterError",
    "CancelledError",
    "Superseded",
    "CACHE",
    "law",
    "make_law",
    "law_key",
    "exact",
    "run_job",
]


def exact(x: float) -> str:
    """Cache-key form of a float: its repr, which round-trips exactly (no rounding)."""
    return repr(float(x))


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


# --------------------------------------------------------------------------- worker processes
class Superseded(Exception):
    """The caller stopped waiting (a newer request, or Cancel): nothing to show."""


_EXECUTOR: Executor | None = None
_EXECUTOR_LOCK = threading.Lock()
_INFLIGHT: dict[Hashable, list] = {}  # key -> [job, number of waiters, submit time]
_INFLIGHT_LOCK = threading.Lock()
#: jobs cancelled because nobody waited for them any more (for tests and the benchmark)
CANCELLED = [0]


def executor() -> Executor:
    """The process-wide pool of worker processes (started on first use)."""
    global _EXECUTOR
    with _EXECUTOR_LOCK:
        if _EXECUTOR is None:
            _EXECUTOR = Executor(backend="process", workers=None)
        return _EXECUTOR


def shutdown_executor() -> None:
    """Stop the worker pool (server shutdown); a later job starts a new one."""
    global _EXECUTOR
    with _EXECUTOR_LOCK:
        ex, _EXECUTOR = _EXECUTOR, None
    if ex is not None:
        ex.shutdown()


def jobs_in_flight() -> int:
    """Heavy jobs running or queued (for tests and the benchmark)."""
    with _INFLIGHT_LOCK:
        return len(_INFLIGHT)


def run_job(
    key: Hashable,
    fn: Callable,
    args: tuple,
    stop: Callable[[], bool] | None = None,
    progress: Callable[[float], None] | None = None,
    poll_s: float = 0.05,
) -> Computed:
    """``fn(*args)`` in a worker process, through the cache.

    Waits polling ``stop()`` every ``poll_s``: when it returns True the caller leaves
    (:class:`Superseded`) and, if no other caller waits for the same key, the job is
    cancelled (its worker killed).  ``progress(x)`` gets the job's progress in [0, 1].
    Exceptions of ``fn`` (ParameterError ...) are re-raised here.
    """
    hit = CACHE.lookup(key)
    if hit is not None:
        return hit
    with _INFLIGHT_LOCK:
        entry = _INFLIGHT.get(key)
        if entry is None or (entry[0].done() and entry[1] == 0):
            entry = _INFLIGHT[key] = [executor().submit(fn, *args), 0, time.perf_counter()]
        entry[1] += 1
    job = entry[0]
    try:
        while True:
            try:
                value = job.result(timeout=poll_s)
                break
            except TimeoutError:
                if stop is not None and stop():
                    raise Superseded() from None
                if progress is not None and job.progress is not None:
                    progress(job.progress)
    finally:
        with _INFLIGHT_LOCK:
            entry[1] -= 1
            orphan = entry[1] <= 0 and not job.done()
            if (entry[1] <= 0 or job.done()) and _INFLIGHT.get(key) is entry:
                del _INFLIGHT[key]
        if orphan and job.cancel():
            CANCELLED[0] += 1
    elapsed = time.perf_counter() - entry[2]
    CACHE.put(key, value, elapsed)
    return Computed(value, elapsed, False)


# --------------------------------------------------------------------------- QC (cheap)
def law(a: float, b: float) -> CubicLaw:
    """The cubic law f(w) = a w³ + b w² + w (raises ParameterError for a ≥ 0, b ≤ 0, or
    coefficients so large that its closed forms overflow)."""
    try:
        lw = CubicLaw(a=float(a), b=float(b))
        # the closed forms the scenes use first (α, β, w*, c_max) must be finite doubles
        if not all(np.isfinite([lw.alpha, lw.beta, lw.w_star, float(lw.f(lw.beta))])):
            raise OverflowError
        return lw
    except OverflowError:
        raise ParameterError(
            "b", float(b), "|b| small enough for double precision (e.g. b <= 1e100)", "overflow"
        ) from None


@functools.lru_cache(maxsize=64)
def _parsed(expression: str) -> tuple[PolynomialLaw | None, ParameterError | None]:
    try:
        return law_from_expression(expression), None
    except ParameterError as exc:
        return None, exc


def expression_law(expression: str) -> PolynomialLaw:
    """fpucore.law_from_expression, memoised (laws are immutable; the state asks for its law on
    every change and SymPy's parse costs milliseconds).  Raises its ParameterError."""
    lw, exc = _parsed(expression)
    if exc is not None:  # a fresh exception: re-raising the cached one would grow its traceback
        raise ParameterError(exc.name, exc.value, exc.valid, exc.reason)
    return lw


def make_law(a: float, b: float, expression: str = "") -> HardeningSofteningLaw:
    """The explorer's law: the cubic (a, b) when ``expression`` is empty, else the polynomial
    law of the expression (fpucore.law_from_expression).  Raises ParameterError."""
    if expression:
        return expression_law(expression)
    return law(a, b)


def law_key(lw: HardeningSofteningLaw) -> tuple:
    """Exact cache-key form of a law: its kind and coefficients (repr).  The cubic and the same
    cubic as a PolynomialLaw are different keys: different routes (closed forms vs numerical)."""
    if isinstance(lw, CubicLaw):
        return ("cubic", exact(lw.a), exact(lw.b))
    if isinstance(lw, PolynomialLaw):
        return ("poly", *(exact(c) for c in lw.coeffs))
    raise ParameterError("law", lw, "a CubicLaw or PolynomialLaw")


def qc_wave(lw, mode: str, w_plus: float, V: float) -> Computed:
    """QC superkink (mode "superkink": from w_plus) or solitary wave (mode "solitary")."""
    if mode == "superkink":
        return CACHE.get(
            ("qc_sk", law_key(lw), exact(w_plus)),
            lambda: qc.superkink_from_w_plus(lw, w_plus),
        )
    return CACHE.get(
        ("qc_sw", law_key(lw), exact(w_plus), exact(V)),
        lambda: qc.solitary(lw, w_plus, V),
    )


def qc_family(lw, w_plus: float, n: int = 160) -> Computed:
    """fpucore.qc.diagram.solitary_family: amplitude (eq. SWQC_amp) and E_ren (eq. Eren_QC)
    of the QC solitary waves along both velocity intervals for fixed w_plus."""
    return CACHE.get(
        ("qc_family", law_key(lw), exact(w_plus), n),
        lambda: diagram.solitary_family(lw, w_plus, n=n),
    )


def phase_plane(lw, w_plus: float, V: float, n_grid: int = 241) -> Computed:
    """fpucore.qc.phase.phase_plane for the current parameters."""
    return CACHE.get(
        ("phase", law_key(lw), exact(w_plus), exact(V), n_grid),
        lambda: phase.phase_plane(lw, w_plus, V, n_grid=n_grid),
    )


def existence_diagram(lw, n: int = 400) -> Computed:
    """fpucore.qc.diagram.existence_diagram: arrays w_plus, c_plus, V_SK, c_minus."""
    return CACHE.get(("diagram", law_key(lw), n), lambda: diagram.existence_diagram(lw, n=n))


# --------------------------------------------------------------------------- jobs (workers)
def wave_call(lw, mode: str, w_plus: float, V: float, N: int, tol: float):
    """(fpucore function name, positional args, keyword args) of a discrete wave — the exact
    call, used by the job, the cache key and "copy as Python".  Raises ParameterError."""
    if mode == "superkink":
        sk = qc.superkink_from_w_plus(lw, w_plus)  # validates w_plus, gives V_SK and branch
        return "solve_superkink", (lw, sk.V), {"branch": sk.branch, "N": int(N), "tol": tol}
    return "solve_solitary", (lw, float(w_plus), float(V)), {"N": int(N), "tol": float(tol)}


def wave_job(lw, mode: str, w_plus: float, V: float, N: int, tol: float):
    """Discrete traveling wave (fixed point of eq. nonlin_map): fpucore.wave.solve_superkink
    (branch of w_plus) or fpucore.wave.solve_solitary.  Returns the WaveResult."""
    name, args, kwargs = wave_call(lw, mode, w_plus, V, N, tol)
    return getattr(wave, name)(*args, **kwargs)


def floquet_job(lw, mode: str, w_plus: float, V: float, N: int, tol: float):
    """(WaveResult, FloquetResult or None if the wave did not converge)."""
    r = wave_job(lw, mode, w_plus, V, N, tol)
    return r, (fq.spectrum(r) if r.converged else None)


def fraction(progress):
    """fpucore's family callbacks ``progress(i, n, ...)`` → the execution layer's
    ``progress(fraction)``."""
    if progress is None:
        return None
    return lambda i, n, *rest: progress(i / max(n, 1))


def sweep_job(lw, kind, w_plus, V_values, N, branch, progress=None):
    """max |μ| against V for a family (fpucore.floquet.sweep), run inline in this worker: a pool
    worker is daemonic and may not start a pool of its own (the server's pool already spreads
    the sessions' jobs over the cores)."""
    return fq.sweep(
        lw,
        kind=kind,
        V_values=np.asarray(V_values, float),
        w_plus=w_plus,
        N=int(N),
        branch=branch,
        progress=fraction(progress),
        executor=Executor(backend="inline"),
    )


def family_job(lw, w_plus, V_values, N, tol, progress=None):
    """Discrete solitary waves at the given velocities (fpucore.wave.solitary_family, each solve
    continued from its neighbour); the list of WaveResults."""
    fam = wave.solitary_family(
        lw, w_plus, np.asarray(V_values, float), N=N, tol=tol, progress=fraction(progress)
    )
    return list(fam.results)


def simulation_job(kind: str, lw, params: dict, progress=None):
    """Direct simulation via fpucore.simulate: kind "riemann" | "gaussian" | "seeded" (for
    "seeded", ``params`` also holds mode/w_plus/V/N/tol of the seeding wave)."""
    p = dict(params)
    extra = {} if progress is None else {"progress": progress}
    if kind == "riemann":
        return sim.riemann(lw, p.pop("w_left"), p.pop("w_right"), **p, **extra)
    if kind == "gaussian":
        return sim.gaussian(lw, p.pop("w_B"), p.pop("A"), **p, **extra)
    if kind == "seeded":
        wave_args = [p.pop(k) for k in ("mode", "w_plus", "V", "N", "tol")]
        r = wave_job(lw, *wave_args)
        if not r.converged:
            raise ParameterError(
                "N", wave_args[3], "a converged seeding wave", f"did not converge: {r.message}"
            )
        return sim.seeded(r, **p, **extra)
    raise ParameterError("kind", kind, "'riemann', 'gaussian' or 'seeded'")


# --------------------------------------------------------------------------- keys + front ends
def wave_key(lw, mode, w_plus, V, N, tol) -> tuple:
    """Exact key of a discrete wave: the solver's own inputs (raises ParameterError)."""
    name, args, kwargs = wave_call(lw, mode, w_plus, V, N, tol)
    return ("wave", name, law_key(lw), *(exact(x) for x in args[1:]), repr(kwargs))


def floquet_key(lw, mode, w_plus, V, N, tol) -> tuple:
    return ("floquet",) + wave_key(lw, mode, w_plus, V, N, tol)


def sweep_key(lw, kind, w_plus, V_values, N, branch) -> tuple:
    wp = None if w_plus is None else exact(w_plus)
    Vs = tuple(exact(v) for v in V_values)
    return ("fsweep", law_key(lw), kind, wp, Vs, int(N), branch)


def family_key(lw, w_plus, V_values, N, tol) -> tuple:
    Vs = tuple(exact(v) for v in V_values)
    return ("dfamily", law_key(lw), exact(w_plus), Vs, int(N), exact(tol))


def simulation_key(kind: str, lw, params: dict) -> tuple:
    items = tuple(sorted((k, repr(v)) for k, v in params.items()))
    return ("sim", kind, law_key(lw), items)


def is_cached(key: Hashable) -> bool:
    return CACHE.peek(key) is not None


def discrete_wave(lw, mode, w_plus, V, N, tol, stop=None, progress=None) -> Computed:
    """Discrete traveling wave (see :func:`wave_job`) in a worker process, cached exactly."""
    key = wave_key(lw, mode, w_plus, V, N, tol)
    return run_job(key, wave_job, (lw, mode, w_plus, V, N, tol), stop, progress)


def discrete_wave_cached(lw, mode, w_plus, V, N, tol) -> bool:
    """Whether :func:`discrete_wave` would answer from the cache (no solve)."""
    try:
        return is_cached(wave_key(lw, mode, w_plus, V, N, tol))
    except ParameterError:
        return False


def floquet_spectrum(lw, mode, w_plus, V, N, tol, stop=None, progress=None):
    """(wave Computed, spectrum Computed or None): the wave from the shared cache if there,
    else wave and spectrum in one worker job."""
    wk = wave_key(lw, mode, w_plus, V, N, tol)
    rc = CACHE.lookup(wk)
    args = (lw, mode, w_plus, V, N, tol)
    c = run_job(floquet_key(*args), floquet_job, args, stop, progress)
    r, fr = c.value
    if rc is None:
        CACHE.put(wk, r, r.elapsed_s)
        rc = Computed(r, r.elapsed_s, c.cached)
    spec = None if fr is None else Computed(fr, fr.elapsed_s, c.cached)
    return rc, spec


def floquet_sweep(lw, kind, w_plus, V_values, N, branch="lower", stop=None, progress=None):
    """max |μ| against V for the family (fpucore.floquet.sweep) in a worker process."""
    Vs = [float(v) for v in V_values]
    key = sweep_key(lw, kind, w_plus, Vs, N, branch)
    return run_job(key, sweep_job, (lw, kind, w_plus, Vs, int(N), branch), stop, progress)


def floquet_sweep_cached(lw, kind, w_plus, V_values, N, branch="lower") -> bool:
    return is_cached(sweep_key(lw, kind, w_plus, V_values, N, branch))


def discrete_family(lw, w_plus, V_values, N, tol, stop=None, progress=None) -> Computed:
    """Discrete solitary waves at the given velocities (amplitude/energy dots of Figs.
    SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC) in a worker process."""
    Vs = [float(v) for v in V_values]
    key = family_key(lw, w_plus, Vs, N, tol)
    return run_job(key, family_job, (lw, w_plus, Vs, N, tol), stop, progress)


def discrete_family_cached(lw, w_plus, V_values, N, tol) -> bool:
    return is_cached(family_key(lw, w_plus, V_values, N, tol))


def simulation(kind: str, lw, params: dict, stop=None, progress=None):
    """Direct simulation (see :func:`simulation_job`) in a worker process."""
    key = simulation_key(kind, lw, params)
    return run_job(key, simulation_job, (kind, lw, dict(params)), stop, progress)


def warm_job() -> float:
    """Load (or compile) every Numba kernel in a worker process; seconds spent."""
    t0 = time.perf_counter()
    # a worker warms itself (no processes of its own), the essential routes only: the lazy ones
    # are compiled by the server's background `fpu warm` and loaded from the cache when used
    warm_all(parallel=False, lazy=False)
    return time.perf_counter() - t0


def warm_workers() -> None:
    """Start every worker process and warm its JIT (one warm_job per worker, concurrently)."""
    ex = executor()
    for job in [ex.submit(warm_job) for _ in range(ex.workers)]:
        try:
            job.result(timeout=600)
        except Exception:  # noqa: BLE001 - warm-up must never keep the server from starting
            pass


def spec_of(lw, mode, w_plus, V):
    """fpucore.wave's description (Spec) of the wave the parameters define."""
    if mode == "superkink":
        sk = qc.superkink_from_w_plus(lw, w_plus)
        return lw, wave.superkink_spec(lw, sk.V, sk.branch)
    return lw, wave.solitary_spec(lw, w_plus, V)


def n_needed(lw, mode, w_plus, V, tol: float) -> int:
    """The chain size fpucore would choose itself for this wave (``N=None``: tails resolved to
    0.1·tol·scale, eq. fixedBCs), at least the smallest N it accepts (tails cut at 1e-6 of the
    amplitude).  Closed-form QC tails only: cheap."""
    lw, spec = spec_of(lw, mode, w_plus, V)
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    n_auto = wave.required_N(lw, spec, 0.1 * tol * scale)
    n_fit = wave.required_N(lw, spec, 1e-6 * spec.amplitude_qc)
    return int(max(n_auto, n_fit))


# --------------------------------------------------------------------------- energy criterion
#: QC samples per velocity interval for the energy criterion (extrema are bracketed on this
#: grid, then refined): closed forms (cubic) evaluate the whole grid at once (~1 ms; ~8 ms with
#: an extremum to refine); other laws solve the §3 theory point by point (~15 ms each)
ENERGY_QC_SAMPLES = {True: fq.energy.QC_SAMPLES, False: 60}


def energy_qc_samples(lw) -> int:
    """QC samples per interval of the energy criterion's grid: closed forms (the cubic) are
    cheap, a general law's quadrature is not."""
    return ENERGY_QC_SAMPLES[bool(qc.is_closed_form(lw))]


def energy_extrema_qc(lw, w_plus: float) -> Computed:
    """Extrema of E_ren^QC(V) (eq. Eren_QC) along the solitary family of w_plus, each with its
    error bar on V (fpucore.floquet.energy_criterion without discrete waves: QC closed forms on
    a grid, refined by a bounded minimisation; 1–10 ms for the cubic).  Cheap: in process."""
    n = energy_qc_samples(lw)
    return CACHE.get(
        ("energy_qc", law_key(lw), exact(w_plus), n),
        lambda: fq.energy_criterion(lw, w_plus, qc_samples=n),
    )


def sampled_energy_extrema(key: tuple, lw, w_plus: float, V, E, dE, ok):
    """Extrema of the discrete E_ren (eq. Eren_D) from waves already computed (the dots of the
    diagram, the waves of a Floquet sweep): fpucore.floquet.criterion_from_samples without the
    QC part (parabola fits only: cheap).  ``key`` is the cache key of the computation that gave
    the samples (so equal keys mean equal samples; they include the law)."""
    return CACHE.get(
        ("energy_samples", key),
        lambda: fq.criterion_from_samples(lw, w_plus, V, E, dE, ok, qc_samples=0),
    )


def family_energy_extrema(lw, w_plus, V_values, N, tol) -> Computed:
    """The discrete E_ren's extrema along a discrete family that is already cached (the
    diagram's dots): see :func:`sampled_energy_extrema`.  None if the family is not cached."""
    Vs = [float(v) for v in V_values]
    key = family_key(lw, w_plus, Vs, N, tol)
    rows = CACHE.peek(key)
    if rows is None:
        return None
    rows = [r for r in rows if hasattr(r, "energy")]
    V = [r.V for r in rows]
    E = [r.energy for r in rows]
    dE = [fq.energy.wave_energy_error(r) for r in rows]
    ok = [bool(r.converged) for r in rows]
    return sampled_energy_extrema(key, lw, w_plus, V, E, dE, ok)


def sweep_energy_check(lw, w_plus, V_values, N) -> Computed | None:
    """The energy criterion on a cached solitary Floquet sweep (its rows carry each wave's
    E_ren, energy_error and classification): (EnergyCriterion with the discrete extrema from the
    sweep's waves and the QC extrema, list of fpucore.floquet.StabilityChange — the cross-check
    of the classifications against the extrema).  Parabola fits plus the QC grid (1–10 ms for
    the cubic); None if the sweep is not cached."""
    Vs = [float(v) for v in V_values]
    key = sweep_key(lw, "solitary", w_plus, Vs, N, "lower")
    sw = CACHE.peek(key)
    if sw is None:
        return None
    n = energy_qc_samples(lw)

    def check():
        ok = np.asarray(sw.converged, bool)
        ec = fq.criterion_from_samples(lw, w_plus, sw.V, sw.energy, sw.energy_error, ok, n)
        return ec, fq.stability_changes(lw, w_plus, sw.V, sw.classification, ec)

    return CACHE.get(("energy_sweep", key, n), check)
