"""The steps of one Floquet spectrum (:func:`fpucore.floquet.spectrum`), each a small typed
function: prepare (the base state and the step count, read once from the wave) → monodromy
(𝓜 with m steps, and with 2m for the integrator's error) → eigen-solve (all 2N multipliers,
dense or structured) → error bars (the bar of |μ|, the trivial cluster at 1, the unstable
multipliers) → convergence (the checks a spectrum must pass, in words).  The finite-size window
and the verdict that follow live with :func:`~fpucore.floquet.spectrum` (the window computes
spectra of shorter rings)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from fpucore.errors import ParameterError, require_finite
from fpucore.floquet.checks import phonon_gap, quartet_symmetry_error
from fpucore.floquet.monodromy import (
    MAX_STEPS,
    Monodromy,
    base_state,
    default_steps,
    monodromy,
    multipliers_of,
)
from fpucore.floquet.reversible import reversor_of
from fpucore.floquet.structured import structured_multipliers
from fpucore.law.base import HardeningSofteningLaw


@dataclass(frozen=True)
class BaseWave:
    """The base state of a spectrum, read once from the wave result ``r`` (a
    :class:`~fpucore.wave.driver.WaveResult` or a :class:`~fpucore.floquet.HomogeneousState`,
    which has no step count, residual or convergence flag: 0, 0.0 and True stand for them).

    r : the result itself (re-integrated, rebuilt on shorter rings).  law : its force law.
    w, wd : (N,) strains and strain rates at t = 0.  V : velocity.  N : sites (even).
    m : RK steps per period of the tangent integration.  residual : the wave's residual (the
    scale of the trivial cluster's split).  converged : the wave passed its own check."""

    r: Any
    law: HardeningSofteningLaw
    w: np.ndarray
    wd: np.ndarray
    V: float
    N: int
    m: int
    residual: float
    converged: bool


def prepare(r: Any, m: int | None) -> BaseWave:
    """The base state of ``r`` (refused with the attribute that is wrong, see
    :func:`~fpucore.floquet.monodromy.base_state`) and the step count: ``m``, or
    max(r.m, h·ω_max ≤ 0.12) (:func:`~fpucore.floquet.monodromy.default_steps`)."""
    law, w, wd, V, N, _, _ = base_state(r)
    if m is None:
        m = max(int(getattr(r, "m", 0) or 0), default_steps(law, V))
    elif not (isinstance(m, (int, np.integer)) and 2 <= m <= MAX_STEPS):
        raise ParameterError("m", m, f"an integer in [2, {MAX_STEPS}]", "RK steps per period")
    residual = float(getattr(r, "residual", 0.0) or 0.0)
    return BaseWave(r, law, w, wd, V, N, int(m), residual, bool(getattr(r, "converged", True)))


@dataclass(frozen=True)
class Monodromies:
    """𝓜 with m steps (``mono``) and, with the check, the bound ``integrator_error`` ≥
    ‖𝓜_m − 𝓜_2m‖₂ (NaN without it) and the check's wall time ``check_s`` (s)."""

    mono: Monodromy
    integrator_error: float
    check_s: float


def monodromy_pair(base: BaseWave, check: bool) -> Monodromies:
    """𝓜 of ``base`` with base.m steps and, if ``check``, with 2m steps: their difference bounds
    the tangent integration's error (step doubling)."""
    mono = monodromy(base.r, base.m)
    check_s, integ = 0.0, math.nan
    if check:
        tc = time.perf_counter()
        mono2 = monodromy(base.r, 2 * base.m)
        d = np.abs(mono.matrix - mono2.matrix)
        integ = float(math.sqrt(d.sum(axis=0).max() * d.sum(axis=1).max()))  # ≥ ‖δ𝓜‖₂
        check_s = time.perf_counter() - tc
    return Monodromies(mono, integ, check_s)


@dataclass(frozen=True)
class Eigen:
    """All multipliers of 𝓜: mu_rest (2N−2,) complex (outside the conservation block), mu_sums
    (2,) (the conservation pair, exactly 1), conservation_defect (round-off coupling of the
    sums), mu_error (2N−2,) per-multiplier bounds (zeros for dense), structure_error (the
    structured route's bound on λ = μ + 1/μ; NaN for dense), route ("dense" | "reversible" |
    "arnoldi"), eig_s (wall time, s)."""

    mu_rest: np.ndarray
    mu_sums: np.ndarray
    conservation_defect: float
    mu_error: np.ndarray
    structure_error: float
    route: str
    eig_s: float


def eigen_solve(base: BaseWave, mono: Monodromy, method: str) -> Eigen:
    """The multipliers of ``mono`` by ``method`` ("dense": LAPACK on the deflated block;
    "structured": :func:`~fpucore.floquet.structured.structured_multipliers`, the quarter-size
    reversible route when the base state has a reversor)."""
    te = time.perf_counter()
    N = base.N
    if method == "dense":
        mu_rest, mu_sums, defect = multipliers_of(mono.matrix, N)
        mu_err, struct, route = np.zeros(2 * N - 2), math.nan, "dense"
    else:
        c = reversor_of(base.law, base.w, base.wd)
        mu_rest, mu_sums, defect, info = structured_multipliers(mono.matrix, N, mono.K, reversor=c)
        mu_err, struct, route = info["mu_error"], float(info["lam_error"]), info["route"]
    eig_s = time.perf_counter() - te
    return Eigen(mu_rest, mu_sums, defect, mu_err, struct, route, eig_s)


