"""The jobs run in worker processes (:mod:`app.compute.workers`) and their exact cache keys.

The ``*_job`` functions are module-level and take plain parameters (picklable) and return the
fpucore result; each ``*_key`` is the exact key of the same call (the solver's own inputs, the
law's :func:`~app.compute.laws.law_key`).  Bad parameters surface as
``fpucore.errors.ParameterError``.
"""

from __future__ import annotations

import numpy as np

from fpucore import floquet as fq
from fpucore import qc, wave
from fpucore import simulate as sim
from fpucore.atlas import sweep
from fpucore.errors import ParameterError
from fpucore.parallel import Executor

from .cache import exact
from .laws import law_key

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
    "wave_key",
    "floquet_key",
    "sweep_key",
    "family_key",
    "simulation_key",
]


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


def floquet_job(lw, mode: str, w_plus: float, V: float, N: int, tol: float, progress=None):
    """(WaveResult, FloquetResult or None if the wave did not converge).  ``progress`` gets
    :func:`stage_progress` values: the wave, the spectrum, the shorter rings."""
    send = None if progress is None else (lambda stage, x: progress(stage_progress(stage, x)))
    if send is not None:
        send("discrete wave", 0.0)
    r = wave_job(lw, mode, w_plus, V, N, tol)
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


# --------------------------------------------------------------------------- keys
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
