"""The heavy computations the scenes ask for: discrete waves, Floquet spectra and sweeps,
discrete families and simulations, each in a worker process through
:func:`~app.compute.workers.run_job`, cached exactly.

Views call these and the ``*_cached`` questions (would it answer from the cache?) instead of
building keys themselves (:mod:`app.compute.jobs` holds the jobs and their keys).
"""

from __future__ import annotations

from collections.abc import Hashable

from fpucore.errors import ParameterError

from .cache import CACHE, Computed
from .jobs import (
    family_job,
    family_key,
    floquet_job,
    floquet_key,
    simulation_job,
    simulation_key,
    sweep_job,
    sweep_key,
    wave_job,
    wave_key,
)
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
]


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
