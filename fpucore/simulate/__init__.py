"""Direct simulation of the FPU chain in strain form (paper §6, eq. FPUstrain) with wave tracking.

layout (state vector, end conditions, status codes)  →  observer (events, probes, guard)
→  kernels (first-order RHS, DOP853/DOPRI5, Yoshida)  and  rkn (RKN12/RKN8 steppers)
→  steppers (the METHODS table)  →  config (validation, memory and work estimates before
allocating, output schedule)  →  messages (status text)  →  engine (run_chain: the loop)
→  scenarios (riemann, gaussian, seeded)
→  tracking (fronts and pulses in space–time)
"""

from fpucore.simulate.config import memory_estimate, work_estimate
from fpucore.simulate.scenarios import (
    BOUNDARIES,
    GUARDS,
    MAX_L,
    METHODS,
    SimulationResult,
    TrackedWave,
    gaussian,
    restoring_interval,
    riemann,
    seeded,
    whole_periods,
)

__all__ = [
    "SimulationResult",
    "TrackedWave",
    "riemann",
    "gaussian",
    "seeded",
    "restoring_interval",
    "whole_periods",
    "work_estimate",
    "memory_estimate",
    "BOUNDARIES",
    "GUARDS",
    "METHODS",
    "MAX_L",
]
