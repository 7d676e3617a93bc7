"""The result of the energy criterion (paper eqs. Eren_D, Eren_QC): extrema of E_ren(V) along a
solitary-wave family, discrete and QC, each with its error bar on V (built by
:func:`fpucore.floquet.energy.energy_criterion`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.result import Result
from fpucore.wave import Family


@dataclass(frozen=True)
class EnergyCriterion(Result):
    """Extrema of E_ren(V) along a solitary-wave family, discrete and QC.

    V, energy, energy_error : (n,) the discrete family (energy_error: the wave's own bound,
    ``WaveResult.energy_error`` where present, else a residual-based indicator, see
    :func:`wave_energy_error`); wave_converged : (n,) bool.
    extrema_V, extrema_V_error, extrema_energy : (k,) located extrema of the discrete E_ren;
    extrema_kind : ("min" | "max", …).
    qc_V, qc_energy : (m,) the QC closed form on a grid over both intervals;
    qc_extrema_V, qc_extrema_V_error, qc_extrema_energy, qc_extrema_kind : the same for E_ren^QC.
    stability_may_change : True where any extremum was found (in the discrete family, or in the
    QC family inside the sampled V range); the criterion is necessary, not sufficient.
    location_error : the largest error bar on V of all extrema found (0 when none).
    """

    w_plus: float
    V: np.ndarray
    energy: np.ndarray
    energy_error: np.ndarray
    wave_converged: np.ndarray
    extrema_V: np.ndarray
    extrema_V_error: np.ndarray
    extrema_energy: np.ndarray
    extrema_kind: tuple
    qc_V: np.ndarray
    qc_energy: np.ndarray
    qc_extrema_V: np.ndarray
    qc_extrema_V_error: np.ndarray
    qc_extrema_energy: np.ndarray
    qc_extrema_kind: tuple
    stability_may_change: bool
    location_error: float
    elapsed_s: float
    converged: bool
    message: str
    family: Family | None = field(default=None, repr=False)

    ERROR_FIELDS: ClassVar = ("location_error",)
    DERIVED: ClassVar = ("status",)
    EXCLUDE: ClassVar = ("family",)

    @property
    def status(self) -> str:
        return "ok" if self.converged else "not_converged"
