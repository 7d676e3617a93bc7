"""Thin adapter between the dashboard and fpucore: cached, exact, off the server process.

The app computes nothing itself: every number shown comes from fpucore's public API through the
functions re-exported here (the views' single entry point: ``from app import compute``).  They
add what the views need:

* a process-wide cache shared by all scenes and sessions, keyed on the **exact** inputs
  (``repr`` of each float, the law's coefficients, N, tol): a cached result is only ever
  returned for the very same inputs.  Keys are made from the requests only; views ask
  ``is_cached(law, request)`` instead of building them;
* heavy computations (discrete waves, Floquet spectra, sweeps, discrete families, simulations,
  small atlases) run in worker processes (the project's execution layer,
  :mod:`fpucore.parallel`) through :func:`run` (``run(law, request)``): progress is
  forwarded, a caller that no longer wants the result (a newer slider value, the Cancel button)
  leaves, and the job is killed once nobody waits for it; two sessions asking for the same key
  share one job;
* wall time of the computation (``Computed.elapsed_s``) and whether it was cached;
* typed requests (:mod:`~app.compute.requests`: frozen dataclasses checked when made, each
  the job, its exact key and the fpucore call it stands for — "Copy as Python" shows that
  call).  A new heavy computation is a new request, not a new function here.

    cache (exact keys, Computed, the LRU ResultCache CACHE) → laws (the app's laws, law_key)
    → workers (the process pool, run_job, Superseded, worker warm-up)
    → qc_calls (QC waves, families, phase plane, existence diagram, n_needed: in process)
    → requests (WaveRequest, FamilyRequest, SweepRequest, SimulationRequest and its kinds,
      AtlasRequest: each the job, its exact key and its Call, the source of "Copy as Python")
    → jobs (the Floquet job: a wave and its spectrum, in stages)
    → heavy (the road: run(law, request), is_cached, job_key; floquet_spectrum)
    → energy (the energy criterion's extrema, from QC and from cached waves)

Bad parameters surface as ``fpucore.errors.ParameterError`` (re-exported).
"""

from concurrent.futures import CancelledError

from fpucore.errors import ParameterError

from .cache import CACHE, Computed, ResultCache, exact
from .energy import (
    ENERGY_QC_SAMPLES,
    energy_extrema_qc,
    energy_qc_samples,
    family_energy_extrema,
    sampled_energy_extrema,
    sweep_energy_check,
)
from .heavy import floquet_spectrum, is_cached, job_key, run, spectrum_key
from .laws import (
    LAW_TIME_S,
    building_page,
    expression_law,
    join_law,
    law,
    law_from_text,
    law_key,
    lookup_law,
    make_law,
    request_law,
    shutdown_law_executor,
    split_law,
    trusted_expression_law,
)
from .qc_calls import (
    existence_diagram,
    n_needed,
    phase_orbit,
    phase_plane,
    qc_family,
    qc_method,
    qc_wave,
    spec_of,
)

# every request of requests.py (its __all__) is app.compute's: a new request needs no line here
from .requests import *  # noqa: F403
from .requests import __all__ as _REQUESTS
from .workers import (
    CANCELLED,
    Superseded,
    executor,
    jobs_in_flight,
    run_job,
    shutdown_executor,
    warm_workers,
)

__all__ = [
    # errors
    "ParameterError",
    "CancelledError",
    # cache
    "CACHE",
    "Computed",
    "ResultCache",
    "exact",
    # laws
    "law",
    "expression_law",
    "trusted_expression_law",
    "lookup_law",
    "request_law",
    "shutdown_law_executor",
    "building_page",
    "LAW_TIME_S",
    "make_law",
    "law_key",
    "split_law",
    "join_law",
    "law_from_text",
    # workers
    "CANCELLED",
    "Superseded",
    "executor",
    "shutdown_executor",
    "jobs_in_flight",
    "run_job",
    "warm_workers",
    # QC
    "qc_method",
    "qc_wave",
    "qc_family",
    "phase_plane",
    "phase_orbit",
    "existence_diagram",
    "spec_of",
    "n_needed",
    # the road: typed requests, run in workers and cached on their exact keys
    *_REQUESTS,
    "run",
    "is_cached",
    "job_key",
    "floquet_spectrum",
    "spectrum_key",
    # energy criterion
    "ENERGY_QC_SAMPLES",
    "energy_qc_samples",
    "energy_extrema_qc",
    "sampled_energy_extrema",
    "family_energy_extrema",
    "sweep_energy_check",
]
