"""The Floquet job (a wave and its spectrum in one worker job) and its stages.

Every other job is its request's own :meth:`~app.compute.requests.Request.job`; this one runs a
:class:`~app.compute.requests.WaveRequest`'s wave and then fpucore.floquet.spectrum, reporting
its stages through one progress number.  Bad parameters surface as
``fpucore.errors.ParameterError``.
"""

from __future__ import annotations

from fpucore import floquet as fq

from .requests import WaveRequest

__all__ = ["floquet_job", "FLOQUET_STAGES", "stage_progress", "stage_of"]

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
    r = req.job(lw)
    return r, (fq.spectrum(r, progress=send) if r.converged else None)
