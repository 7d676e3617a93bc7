"""Structure checks of Floquet spectra and the closed-form test case (used by
:mod:`fpucore.floquet`, re-exported there).

* :func:`quartet_symmetry_error` — the measured violation of the Hamiltonian quartet symmetry
  (μ, μ̄, 1/μ, 1/μ̄): the error bar of |μ| − 1;
* :func:`phonon_gap` — how far the continuous spectrum of a background state stays from μ = 1;
* :class:`HomogeneousState` with :func:`homogeneous_multipliers` — the constant state as a
  "traveling wave" of any V, whose spectrum is known in closed form (dispersion relation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.spatial import cKDTree

from fpucore.errors import ParameterError, require_finite, require_in, require_int
from fpucore.law import require_law

if TYPE_CHECKING:
    from fpucore.law.base import HardeningSofteningLaw


def quartet_symmetry_error(mu: np.ndarray) -> tuple[float, float]:
    """Measured violation of the Hamiltonian quartet symmetry of a multiplier set.

    For every μ_i the partner 1/μ̄_i must be in the set; the relative mismatch is
    min_j |μ̄_i μ_j − 1| (= |μ_j − 1/μ̄_i| / |1/μ̄_i|).  For a multiplier on the unit circle the
    partner is itself, so a multiplier pushed off the circle by δ with no partner contributes 2δ:
    this is exactly the error bar of |μ| − 1 for elliptic multipliers.

    Parameters
    ----------
    mu : array_like, shape (M,)
        Multipliers (complex; e.g. M = 2N of a chain of N sites).

    Returns
    -------
    tuple of (float, float)
        (reciprocal_error, conjugate_error): maxima over the set of the two mismatches
        (dimensionless).
    """
    mu = np.asarray(mu, dtype=complex)
    pts = np.column_stack([mu.real, mu.imag])
    tree = cKDTree(pts)
    inv = 1.0 / np.conj(mu)
    _, j = tree.query(np.column_stack([inv.real, inv.imag]))
    rec = np.abs(np.conj(mu) * mu[j] - 1.0)
    _, jc = tree.query(np.column_stack([mu.real, -mu.imag]))
    conj = np.abs(mu[jc] - np.conj(mu))
    return float(rec.max(initial=0.0)), float(conj.max(initial=0.0))


RING_MAX = 10**6  # sites of a homogeneous ring (its multipliers are closed forms, O(N))
V_RANGE = (1e-150, 1e150)  # wave velocities whose period 1/V and phases stay finite


def require_velocity(V) -> float:
    """A wave velocity for a period T = 1/V: finite, in :data:`V_RANGE`."""
    return require_in("V", V, *V_RANGE, "a velocity V > 0 whose period 1/V is a finite double")


def phonon_gap(law: HardeningSofteningLaw, w_bg: float, V: float, N: int) -> float:
    """Smallest |μ − 1| of the continuous-spectrum multipliers of a background state w_bg.

    Homogeneous state, periodic ring of N sites: μ = exp(i(k ± ω(k)T)), k = 2πj/N, j ≠ 0,
    ω = 2√f′(w_bg)|sin(k/2)|, T = 1/V.  The trivial cluster at 1 must be well inside this.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_bg : float
        Background strain.
    V : float
        Wave velocity, sites per unit time (period T = 1/V), in [1e-150, 1e150].
    N : int
        Sites of the ring, in [2, 10⁶].

    Returns
    -------
    float
        min |μ − 1| over j = 1 … N−1 and both signs (dimensionless).

    Raises
    ------
    ParameterError
        When ``law``, ``w_bg``, ``V`` or ``N`` is invalid.
    """
    law, w_bg = require_law(law), require_finite("w_bg", w_bg)
    V, N = require_velocity(V), require_int("N", N, 2, RING_MAX)
    c = math.sqrt(max(float(law.df(w_bg)), 0.0))
    k = 2.0 * np.pi * np.arange(1, N) / N
    om = 2.0 * c * np.abs(np.sin(0.5 * k)) / V
    d = np.concatenate([np.abs(2.0 * np.sin(0.5 * (k + om))), np.abs(2.0 * np.sin(0.5 * (k - om)))])
    return float(d.min())


def homogeneous_multipliers(law: HardeningSofteningLaw, w0: float, V: float, N: int) -> np.ndarray:
    """Exact multipliers of the shifted monodromy for the constant state w_n ≡ w0 (test case).

    With F = f′(w0) = c² the linear chain on the ring is ÿ = c²Δy; Fourier mode y_n = e^{ikn},
    k = 2πj/N (j = 0 … N−1, the periodic BC), solves it with e^{±iωt}, ω² = 4c² sin²(k/2).  The
    shifted map sends y_n(0) to y_{n+1}(T) = e^{ik} e^{±iωT} y_n(0), so μ = e^{i(k ± ωT)},
    T = 1/V.  For k = 0 (ω = 0) both are μ = 1 (the Jordan block of the conserved sums).
    Returns the 2N multipliers (complex), all on |μ| = 1 when f′(w0) > 0.

    f′(w0) < 0 (outside the convex interval): ω = ±iσ, σ = 2√(−f′)|sin(k/2)|, so
    μ = e^{ik} e^{±σT}: a genuine instability, largest at k = π, |μ| = e^{2√(−f′)/V} for every
    even N (growth rate 2√(−f′(w0)) per unit time, independent of the chain length).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w0 : float
        The constant strain; f′(w0) must not be 0.
    V : float
        Wave velocity, sites per unit time (period T = 1/V), in [1e-150, 1e150].
    N : int
        Sites of the ring, in [2, 10⁶].

    Returns
    -------
    ndarray, shape (2N,), complex
        μ = e^{i(k + ωT)} for j = 0 … N−1, then μ = e^{i(k − ωT)} (or e^{ik ± σT} when
        f′(w0) < 0).

    Raises
    ------
    ParameterError
        When ``law``, ``w0``, ``V`` or ``N`` is invalid, or f′(w0) = 0 (degenerate state).
    """
    law, w0 = require_law(law), require_finite("w0", w0)
    V, N = require_velocity(V), require_int("N", N, 2, RING_MAX)
    c2 = float(law.df(w0))
    if c2 == 0.0:
        raise ParameterError("w0", w0, "f'(w0) != 0", "degenerate constant state")
    k = 2.0 * np.pi * np.arange(N) / N
    s = np.abs(np.sin(0.5 * k))
    T = 1.0 / V
    if c2 > 0:
        om = 2.0 * math.sqrt(c2) * s
        return np.concatenate([np.exp(1j * (k + om * T)), np.exp(1j * (k - om * T))])
    sig = 2.0 * math.sqrt(-c2) * s
    return np.concatenate([np.exp(1j * k + sig * T), np.exp(1j * k - sig * T)])


@dataclass(frozen=True)
class HomogeneousState:
    """The constant state w_n ≡ w0 seen as a "traveling wave" of any velocity V (test case with a
    closed-form spectrum, :func:`homogeneous_multipliers`).  Same attributes as a wave result.

    convex=False admits a strain outside the convex interval (f′(w0) < 0, f′ ≠ 0): the test case
    of a genuine instability with a known growth rate 2√(−f′(w0))."""

    law: object
    w0: float
    V: float
    N: int
    kind: str = "homogeneous"
    convex: bool = True

    def __post_init__(self):
        require_law(self.law)
        if self.kind != "homogeneous":
            raise ParameterError("kind", self.kind, "'homogeneous' (the kind of a constant state)")
        if self.convex:
            self.law.require_convex("w0", self.w0)
        elif not (math.isfinite(self.w0) and float(self.law.df(self.w0)) != 0.0):
            raise ParameterError("w0", self.w0, "finite with f'(w0) != 0")
        if not (self.V > 0 and math.isfinite(self.V)):
            raise ParameterError("V", self.V, "V > 0")
        if not (isinstance(self.N, (int, np.integer)) and self.N >= 4 and self.N % 2 == 0):
            raise ParameterError("N", self.N, "an even integer >= 4")

    @property
    def w(self) -> np.ndarray:
        return np.full(self.N, float(self.w0))

    @property
    def wdot(self) -> np.ndarray:
        return np.zeros(self.N)

    @property
    def w_left(self) -> float:
        return float(self.w0)

    @property
    def w_right(self) -> float:
        return float(self.w0)
