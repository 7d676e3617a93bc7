"""The heavy computations the scenes ask for: discrete waves, Floquet spectra and sweeps,
discrete families, simulations and small atlases, each in a worker process through
:func:`~app.compute.workers.run_job`, cached exactly.

Views call these and the ``*_cached`` questions (would it answer from the cache?) instead of
building keys themselves (:mod:`app.compute.jobs` holds the jobs and their keys).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Hashable

from fpucore.errors import ParameterError

from .cache import CACHE, Computed
from .jobs import (
    atlas_job,
    atlas_key,
    family_job,
    family_key,
    floquet_job,
    floquet_key,
    simulation_job,
    simulation_key,
    stage_of,
    sweep_job,
    sweep_key,
    wave_job,
    wave_key,
)
from .requests import AtlasRequest, SimulationRequest, WaveRequest
from .workers import run_job

__all__ = [
    "is_cached",
    "discrete_wave",
    "discrete_wave_cached",
    "floquet_spectrum",
    "floquet_sweep",
    "floquet_sweep_cached",
    "discrete_family",
    "discrete_family_cached",
    "simulation",
    "small_atlas",
    "small_atlas_cached",
]


def is_cached(key: Hashable) -> bool:
    return CACHE.peek(key) is not None


def discrete_wave(lw, mode, w_plus, V, N, tol, stop=None, progress=None) -> Computed:
    """Discrete traveling wave (see :func:`wave_job`) in a worker process, cached exactly."""
    req = WaveRequest(mode, w_plus, V, N, tol)
    return run_job(wave_key(lw, req), wave_job, (lw, req), stop, progress)


def discrete_wave_cached(lw, mode, w_plus, V, N, tol) -> bool:
    """Whether :func:`discrete_wave` would answer from the cache (no solve)."""
    try:
        return is_cached(wave_key(lw, WaveRequest(mode, w_plus, V, N, tol)))
    except ParameterError:
        return False


#: seconds per (2N)³ of the last spectrum computed here (monodromy, check and
#: eigenvalues): the time-left estimate of the next one, whose LAPACK call reports nothing
_SPECTRUM_RATE: list[float] = []
_RATE_LOCK = threading.Lock()


def spectrum_time_estimate(N: int) -> float | None:
    """Seconds a spectrum of a chain of N sites should take here (its eigenvalues: O(N³)), from
    the last one computed (None before the first)."""
    with _RATE_LOCK:
        rate = _SPECTRUM_RATE[-1] if _SPECTRUM_RATE else None
    return None if rate is None else rate * (2.0 * N) ** 3


class SpectrumProgress:
    """The Floquet job's progress for a scene's ``set_progress(done, stage=...)``: the stage and
    its fraction from the worker (:func:`~app.compute.jobs.stage_of`); during the eigenvalues,
    which report nothing until they end, the fraction is the elapsed share of the time the last
    spectrum here predicts for this N (at most 95 %), so the bar moves and gives a time left."""

    def __init__(self, progress: Callable, N: int):
        self.progress, self.N = progress, int(N)
        self.stage, self.t_stage = "", time.perf_counter()

    def __call__(self, x: float) -> None:
        stage, done = stage_of(x)
        now = time.perf_counter()
        if stage != self.stage:
            self.stage, self.t_stage = stage, now
        if stage == "Floquet spectrum" and done < 1.0:
            expected = spectrum_time_estimate(self.N)
            if expected is not None:
                done = max(done, min(0.95, (now - self.t_stage) / max(expected, 1e-3)))
        self.progress(done, stage=stage)


def floquet_spectrum(lw, mode, w_plus, V, N, tol, stop=None, progress=None):
    """(wave Computed, spectrum Computed or None): the wave from the shared cache if there,
    else wave and spectrum in one worker job.  ``progress(done, stage=...)``: its stages
    (:data:`~app.compute.jobs.FLOQUET_STAGES`)."""
    req = WaveRequest(mode, w_plus, V, N, tol)
    wk = wave_key(lw, req)
    rc = CACHE.lookup(wk)
    staged = None if progress is None else SpectrumProgress(progress, req.N)
    c = run_job(floquet_key(lw, req), floquet_job, (lw, req), stop, staged)
    r, fr = c.value
    if fr is not None and not c.cached:  # the job's spectra take one route (the default)
        spent = fr.monodromy_s + fr.check_s + fr.eig_s
        with _RATE_LOCK:
            _SPECTRUM_RATE[:] = [spent / (2.0 * fr.N) ** 3]
    if rc is None:
        CACHE.put(wk, r, r.elapsed_s)
        rc = Computed(r, r.elapsed_s, c.cached)
    spec = None if fr is None else Computed(fr, fr.elapsed_s, c.cached)
    return rc, spec


def floquet_sweep(lw, kind, w_plus, V_values, N, branch="lower", stop=None, progress=None):
    """max |μ| against V for the family (fpucore.atlas.sweep) in a worker process."""
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


def simulation(lw, req: SimulationRequest, stop=None, progress=None) -> Computed:
    """Direct simulation (see :func:`simulation_job`) in a worker process."""
    return run_job(simulation_key(lw, req), simulation_job, (lw, req), stop, progress)


def small_atlas(lw, req: AtlasRequest, stop=None, progress=None) -> Computed:
    """A small atlas with Floquet (see :func:`atlas_job`) in a worker process, cached exactly:
    the same request again is answered from the cache.  ``progress``: the fraction of points
    done."""
    return run_job(atlas_key(lw, req), atlas_job, (lw, req), stop, progress)


def small_atlas_cached(lw, req: AtlasRequest) -> bool:
    return is_cached(atlas_key(lw, req))
