"""Floquet stability of discrete traveling waves (paper §6, eqs. linear, linear_map).

kernels (Numba: shifted rows, exact deflation)  →  monodromy (𝓜 from the tangent flow,
its multipliers)  →  reversible_kernels → reversible (the quarter-size route of reversible
waves)  →  structured_kernels → arnoldi_kernels → structured (the half-size symplectic route)
→  spectrum_steps (prepare, monodromy pair, eigen-solve, error bars, convergence: one typed
function each)  →  multipliers (FloquetResult: spectrum = those steps, the finite-size window
and the verdict)
→  checks (quartet symmetry, homogeneous closed form, phonon gap)  →  finite_size (is an
excess |μ| − 1 an artefact of the finite ring?)  →  decision (the one Decision record and its
words)  →  energy_result  →  energy_extrema (extrema of E_ren(V) located from samples),
energy_changes (a sweep's classes checked against them)  →  energy (the criterion along
solitary families: where stability may change)

Sweeps of max|μ| along V are one-row atlases and live in the atlas stage
(:func:`fpucore.atlas.sweep`): this package imports nothing above it.
"""

from fpucore.floquet.checks import (
    HomogeneousState,
    homogeneous_multipliers,
    phonon_gap,
    quartet_symmetry_error,
)
from fpucore.floquet.decision import Decision
from fpucore.floquet.energy import (
    EnergyCriterion,
    StabilityChange,
    changes_summary,
    criterion_from_samples,
    energy_criterion,
    stability_changes,
)
from fpucore.floquet.finite_size import CLASSES, chain_lengths
from fpucore.floquet.monodromy import MAX_N, Monodromy, default_steps, monodromy, multipliers_of
from fpucore.floquet.multipliers import DEFAULT_METHOD, METHODS, FloquetResult, spectrum
from fpucore.floquet.reversible import reversor_of
from fpucore.floquet.structured import structured_multipliers

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
    "DEFAULT_METHOD",
    "structured_multipliers",
    "reversor_of",
    "FloquetResult",
    "spectrum",
]
