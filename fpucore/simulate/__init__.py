"""Direct simulation of the FPU chain in strain form (paper §6, eq. FPUstrain) with wave tracking.

layout (state vector, end conditions, status codes)  →  observer (events, probes, guard)
→  kernels (first-order RHS, DOP853/DOPRI5, Yoshida)  and  rkn (RKN12/RKN8 steppers)
(pwl_rkn: the RKN steppers with event location at a piecewise-linear law's breakpoints)
→  steppers (the METHODS table)  →  config (validation, memory and work estimates before
allocating, output schedule)  →  messages (status text)  →  tracking (fronts and pulses in
space–time)  →  observer_arrays (the observer allocated and finished), chain_energy (H per end
condition)  →  engine (run_chain: the loop)  →  result (SimulationResult)
→  scenarios (riemann, gaussian; the end conditions, methods, guards and budgets of every run)
and seeded (a run seeded with a computed traveling wave, checked against it);
field (extreme_blocks: a field reduced for drawing with its extremes kept)
"""

from fpucore.simulate.config import (
    BOUNDARIES,
    GUARDS,
    MAX_L,
    memory_estimate,
    restoring_interval,
    work_estimate,
)
from fpucore.simulate.field import Blocks, extreme_blocks
from fpucore.simulate.result import SimulationResult, TrackedWave
from fpucore.simulate.scenarios import gaussian, riemann
from fpucore.simulate.seeded import seeded, whole_periods
from fpucore.simulate.steppers import METHODS

__all__ = [
    "SimulationResult",
    "TrackedWave",
    "riemann",
    "gaussian",
    "seeded",
    "extreme_blocks",
    "Blocks",
    "restoring_interval",
    "whole_periods",
    "work_estimate",
    "memory_estimate",
    "BOUNDARIES",
    "GUARDS",
    "METHODS",
    "MAX_L",
]
