"""Floquet stability of discrete traveling waves (paper §6, eqs. linear, linear_map).

kernels (Numba: shifted rows, exact deflation)  →  monodromy (𝓜 from the tangent flow,
its multipliers)  →  reversible_kernels → reversible (the quarter-size route of reversible
waves)  →  structured_kernels → arnoldi_kernels → structured (the half-size symplectic route)
→  multipliers (FloquetResult: spectrum, error bars, verdict)
→  checks (quartet symmetry, homogeneous closed form, phonon gap)  →  finite_size (is an
excess |μ| − 1 an artefact of the finite ring? the one Decision record)  →  energy (extrema
of E_ren(V) along solitary families, where stability may change)  →  sweep (max|μ| along V)
"""

from fpucore.floquet.checks import (
    HomogeneousState,
    homogeneous_multipliers,
    phonon_gap,
    quartet_symmetry_error,
)
from fpucore.floquet.energy import (
    EnergyCriterion,
    StabilityChange,
    changes_summary,
    criterion_from_samples,
    energy_criterion,
    stability_changes,
)
from fpucore.floquet.finite_size import CLASSES, Decision, chain_lengths
from fpucore.floquet.monodromy import MAX_N, Monodromy, default_steps, monodromy, multipliers_of
from fpucore.floquet.multipliers import METHODS, FloquetResult, spectrum
from fpucore.floquet.reversible import reversor_of
from fpucore.floquet.structured import structured_multipliers
from fpucore.floquet.sweeps import SweepResult, sweep

__all__ = [
    "HomogeneousState",
    "homogeneous_multipliers",
    "phonon_gap",
    "quartet_symmetry_error",
    "MAX_N",
    "Monodromy",
    "default_steps",
    "monodromy",
    "multipliers_of",
    "EnergyCriterion",
    "energy_criterion",
    "criterion_from_samples",
    "StabilityChange",
    "stability_changes",
    "changes_summary",
    "CLASSES",
    "chain_lengths",
    "Decision",
    "METHODS",
    "structured_multipliers",
    "reversor_of",
    "FloquetResult",
    "spectrum",
    "SweepResult",
    "sweep",
]