@dataclass(frozen=True)
class ErrorBars:
    """The spectrum's error bars and its partition.

    mu : (2N,) all multipliers (the conservation pair first).  symmetry_error, conjugate_error :
    quartet and conjugate mismatches (:func:`~fpucore.floquet.checks.quartet_symmetry_error`).
    error : the error bar of the largest multiplier away from 1 (its own bound on the structured
    route), else the spectrum's.  phonon_gap : nearest continuous-spectrum multiplier to 1 of the
    end states.  split_scale : √max(error, residual), the split of a perturbed Jordan block at 1.
    trivial_radius : the cluster's radius; trivial : its multipliers (conservation pair first).
    away : the multipliers outside it.  max_modulus, max_modulus_away_from_1 : max |μ| over all
    / over ``away``; excess = max_modulus_away_from_1 − 1.  unstable : ``away`` with
    |μ| − 1 beyond its bar, largest first."""

    mu: np.ndarray
    symmetry_error: float
    conjugate_error: float
    error: float
    phonon_gap: float
    split_scale: float
    trivial_radius: float
    trivial: np.ndarray
    away: np.ndarray
    max_modulus: float
    max_modulus_away_from_1: float
    excess: float
    unstable: np.ndarray


def _background_states(base: BaseWave) -> list[float]:
    """Strains the chain tends to at its ends (where the continuous spectrum lives)."""
    return [float(base.w[0]), float(base.w[-1])]


def error_bars(
    base: BaseWave,
    eig: Eigen,
    mono: Monodromy,
    integrator_error: float,
    method: str,
    trivial_radius: float | None,
) -> ErrorBars:
    """The error bar max(quartet symmetry, integrator error, round-off floor 64 ε ‖𝓜‖₁; the
    structured route's λ bound), the trivial cluster (radius ``trivial_radius``, default
    min(phonon_gap / 10, max(1e-6, 100 √ε)), ε = max(error bar, residual)) and the multipliers
    away from it, with their own bars."""
    mu_rest, mu_sums = eig.mu_rest, eig.mu_sums
    mu = np.concatenate([mu_sums, mu_rest])
    sym, conj = quartet_symmetry_error(mu)
    norm = float(np.abs(mono.matrix).sum(axis=0).max())
    floor = 64.0 * np.finfo(float).eps * norm
    integ = integrator_error
    error = max(sym, integ if math.isfinite(integ) else 0.0, floor)
    if method == "structured":  # λ-level bound; per-multiplier bounds mu_error below
        error = max(error, eig.structure_error)
    gap = min(phonon_gap(base.law, wb, base.V, base.N) for wb in _background_states(base))
    # a Jordan block at 1 perturbed by ε splits by ~√ε: ε = the error bar or the wave's residual
    split_scale = math.sqrt(max(error, base.residual))
    if trivial_radius is None:
        trivial_radius = min(0.1 * gap, max(1e-6, 100.0 * split_scale))
    trivial_radius = require_finite("trivial_radius", trivial_radius)
    if not trivial_radius >= 0:
        raise ParameterError("trivial_radius", trivial_radius, "a radius >= 0")
    near = np.abs(mu_rest - 1.0) < trivial_radius
    trivial = np.concatenate([mu_sums, mu_rest[near]])
    away = mu_rest[~near]
    err_away = np.maximum(eig.mu_error[~near], error)
    max_away = float(np.abs(away).max(initial=0.0))
    if away.size:  # the error bar of the largest multiplier (structured: its own bound)
        error = float(err_away[int(np.argmax(np.abs(away)))])
    unstable = away[np.abs(away) - 1.0 > err_away]
    unstable = unstable[np.argsort(-np.abs(unstable))]
    return ErrorBars(
        mu,
        sym,
        conj,
        error,
        gap,
        split_scale,
        trivial_radius,
        trivial,
        away,
        float(np.abs(mu).max()),
        max_away,
        max_away - 1.0,
        unstable,
    )


def convergence(base: BaseWave, mono: Monodromy, bars: ErrorBars) -> tuple[bool, list[str]]:
    """(converged, messages): the checks a spectrum must pass — a converged base wave, a tangent
    window that truncates nothing, a trivial cluster well inside the phonon gap, the quartet
    symmetry — each failure said in words (an odd cluster is said, not failed)."""
    msgs = []
    converged = True
    if not base.converged:
        converged = False
        msgs.append("the base wave did not converge: its spectrum describes no traveling wave")
    if mono.truncation > 1e-14:
        converged = False
        msgs.append(f"tangent window truncation {mono.truncation:.1e} (increase K)")
    gap, split_scale, radius = bars.phonon_gap, bars.split_scale, bars.trivial_radius
    if radius > 0.5 * gap or gap < 10.0 * split_scale:
        converged = False
        msgs.append(
            f"phonon gap {gap:.1e} (nearest continuous-spectrum multiplier to 1) is not well "
            f"outside the round-off split {split_scale:.0e} of the trivial cluster / its radius "
            f"{radius:.0e}: cluster and continuous spectrum overlap (increase N or move "
            "V away from the sound speed)"
        )
    if (bars.trivial.size % 2) != 0:
        msgs.append(
            f"odd trivial cluster size {bars.trivial.size}: radius {radius:.1e} cuts a pair"
        )
    if bars.symmetry_error > 1e-6:
        converged = False
        msgs.append(f"quartet symmetry violated by {bars.symmetry_error:.1e} (increase m)")
    return converged, msgs
