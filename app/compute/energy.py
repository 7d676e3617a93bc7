"""The energy criterion's requests: extrema of E_ren(V) along a solitary family.

    EnergyRequest(w_plus)          the QC extrema (eq. Eren_QC): closed forms or quadratures
    SampledEnergyRequest(source)   the discrete extrema (eq. Eren_D) from the waves of a cached
                                   FamilyRequest (the diagram's dots) or solitary SweepRequest
                                   (with the cross-check of the sweep's classifications)

Both are cheap and computed in the server process (:class:`~app.compute.request_base.
LocalRequest`), cached exactly; a sampled one reads its source's cached result and is never
computed before it (:func:`app.compute.run` gives None meanwhile).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore import floquet as fq
from fpucore import qc
from fpucore.errors import ParameterError, require_finite

from .request_base import Call, LocalRequest
from .requests import FamilyRequest, SweepRequest

__all__ = ["ENERGY_QC_SAMPLES", "energy_qc_samples", "EnergyRequest", "SampledEnergyRequest"]


#: QC samples per velocity interval for the energy criterion (extrema are bracketed on this
#: grid, then refined): closed forms (cubic) evaluate the whole grid at once (~1 ms; ~8 ms with
#: an extremum to refine); other laws solve the §3 theory point by point (~15 ms each)
ENERGY_QC_SAMPLES = {True: fq.energy.QC_SAMPLES, False: 60}


def energy_qc_samples(lw) -> int:
    """QC samples per interval of the energy criterion's grid: closed forms (the cubic) are
    cheap, a general law's quadrature is not."""
    return ENERGY_QC_SAMPLES[bool(qc.is_closed_form(lw))]


@dataclass(frozen=True)
class EnergyRequest(LocalRequest):
    """Extrema of E_ren^QC(V) (eq. Eren_QC) along the solitary family of w₊, each with its
    error bar on V (fpucore.floquet.energy_criterion without discrete waves: QC closed forms on
    a grid of :func:`energy_qc_samples` points, refined by a bounded minimisation; 1–10 ms for
    the cubic)."""

    w_plus: float

    def __post_init__(self):
        self._set("w_plus", require_finite("w_plus", self.w_plus))

    def call(self, lw) -> Call:
        """The call under the law ``lw`` (its grid size depends on the law)."""
        n = energy_qc_samples(lw)
        return Call("floquet", fq.energy_criterion, (self.w_plus,), (("qc_samples", n),))

    def job_key(self, lw) -> tuple:
        return ("energy_qc", self.call(lw).key())

    def job(self, lw, progress=None):
        return self.call(lw).run(lw)


@dataclass(frozen=True)
class SampledEnergyRequest(LocalRequest):
    """Extrema of the discrete E_ren (eq. Eren_D) from waves already computed: the rows of a
    cached FamilyRequest (an EnergyCriterion from parabola fits only) or of a cached solitary
    SweepRequest (EnergyCriterion with the QC extrema too, and the list of
    fpucore.floquet.StabilityChange: the cross-check of the sweep's classifications against
    the extrema).  fpucore.floquet.criterion_from_samples; cheap."""

    source: FamilyRequest | SweepRequest

    def __post_init__(self):
        src = self.source
        if not (
            isinstance(src, FamilyRequest)
            or isinstance(src, SweepRequest)
            and src.kind == "solitary"
        ):
            raise ParameterError("source", src, "a FamilyRequest or a solitary SweepRequest")

    def job_key(self, lw) -> tuple:
        n = energy_qc_samples(lw) if isinstance(self.source, SweepRequest) else 0
        return (*self.key(), n)

    def job(self, lw, progress=None):  # pragma: no cover - computed from its source only
        raise ParameterError("source", self.source, "a cached result", "not computed yet")

    def from_source(self, lw, value):
        w_plus = self.source.w_plus
        if isinstance(self.source, FamilyRequest):
            rows = [r for r in value if hasattr(r, "energy")]
            V = [r.V for r in rows]
            E = [r.energy for r in rows]
            dE = [fq.energy.wave_energy_error(r) for r in rows]
            ok = [bool(r.converged) for r in rows]
            return fq.criterion_from_samples(lw, w_plus, V, E, dE, ok, qc_samples=0)
        sw, n = value, energy_qc_samples(lw)
        ok = np.asarray(sw.floquet_converged, bool)
        ec = fq.criterion_from_samples(lw, w_plus, sw.V, sw.energy, sw.energy_error, ok, n)
        return ec, fq.stability_changes(lw, w_plus, sw.V, sw.classification, ec)
