"""The record of one chain simulation (:class:`SimulationResult`), returned by every driver
(:mod:`fpucore.simulate.scenarios`, :mod:`fpucore.simulate.seeded`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.result import Result, status_of
from fpucore.simulate.tracking import TrackedWave

__all__ = ["SimulationResult", "TrackedWave"]


@dataclass(frozen=True)
class SimulationResult(Result):
    """Outcome of one chain simulation.

    t : (n_t,) snapshot times; sites : (n_sites_out,) 1-based site numbers n kept in the output;
    snapshots : (n_t, n_sites_out) strains w_n(t_k); probe_sites : (P,) 1-based sites;
    probe_t : (M,) and probe_series : (P, M) strains at the probe sites on a uniform time grid
    (degree-7 Hermite interpolation between steps); energy : (n_t,) conserved energy H at the
    snapshot times (which H per boundary: :mod:`fpucore.simulate.scenarios`); energy_drift :
    max_k |H(t_k) − H(0)| / E_scale (relative; E_scale = Σ of the absolute values of the terms of H
    at t = 0), energy_drift_abs the same unscaled; error_estimate : the integrator's own error
    estimate — for adaptive RK the accumulated local error estimates (absolute, RMS over the
    state: (w, v) for the first-order pairs, (w, ẇ) for the RKN pairs), for the symplectic
    method the step-doubling difference of the strains, max|w_h − w_2h| / 15, at the snapshot
    times; waves : tracked waves (:class:`TrackedWave`);
    stop_reason : "ok" | "left_convex" | "budget" (max_steps) | "time_budget" (time_budget_s) |
    "step_underflow" | "nonfinite" (why the run ended);
    converged : it reached t_end (stop_reason == "ok"); status : "ok" | "stopped" (the
    common vocabulary of :mod:`fpucore.result`); message : human-readable summary (reason +
    suggestion on failure).
    final_w : (L,) strains at t_final (full resolution).  details : scenario-specific numbers
    (seeded runs: prescribed/measured velocity, phase and shape errors).
    """

    scenario: str
    L: int
    boundary: str
    method: str
    rtol: float
    dt: float | None
    t: np.ndarray
    sites: np.ndarray
    snapshots: np.ndarray
    probe_sites: np.ndarray
    probe_t: np.ndarray
    probe_series: np.ndarray
    energy: np.ndarray
    energy_drift: float
    energy_drift_abs: float
    energy_name: str
    error_estimate: float
    n_steps: int
    n_rejected: int
    n_rhs: int
    t_final: float
    final_w: np.ndarray
    waves: list
    stop_reason: str
    message: str
    elapsed_s: float
    details: dict = field(default_factory=dict)

    ERROR_FIELDS: ClassVar = ("error_estimate", "energy_drift")
    DERIVED: ClassVar = ("status", "converged")

    @property
    def converged(self) -> bool:
        return self.stop_reason == "ok"

    @property
    def success(self) -> bool:  # the name used before the result protocol
        return self.converged

    @property
    def status(self) -> str:
        return status_of(self.converged, stopped=True)

    def summary(self) -> dict:
        """JSON-friendly summary: :meth:`as_dict` without the arrays."""
        return self.as_dict(arrays=False)
