"""The record of one chain simulation (:class:`SimulationResult`), returned by every driver
(:mod:`fpucore.simulate.scenarios`, :mod:`fpucore.simulate.seeded`), and of each wave tracked in
it (:class:`TrackedWave`)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.result import Result, status_of

__all__ = ["SimulationResult", "TrackedWave"]


@dataclass(frozen=True)
class TrackedWave:
    """A tracked wave at the end of a run (found and measured by :mod:`fpucore.simulate.tracking`,
    whose WINDOWS and THRESHOLDS are the fit windows and detection thresholds below).

    Its fields::

        kind : "superkink" | "front" | "solitary" | "dsw_edge".
        velocity : sites per unit time (signed, > 0 moving to larger n).
        velocity_error : error of the velocity: the fit's standard error plus the measured spreads
            over fit windows and detection thresholds (the three parts below).
        velocity_fit_error : standard error of the velocity fit alone.
        velocity_window_spread : max |V(window) − V| over WINDOWS.
        velocity_threshold_spread : max |V(threshold) − V| over THRESHOLDS (NaN if the wave
            was found at neither).
        amplitude : pulses — crest strain minus the state ahead (signed: > 0 tensile, < 0
            compressive; the crest is the median of the time extrema of w_n(t) at the sites passed,
            which for a traveling wave all equal its true extremum); fronts — state behind minus
            state ahead.
        left_state / right_state : strain on the lower-n / higher-n side (median over a short
            window; behind a DSW edge, the local mean of the oscillations).
        background : the state ahead (into which the wave moves).
        peak : crest strain of a pulse (front: NaN).
        position : site number n at the end of the window (crest or mid-level crossing).
        n_fit : number of passage times (or snapshots) in the velocity fit.
        method : "passage_times" or "snapshots".
    """

    kind: str
    velocity: float
    velocity_error: float
    amplitude: float
    left_state: float
    right_state: float
    background: float
    peak: float
    position: float
    n_fit: int
    method: str
    velocity_fit_error: float = float("nan")
    velocity_window_spread: float = float("nan")
    velocity_threshold_spread: float = float("nan")
    background_error: float = float("nan")

    def as_dict(self) -> dict:
        return asdict(self)


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
