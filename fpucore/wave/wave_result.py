"""The result of a discrete traveling-wave solve (paper §5): the wave at t = 0 and its error
budget against the infinite chain's exact wave (built by :mod:`fpucore.wave.driver`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fpucore.result import Result, status_of

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw


@dataclass(frozen=True)
class WaveResult(Result):
    """A discrete traveling wave at t = 0 and its error budget.

    kind : "superkink" | "tensile" | "compressive".  V : velocity.  N : sites n = −N/2 … N/2−1.
    n : (N,) int64 site indices; w, wdot : (N,) w_n(0), ẇ_n(0).  w_left, w_right : the fixed
    boundary strains w_{−N/2−1}, w_{N/2} (eq. fixedBCs).  w_plus : state ahead (the superkink's
    w₊ for solitary waves, whose background is w_B = w_left = w_right).
    residual : max-norm of eq. nonlin_system; dropped_residual : |ẇ_{N/2}(T) − ẇ_{N/2−1}(0)|.
    profile_error : a-posteriori BOUND on max_n |w_n(0) − w_n*(0)| against the exact traveling
    wave of the infinite chain with the same pinning (Newton stopping point and RK error through
    J⁻¹, round-off through ‖J⁻¹‖, truncation by N: :mod:`fpucore.wave.bounds`).
    amplitude_error, energy_error : bounds on |Δ amplitude|, |Δ E_ren^D| derived the same way
    (solitary waves; a superkink's amplitude |w₋ − w₊| is exact: 0; its energy_error is NaN like
    its energy).  residual_floor : the round-off level of the residual (× FLOOR_FACTOR) that
    Newton accepted when it exceeded tol·scale (stiff laws) — the achievable tolerance.
    tail_error : |w − w_∞|, |ẇ| at the 3 outermost sites per end (truncation by finite N).
    integrator_error : step-doubling |Φ_m − Φ_2m| at the solution (m RK steps per period).
    jacobian_truncation : largest tangent-window edge value (neglected Jacobian entries < it).
    amplitude : |w(0) − w_B| (solitary, paper's w_amp) or |w_left − w_right| (superkink).
    energy : E_ren^D of eq. Eren_D (solitary waves; NaN for superkinks, whose two backgrounds
    differ).  qc_max_deviation : max_n |w_n − w_QC(n)|.  route : how it converged.
    """

    kind: str
    V: float
    N: int
    n: np.ndarray
    w: np.ndarray
    wdot: np.ndarray
    w_left: float
    w_right: float
    w_plus: float
    law: HardeningSofteningLaw
    residual: float
    dropped_residual: float
    converged: bool
    iterations: int
    residual_history: tuple
    elapsed_s: float
    message: str
    amplitude: float
    energy: float
    qc_max_deviation: float
    tail_error: float
    integrator_error: float
    jacobian_truncation: float
    profile_error: float
    amplitude_error: float
    energy_error: float
    residual_floor: float
    m: int
    K: int
    jacobian: str
    route: str
    v: np.ndarray
    branch: str | None = None
    front_uncertainty: float = math.nan  # sites; flat-top waves near V_SK only (wave_plateau)

    ERROR_FIELDS: ClassVar = (
        "residual",
        "dropped_residual",
        "tail_error",
        "integrator_error",
        "jacobian_truncation",
        "profile_error",
        "amplitude_error",
        "energy_error",
    )
    DERIVED: ClassVar = ("status",)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def T(self) -> float:
        return 1.0 / self.V

    def errors(self) -> dict[str, float]:
        """The error fields that apply to this wave: a superkink has no E_ren^D (two different
        backgrounds), so its energy_error (NaN, like its energy) is left out."""
        out = Result.errors(self)
        if self.kind == "superkink":
            del out["energy_error"]
        return out

    def as_dict(self, profile: bool = True, arrays: bool | None = None) -> dict:  # type: ignore[override]
        """Every field (see :meth:`fpucore.result.Result.as_dict`); ``profile=False`` leaves out the
        arrays n, w, wdot, v."""
        return Result.as_dict(self, arrays=profile if arrays is None else arrays)
