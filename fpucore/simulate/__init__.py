"""Direct simulation of the FPU chain in strain form (paper §6, eq. FPUstrain) with wave tracking.

layout (state vector, end conditions, status codes)  →  observer (events, probes, guard)
→  kernels (first-order RHS, DOP853/DOPRI5, Yoshida)  and  rkn (RKN12/RKN8 steppers)
→  engine (run_chain: the integration driver)  →  scenarios (riemann, gaussian, seeded)
→  tracking (fronts and pulses in space–time)
"""

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
)

__all__ = [
    "SimulationResult",
    "TrackedWave",
    "riemann",
    "gaussian",
    "seeded",
    "restoring_interval",
    "BOUNDARIES",
    "GUARDS",
    "METHODS",
    "MAX_L",
]
