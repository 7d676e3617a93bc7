"""The jobs run in worker processes (:mod:`app.compute.workers`) and their exact cache keys.

The ``*_job`` functions are module-level, take the law and plain or typed parameters
(:mod:`app.compute.requests`: picklable, checked when made) and return the fpucore result; each
``*_key`` is the exact key of the same call (the solver's own inputs, the law's
:func:`~app.compute.laws.law_key`).  Bad parameters surface as
``fpucore.errors.ParameterError``.
"""

from __future__ import annotations

import numpy as np

from fpucore import floquet as fq
from fpucore import wave
from fpucore.atlas import sweep
from fpucore.errors import ParameterError
from fpucore.parallel import Executor

from .cache import exact
from .laws import law_key
from .requests import AtlasRequest, Call, SeededRequest, SimulationRequest, WaveRequest

__all__ = [
    "wave_call",
    "wave_job",
    "floquet_job",
    "FLOQUET_STAGES",
    "stage_progress",
    "stage_of",
    "fraction",
    "sweep_job",
    "family_job",
    "simulation_job",
    "atlas_job",
    "wave_key",
    "floquet_key",
    "sweep_key",
    "family_key",
    "simulation_key",
    "atlas_key",
]


def wave_call(lw, req: WaveRequest) -> Call:
    """The exact fpucore call of a discrete wave (used by the job, the cache key and "copy as
    Python").  Raises ParameterError (a superkink's w₊ outside its range)."""
    return req.call(lw)


def wave_job(lw, req: WaveRequest):
    """Discrete traveling wave (fixed point of eq. nonlin_map): fpucore.wave.solve_superkink
    (branch of w_plus) or fpucore.wave.solve_solitary.  Returns the WaveResult."""
    return req.call(lw).run(lw)


#: the stages of a Floquet job in order (the shorter rings only when the excess needs them)
FLOQUET_STAGES = ("discrete wave", "Floquet spectrum", "shorter rings")


def stage_progress(stage: str, done: float) -> float:
    """(stage, its fraction done) → the one number the execution layer forwards: stage k of n
    covers [k/n, (k+1)/n)."""
    k, n = FLOQUET_STAGES.index(stage), len(FLOQUET_STAGES)
    return (k + min(max(float(done), 0.0), 0.999)) / n


def stage_of(x: float) -> tuple[str, float]:
    """Inverse of :func:`stage_progress`: (stage, its fraction done)."""
    n = len(FLOQUET_STAGES)
    k = min(int(float(x) * n), n - 1)
    return FLOQUET_STAGES[k], min(float(x) * n - k, 1.0)


def floquet_job(lw, req: WaveRequest, progress=None):
    """(WaveResult, FloquetResult or None if the wave did not converge).  ``progress`` gets
    :func:`stage_progress` values: the wave, the spectrum, the shorter rings."""
    send = None if progress is None else (lambda stage, x: progress(stage_progress(stage, x)))
    if send is not None:
        send("discrete wave", 0.0)
    r = wave_job(lw, req)
    return r, (fq.spectrum(r, progress=send) if r.converged else None)


def fraction(progress):
    """fpucore's family callbacks ``progress(i, n, ...)`` → the execution layer's
    ``progress(fraction)``."""
    if progress is None:
        return None
    return lambda i, n, *rest: progress(i / max(n, 1))


def sweep_job(lw, kind, w_plus, V_values, N, branch, progress=None):
    """max |μ| against V for a family (fpucore.atlas.sweep), run inline in this worker: a pool
    worker is daemonic and may not start a pool of its own (the server's pool already spreads
    the sessions' jobs over the cores)."""
    return sweep(
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


def simulation_job(lw, req: SimulationRequest, progress=None):
    """Direct simulation via fpucore.simulate (riemann, gaussian, or seeded by the discrete
    wave of ``req.wave``, which must converge)."""
    extra = {} if progress is None else {"progress": progress}
    first = lw
    if isinstance(req, SeededRequest):
        first = wave_job(lw, req.wave)
        if not first.converged:
            raise ParameterError("N", req.wave.N, "a converged seeding wave",
                                 f"did not converge: {first.message}")  # fmt: skip
    return req.call().run(first, **extra)


def atlas_job(lw, req: AtlasRequest, progress=None):
    """A small atlas (fpucore.atlas.run, see :class:`AtlasRequest`), its chunks computed one
    after the other in this worker (a pool worker may not start a pool of its own; the server's
    pool spreads the sessions' jobs over the cores).  ``progress``: the fraction of points
    done, after each chunk (a row of the grid).  Returns the AtlasResult."""
    return req.call().run(lw, executor=Executor(backend="inline"), progress=fraction(progress))


# --------------------------------------------------------------------------- keys
def wave_key(lw, req: WaveRequest) -> tuple:
    """Exact key of a discrete wave: the solver's own inputs (raises ParameterError)."""
    return ("wave", law_key(lw), req.call(lw).key())


def floquet_key(lw, req: WaveRequest) -> tuple:
    return ("floquet",) + wave_key(lw, req)


def sweep_key(lw, kind, w_plus, V_values, N, branch) -> tuple:
    wp = None if w_plus is None else exact(w_plus)
    Vs = tuple(exact(v) for v in V_values)
    return ("fsweep", law_key(lw), kind, wp, Vs, int(N), branch)


def family_key(lw, w_plus, V_values, N, tol) -> tuple:
    Vs = tuple(exact(v) for v in V_values)
    return ("dfamily", law_key(lw), exact(w_plus), Vs, int(N), exact(tol))


def simulation_key(lw, req: SimulationRequest) -> tuple:
    return ("sim", law_key(lw), req.key())


def atlas_key(lw, req: AtlasRequest) -> tuple:
    return ("atlas", law_key(lw), req.key())
