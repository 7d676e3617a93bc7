"""Discrete traveling waves (paper §5): fixed points of the one-period-and-shift map.

Flow of this subpackage:

    period_map (RK integration over one period, tangent columns; a piecewise-linear law's
    period through period_events: crossings located, tangent on the same sub-steps; its
    explicit compact waves: compact)  →  system (Newton system, banded Jacobian)  →  tails
    (N from the decay, resize)  →  tolerances (strain scale, Tolerances)  →  setup (Spec: the
    wave, its law and what derives from them: tolerances, N, m, K, the system, the predictor)
    →  plateau_newton (the bordered Newton system in plateau mass)  →  plateau (flat tops
    near V_SK)  →  continuation  →  attempt (one solve: tolerances, routes, rescues)
    →  bounds (error bounds, E_ren)  →  observables (particle velocities, E_ren^D)
    →  wave_result (WaveResult)  →  driver (solve_superkink / solve_solitary)
    →  family (families over V)

    r = wave.solve_superkink(law, V, branch="lower", N=None, tol=1e-12)
    r = wave.solve_solitary(law, w_plus, V, N=None, tol=1e-12)
"""

from fpucore.wave.driver import (
    WaveResult,
    particle_velocities,
    renormalized_energy,
    solve_solitary,
    solve_superkink,
    warm,
)
from fpucore.wave.family import Family, solitary_family, superkink_family
from fpucore.wave.setup import (
    M_STEPS,
    Spec,
    Tolerances,
    resize,
    solitary_spec,
    spec_of,
    strain_scale,
    superkink_spec,
)

__all__ = [
    "WaveResult",
    "solve_superkink",
    "solve_solitary",
    "warm",
    "particle_velocities",
    "renormalized_energy",
    "Family",
    "superkink_family",
    "solitary_family",
    "M_STEPS",
    "Spec",
    "Tolerances",
    "resize",
    "solitary_spec",
    "spec_of",
    "strain_scale",
    "superkink_spec",
]
