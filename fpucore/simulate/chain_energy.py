"""The conserved energy H of a chain simulation per end condition (paper §6; the module
docstring of :mod:`fpucore.simulate.scenarios`): its value with the scale its round-off is
measured against, and its formula as the result names it."""

from __future__ import annotations

import math

import numpy as np


def energy_terms(law, y: np.ndarray, L: int, bc: str, fL: float, fR: float):
    """(H, E_scale) for the state y; see the module docstring of scenarios for H per boundary."""
    w = y[:L]
    v = y[L : 2 * L + 1]
    phi = law.phi(w)
    kin = 0.5 * v * v
    if bc == "fixed_particles":
        kin = kin[1:-1]
    terms = [kin.sum(), phi.sum()]
    scale = float(np.abs(kin).sum() + np.abs(phi).sum())
    if bc == "fixed_strain":
        u0 = y[2 * L + 1]
        lin = -fR * w.sum()
        load = (fL - fR) * u0
        terms += [lin, load]
        scale += abs(lin) + abs(load)
    return float(math.fsum(terms)), scale


#: the conserved energy per end condition, as the result names it
ENERGY_NAME = {
    "fixed_particles": "H = sum_{j=1}^{L-1} v_j^2/2 + sum_n Phi(w_n) (end particles at rest)",
    "free": "H = sum_{j=0}^{L} v_j^2/2 + sum_n Phi(w_n)",
    "fixed_strain": (
        "H = sum_{j=0}^{L} v_j^2/2 + sum_n [Phi(w_n) - f(w_right) w_n] "
        "+ (f(w_left) - f(w_right)) u_0 (dead-load potential included)"
    ),
}
