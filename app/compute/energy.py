"""The energy criterion for the scenes: extrema of E_ren(V) along a solitary family.

The QC extrema (eq. Eren_QC) are cheap and computed in process; the discrete ones (eq. Eren_D)
come from waves already computed (a cached discrete family, a cached Floquet sweep) by parabola
fits, and the sweep's classifications are cross-checked against them.  Everything is cached
exactly (:mod:`app.compute.cache`).
"""

from __future__ import annotations

import numpy as np

from fpucore import floquet as fq
from fpucore import qc

from .cache import CACHE, Computed, exact
from .heavy import job_key
from .laws import law_key
from .requests import FamilyRequest, SweepRequest

__all__ = [
    "ENERGY_QC_SAMPLES",
    "energy_qc_samples",
    "energy_extrema_qc",
    "sampled_energy_extrema",
    "family_energy_extrema",
    "sweep_energy_check",
]


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


def family_energy_extrema(lw, req: FamilyRequest) -> Computed:
    """The discrete E_ren's extrema along a discrete family that is already cached (the
    diagram's dots): see :func:`sampled_energy_extrema`.  None if the family is not cached."""
    key = job_key(lw, req)
    w_plus = req.w_plus
    rows = CACHE.peek(key)
    if rows is None:
        return None
    rows = [r for r in rows if hasattr(r, "energy")]
    V = [r.V for r in rows]
    E = [r.energy for r in rows]
    dE = [fq.energy.wave_energy_error(r) for r in rows]
    ok = [bool(r.converged) for r in rows]
    return sampled_energy_extrema(key, lw, w_plus, V, E, dE, ok)


def sweep_energy_check(lw, req: SweepRequest) -> Computed | None:
    """The energy criterion on a cached solitary Floquet sweep (its rows carry each wave's
    E_ren, energy_error and classification): (EnergyCriterion with the discrete extrema from the
    sweep's waves and the QC extrema, list of fpucore.floquet.StabilityChange — the cross-check
    of the classifications against the extrema).  Parabola fits plus the QC grid (1–10 ms for
    the cubic); None if the sweep is not cached."""
    key = job_key(lw, req)
    w_plus = req.w_plus
    sw = CACHE.peek(key)
    if sw is None:
        return None
    n = energy_qc_samples(lw)

    def check():
        ok = np.asarray(sw.floquet_converged, bool)
        ec = fq.criterion_from_samples(lw, w_plus, sw.V, sw.energy, sw.energy_error, ok, n)
        return ec, fq.stability_changes(lw, w_plus, sw.V, sw.classification, ec)

    return CACHE.get(("energy_sweep", key, n), check)
