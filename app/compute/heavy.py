"""The one road from a scene to a result: :func:`run` takes the law and a typed request and
computes the request's job, cached exactly on :func:`job_key`; :func:`is_cached` says whether
it would answer from the cache.  A heavy request (:mod:`app.compute.requests`) runs in a worker
process through :func:`~app.compute.workers.run_job`; a cheap one
(:class:`~app.compute.request_base.LocalRequest`: the QC requests, the energy criterion) in
this process.  The Floquet spectrum of a wave (:class:`SpectrumRequest`) is the one job that
fills two cache entries (the wave's and the spectrum's), with a time-left estimate for its
silent eigenvalue call.

Views never build keys themselves: a request's key is the request.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Hashable
from dataclasses import dataclass

from fpucore import floquet as fq
from fpucore.errors import ParameterError

from .cache import CACHE, Computed
from .jobs import floquet_job, stage_of
from .laws import law_key
from .request_base import Call, Request
from .requests import WaveRequest
from .workers import run_job

__all__ = ["run", "is_cached", "job_key", "SpectrumRequest"]


@dataclass(frozen=True)
class SpectrumRequest(Request):
    """The Floquet spectrum (fpucore.floquet.spectrum) of the discrete wave ``wave``: one
    worker job computes the wave and its spectrum, and its value under :func:`run` is the pair
    (the wave's Computed, the spectrum's Computed or None if the wave did not converge); the
    wave also goes into the wave request's own cache entry."""

    wave: WaveRequest

    def __post_init__(self):
        if not isinstance(self.wave, WaveRequest):
            raise ParameterError("wave", self.wave, "a WaveRequest")

    def call(self) -> Call:
        """The spectrum's call on the wave's result (``floquet.spectrum(r)``)."""
        return Call("floquet", fq.spectrum)

    def job_key(self, lw) -> tuple:
        return ("floquet", self.wave.job_key(lw))

    def job(self, lw, progress=None):
        """(WaveResult, FloquetResult or None), in stages
        (:func:`~app.compute.jobs.floquet_job`)."""
        return floquet_job(lw, self.wave, progress)


def job_key(lw, req: Request) -> Hashable:
    """The exact cache key of ``req``'s result under the law ``lw``: the law's exact key and
    the request's (its solver's inputs).  Raises ParameterError (e.g. a superkink's w₊ outside
    its range)."""
    return (law_key(lw), req.job_key(lw))


def run(lw, req: Request, stop=None, progress=None, queued=None) -> Computed | None:
    """``req``'s job under the law ``lw``, cached exactly: the same request again (from any
    session) is answered from the cache, two sessions asking at once share one computation.

    A heavy request runs in a worker process: ``stop()`` says the caller no longer wants it
    (:class:`~app.compute.workers.Superseded`), ``progress(fraction)`` gets its progress (a
    SpectrumRequest's: ``progress(done, stage=...)``), ``queued(n)`` the number of earlier jobs
    it waits behind (0 once a worker took it).  A local one (``req.local``) is computed
    here; one with a ``source`` request is computed from the source's cached result, None
    while that is not cached."""
    if isinstance(req, SpectrumRequest):
        return _spectrum(lw, req, stop, progress, queued)
    if not req.local:
        return run_job(job_key(lw, req), req.job, (lw,), stop, progress, queued=queued)
    source = getattr(req, "source", None)
    if source is None:
        return CACHE.get(job_key(lw, req), lambda: req.job(lw))
    value = CACHE.peek(job_key(lw, source))
    if value is None:
        return None
    return CACHE.get(job_key(lw, req), lambda: req.from_source(lw, value))


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


def _spectrum(lw, sreq: SpectrumRequest, stop=None, progress=None, queued=None) -> Computed:
    """Computed((wave Computed, spectrum Computed or None)): the wave from the shared cache if
    there (the entry :func:`run` fills), else wave and spectrum in one worker job.
    ``progress(done, stage=...)``: its stages (:data:`~app.compute.jobs.FLOQUET_STAGES`).  The
    one job that answers two requests: its wave goes into the wave's own cache entry."""
    req = sreq.wave
    wk = job_key(lw, req)
    rc = CACHE.lookup(wk)
    staged = None if progress is None else SpectrumProgress(progress, req.N)
    c = run_job(job_key(lw, sreq), sreq.job, (lw,), stop, staged, queued=queued)
    r, fr = c.value
    if fr is not None and not c.cached:  # the job's spectra take one route (the default)
        spent = fr.monodromy_s + fr.check_s + fr.eig_s
        with _RATE_LOCK:
            _SPECTRUM_RATE[:] = [spent / (2.0 * fr.N) ** 3]
    if rc is None:
        CACHE.put(wk, r, r.elapsed_s)
        rc = Computed(r, r.elapsed_s, c.cached)
    spec = None if fr is None else Computed(fr, fr.elapsed_s, c.cached)
    return Computed((rc, spec), c.elapsed_s, c.cached)
