"""Thin adapter between the dashboard and fpucore: cached, exact, off the server process.

The app computes nothing itself: every number shown comes from fpucore's public API, asked for
through one road (the views' single entry point: ``from app import compute``):

    compute.run(law, request)        the request's result (a :class:`Computed`), cached exactly
    compute.is_cached(law, request)  whether run would answer from the cache
    compute.job_key(law, request)    its exact cache key (for a plot's data key)

* a **request** is a typed, frozen dataclass checked when made: at once the job, its exact
  cache key and the fpucore call it stands for ("Copy as Python" shows that call).  A new
  computation is a new request, never a new function here;
* heavy requests (discrete waves, Floquet spectra, sweeps, discrete families, simulations,
  small atlases) run in worker processes (the project's execution layer,
  :mod:`fpucore.parallel`): progress is forwarded, a caller that no longer wants the result (a
  newer slider value, the Cancel button) leaves with :class:`Superseded`, and the job is killed
  once nobody waits for it;
* cheap ones (the QC waves, families, phase plane and existence diagram, the energy criterion)
  are computed in the server process;
* one process-wide cache (:data:`CACHE`) is shared by all scenes and sessions, keyed on the
  **exact** inputs (``repr`` of each float, the law's coefficients, N, tol): two sessions asking
  the same thing share one result; each :class:`Computed` carries its wall time and whether it
  was cached.

Namespaces beside the road: :mod:`~app.compute.laws` (the app's laws, ``law_key``, the law
worker), :mod:`~app.compute.workers` (the process pool, its warm-up, ``CANCELLED``),
:mod:`~app.compute.requests` / :mod:`~app.compute.request_base` (``Call``, the atlas limits),
:mod:`~app.compute.cache` (``exact``, ``ResultCache``), :mod:`~app.compute.energy`.

    cache → laws → workers → request_base → requests (heavy) → qc_requests, energy (local)
    → jobs (the Floquet job) → heavy (the road: run, is_cached, job_key; SpectrumRequest)

Bad parameters surface as ``fpucore.errors.ParameterError`` (re-exported).
"""

from concurrent.futures import CancelledError

from fpucore.errors import ParameterError

from . import cache, laws, request_base, requests, workers  # noqa: F401 - the namespaces
from .cache import CACHE, Computed
from .energy import EnergyRequest, SampledEnergyRequest
from .heavy import SpectrumRequest, is_cached, job_key, run
from .qc_requests import (
    ExistenceRequest,
    PhaseOrbitRequest,
    PhasePlaneRequest,
    QCFamilyRequest,
    QCWaveRequest,
)
from .request_base import Request

# every request of requests.py (its __all__) is app.compute's: a new request needs no line here
from .requests import *  # noqa: F403
from .requests import __all__ as _REQUESTS
from .workers import Superseded

__all__ = [
    # the road
    "run",
    "is_cached",
    "job_key",
    "Computed",
    "CACHE",
    # errors and cancellation
    "ParameterError",
    "CancelledError",
    "Superseded",
    # requests: heavy (worker processes)
    "Request",
    *_REQUESTS,
    "SpectrumRequest",
    # requests: local (this process)
    "QCWaveRequest",
    "QCFamilyRequest",
    "ExistenceRequest",
    "PhasePlaneRequest",
    "PhaseOrbitRequest",
    "EnergyRequest",
    "SampledEnergyRequest",
]
