"""Direct simulation of the FPU chain in strain form (paper §6, eq. FPUstrain) with wave tracking.

layout (state vector, end conditions, status codes)  →  observer (events, probes, guard)
→  kernels (first-order RHS, DOP853/DOPRI5, Yoshida)  and  rkn (RKN12/RKN8 steppers)
(pwl_pieces: a piecewise-linear law's frozen pieces and breakpoint crossings  →  pwl_rkn: the
RKN steppers with event location at them)  →  steppers (the METHODS table)  →  config
(validation, memory and work estimates before allocating), schedule (the output times)
→  messages (status text)  →  result (SimulationResult, TrackedWave)  →  tracking (fronts and
pulses in space–time)  →  observer_arrays (the observer allocated and finished), chain_energy
(H per end condition)  →  engine (run_chain: the loop)
→  scenarios (riemann, gaussian; the end conditions, methods, guards and budgets of every run)
and seeded (a run seeded with a computed traveling wave, checked against it); impact
(velocity_jump: Riemann data with a velocity jump); trains (track_train: the trains of compact
waves of a zero-modulus law, each wave with its velocity and crest);
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
from fpucore.simulate.impact import velocity_jump
from fpucore.simulate.result import SimulationResult, TrackedWave
from fpucore.simulate.scenarios import gaussian, riemann
from fpucore.simulate.seeded import seeded, whole_periods
from fpucore.simulate.steppers import METHODS
from fpucore.simulate.trains import TrainResult, track_train, train_velocity

__all__ = [
    "SimulationResult",
    "TrackedWave",
    "riemann",
    "gaussian",
    "velocity_jump",
    "track_train",
    "train_velocity",
    "TrainResult",
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
