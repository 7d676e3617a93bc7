"""What a traveling wave's strains and strain rates at t = 0 give (paper §5): the particle
velocities (eq. FPUsystem, normalised by the Rankine–Hugoniot condition, eq. RHconds) and the
renormalized energy E_ren^D (eq. Eren_D)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from fpucore.wave import bounds as wb

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw


def particle_velocities(w: np.ndarray, wdot: np.ndarray, V: float, w_left: float) -> np.ndarray:
    """Particle velocities v_n(0) for n = −N/2−1 … N/2−1 (N+1 values) of a traveling wave.

    Derivation: eq. FPUsystem gives ẇ_n = v_n − v_{n−1} at every t, so at t = 0::

        v_n = v_{−N/2−1} + Σ_{k=−N/2}^{n} ẇ_k(0).

    The boundary strain w_{−N/2−1} is held fixed, so particle −N/2−1 moves with the constant
    far-field velocity v_−.  The traveling-wave ansatz u_n(t) = U(n − Vt) gives v = −V U′ and
    w(ξ) = U(ξ) − U(ξ−1), which fixes v only up to a Galilean constant; the Rankine–Hugoniot
    condition (eq. RHconds) −V(w₊ − w₋) = v₊ − v₋ holds for v_± = −V w_±, the normalisation the
    paper's renormalisation (−½V² w_B², eqs. Eren_QC, Eren_D) assumes.  Hence
    v_{−N/2−1} = −V w_left; the other end then returns v_{N/2−1} ≈ −V w_right up to the tail
    error (checked in tests).

    Parameters
    ----------
    w : ndarray, shape (N,)
        Strains w_n(0) of the wave, n = −N/2 … N/2−1 (``WaveResult.w``).
    wdot : ndarray, shape (N,)
        Strain rates ẇ_n(0), per unit time (``WaveResult.wdot``).
    V : float
        Wave velocity, sites per unit time.
    w_left : float
        Boundary strain w_{−N/2−1} (far field behind the wave, w₋ or w_B).

    Returns
    -------
    ndarray, shape (N+1,)
        Particle velocities v_n(0), n = −N/2−1 … N/2−1, normalised by v_{−N/2−1} = −V w_left.
    """
    v = np.empty(w.size + 1)
    v[0] = -V * w_left
    v[1:] = v[0] + np.cumsum(wdot)
    return v


def renormalized_energy(
    law: HardeningSofteningLaw,
    w: np.ndarray,
    wdot: np.ndarray,
    V: float,
    w_left: float,
    w_right: float,
    w_B: float,
) -> float:
    """E_ren^D (eq. Eren_D): Σ_n {½v_n² + ½(Φ(w_n) + Φ(w_{n+1})) − Φ(w_B) − ½V²w_B²} over the
    particles n = −N/2−1 … N/2−1 (particle n sits between springs w_n and w_{n+1}), summed
    relative to the background with the far field beyond the chain added
    (:func:`fpucore.wave.bounds.energy`; solitary waves, w_left = w_right = w_B).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w), with potential Φ.
    w : array_like, shape (N,)
        Strains w_n(0) of the wave.
    wdot : array_like, shape (N,)
        Strain rates ẇ_n(0), per unit time.
    V : float
        Wave velocity, sites per unit time.
    w_left, w_right : float
        Boundary strains (equal to w_B for a solitary wave; ``w_right`` is not used by the sum).
    w_B : float
        Background strain the energy is measured against.

    Returns
    -------
    float
        E_ren^D, nondimensional energy (eq. Eren_D).
    """
    return wb.energy(law, np.asarray(w, float), np.asarray(wdot, float), V, w_B)[0]
