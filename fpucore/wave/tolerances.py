"""The tolerances of a discrete-wave solve (paper §5): the strain scale s of eq. nonlin_system's
round-off, every tolerance derived from the user's relative ``tol`` and s (:class:`Tolerances`),
and the factor above the round-off level up to which residuals are accepted."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from fpucore.errors import require_finite

FLOOR_FACTOR = 4.0  # accept residuals / step-doubling errors up to this × the round-off level


class ScaledWave(Protocol):
    """What the tolerances of a solve depend on: a :class:`fpucore.wave.setup.Spec`'s strain
    scale and QC amplitude."""

    @property
    def scale(self) -> float: ...

    @property
    def amplitude_qc(self) -> float: ...


def strain_scale(w_left: float, w_right: float) -> float:
    """s = max(1, |w_left|, |w_right|): the round-off of eq. nonlin_system grows with |w|, so
    every tolerance of a solve is relative to s (:class:`Tolerances`).

    Parameters
    ----------
    w_left, w_right : float
        Boundary strains of the wave.

    Returns
    -------
    float
        The strain scale s >= 1.

    Raises
    ------
    ParameterError
        When ``w_left`` or ``w_right`` is not finite.
    """
    return max(1.0, abs(require_finite("w_left", w_left)), abs(require_finite("w_right", w_right)))


@dataclass(frozen=True)
class Tolerances:
    """Every tolerance of one solve (absolute unless said), from the user's relative ``tol``.

    Its fields::

        scale     strain scale s = max(1, |w_left|, |w_right|) (:func:`strain_scale`): round-off of
                  eq. nonlin_system grows with |w| (b = 100 or a = −0.01 stagnate at ~3e-14·s).
        res_tol   Newton accepts max-norm residual ≤ res_tol = tol·s (raised to the round-off
                  level of the system where that is larger: see :class:`.attempt.WaveSolve`).
        step_tol  Newton keeps stepping until its next correction (strain units, max(|δw|, T|δẇ|))
                  is ≤ step_tol = tol·s, or the corrections stop shrinking (round-off).
        int_tol   step count m: step-doubling error of the period map ≤ int_tol = tol·s.
        tail_tol  automatic N: the tails decay to tail_tol = 0.1·tol·s at the chain's ends.
        tail_ok   a converged wave whose tails miss the boundary states by more than
                  1e-5·A_QC + 1e3·tol·s is another wave (rejected).
    """

    tol: float
    scale: float
    res_tol: float
    step_tol: float
    int_tol: float
    tail_tol: float
    tail_ok: float

    @classmethod
    def of(cls, spec: ScaledWave, tol: float) -> Tolerances:
        s = spec.scale
        t = tol * s
        return cls(tol, s, t, t, t, 0.1 * t, 1e-5 * spec.amplitude_qc + 1e3 * t)
