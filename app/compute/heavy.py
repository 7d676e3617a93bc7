"""The one road from a scene to a worker: :func:`run` takes the law and a typed request
(:mod:`app.compute.requests`) and runs the request's job in a worker process through
:func:`~app.compute.workers.run_job`, cached exactly on :func:`job_key`; :func:`is_cached` says
whether it would answer from the cache.  The Floquet spectrum of a wave request
(:func:`floquet_spectrum`) is the one job that fills two cache entries (the wave's and the
spectrum's), with a time-left estimate for its silent eigenvalue call.

Views never build keys themselves: a request's key is the request.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Hashable

from fpucore.errors import ParameterError

from .cache import CACHE, Computed
from .jobs import floquet_job, stage_of
from .laws import law_key
from .requests import Request, WaveRequest
from .workers import run_job

__all__ = ["run", "is_cached", "job_key", "spectrum_key", "floquet_spectrum"]


def job_key(lw, req: Request) -> Hashable:
    """The exact cache key of ``req``'s result under the law ``lw``: the law's exact key and
    the request's (its solver's inputs).  Raises ParameterError (e.g. a superkink's w₊ outside
    its range)."""
    return (law_key(lw), req.job_key(lw))


def spectrum_key(lw, req: WaveRequest) -> Hashable:
    """The exact cache key of the Floquet spectrum of the wave ``req``."""
    return ("floquet", job_key(lw, req))


def run(lw, req: Request, stop=None, progress=None) -> Computed:
    """``req``'s job under the law ``lw`` in a worker process, cached exactly: the same request
    again (from any session) is answered from the cache, two sessions asking at once share one
    job.  ``stop()``: the caller no longer wants it (:class:`~app.compute.workers.Superseded`);
    ``progress(fraction)``: the job's progress."""
    return run_job(job_key(lw, req), req.job, (lw,), stop, progress)


def is_cached(lw, req: Request) -> bool:
    """Whether :func:`run` would answer from the cache (nothing computed); False for a
    request whose key cannot be made (ParameterError)."""
    try:
        return CACHE.peek(job_key(lw, req)) is not None
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


def floquet_spectrum(lw, req: WaveRequest, stop=None, progress=None):
    """(wave Computed, spectrum Computed or None) of the wave ``req``: the wave from the shared
    cache if there (the entry :func:`run` fills), else wave and spectrum in one worker job.
    ``progress(done, stage=...)``: its stages (:data:`~app.compute.jobs.FLOQUET_STAGES`).  The
    one job that answers two requests: its wave goes into the wave's own cache entry."""
    wk = job_key(lw, req)
    rc = CACHE.lookup(wk)
    staged = None if progress is None else SpectrumProgress(progress, req.N)
    c = run_job(spectrum_key(lw, req), floquet_job, (lw, req), stop, staged)
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
