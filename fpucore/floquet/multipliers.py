"""The Floquet spectrum of one traveling wave (paper §6): all 2N multipliers of the monodromy
matrix (:mod:`fpucore.floquet.monodromy`), the trivial cluster at μ = 1, error bars from the
quartet symmetry and step doubling, and the three-way classification (stable / finite-size
artefact / unstable, :mod:`fpucore.floquet.finite_size`)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fpucore.errors import ParameterError
from fpucore.floquet.decision import Decision, decide
from fpucore.floquet.finite_size import base_at, chain_lengths, min_chain, settled
from fpucore.floquet.spectrum_steps import (
    BaseWave,
    convergence,
    eigen_solve,
    error_bars,
    monodromy_pair,
    prepare,
)
from fpucore.parallel.threads import on_budget
from fpucore.result import Result, status_of

if TYPE_CHECKING:
    from fpucore.wave.driver import WaveResult

METHODS = ("dense", "structured")
# every entry point's default (spectrum, atlas.run, atlas.sweep, fpu floquet, fpu atlas): the
# structured route, 0.17-0.76 x the dense call at N = 500 with the same classifications and max|mu|
# within 5e-14 of dense; its error bars (<= 6e-11) stay far below the excesses that matter (>= 1e-8)
# and its finite-size window is structured whatever the method (benchmarks/floquet_default.py)
DEFAULT_METHOD = "structured"


@dataclass(frozen=True)
class FloquetResult(Result):
    """Floquet spectrum of one traveling wave (paper §6).

    multipliers : (2N,) complex, all eigenvalues of 𝓜 (the two conservation multipliers first).
    max_modulus : max |μ| over all.  max_modulus_away_from_1 : max |μ| outside the trivial cluster.
    trivial : multipliers of the cluster at μ = 1 (the exact conservation pair + those within
    ``trivial_radius``); n_trivial = len(trivial); trivial_split = max |μ − 1| inside it.
    symmetry_error : max relative mismatch of the quartet symmetry μ ↔ 1/μ̄ (see
    :func:`quartet_symmetry_error`); conjugate_error : the same for μ ↔ μ̄ (0 for real 𝓜).
    integrator_error : ‖𝓜_m − 𝓜_2m‖₂ bound (step doubling of the tangent integration).
    error : max(symmetry_error, integrator_error, round-off floor) — the error bar of |μ|
    (method "structured": also structure_error, and the largest multiplier's own bound).
    method : "dense" | "structured"; structure_error : the structured route's bound δλ on
    λ = μ + 1/μ (NaN for dense), see :mod:`fpucore.floquet.structured`.
    route : the eigenvalue route taken, "dense", or for method "structured" "reversible"
    ((N−1)² eigenvalue call, :mod:`fpucore.floquet.reversible`) or "arnoldi" (isotropic Arnoldi).
    excess : max_modulus_away_from_1 − 1; excess_significant : excess > error.
    unstable : multipliers (away from 1) with |μ| − 1 > error.
    growth_rate : V·ln(max_modulus_away_from_1), the growth rate Re λ per unit time (μ = e^{λ/V}).
    decision : the one stability decision (:class:`fpucore.floquet.decision.Decision`): its
    classification "stable" (nothing beyond the error bar) | "finite_size" (absent on a ring of
    the window [N/2, N], or its upper envelope decays with N: an artefact of the finite ring) |
    "unstable" (present on every ring and converged) | "undetermined" (with the computation that
    would decide it, ``decision.next_step``), its headline and its sentence;
    classification, verdict : decision.classification and decision.sentence.
    finite_size_N / finite_size_excess / finite_size_error : (k,) the window's points
    (N_k, max|μ|−1 ± err), N ascending, the requested N last (only N when "stable" or
    ``finite_size=False``); finite_size_exponent p ± finite_size_exponent_error and
    finite_size_prefactor C : the upper envelope max|μ|−1 ≈ C N^−p (NaN when not fitted);
    extrapolated_excess ± extrapolated_excess_error : fit e∞ + C′/N over the window (reported,
    not used by the decision: the 1/N law has curvature);
    finite_size_checked : ≥ MIN_POINTS chain lengths were computed, or an absent excess or a dip
    decided the window early; finite_size_s : wall time (s).
    monodromy_s / check_s / eig_s / elapsed_s : wall times (s).
    """

    multipliers: np.ndarray
    max_modulus: float
    max_modulus_away_from_1: float
    trivial: np.ndarray
    n_trivial: int
    trivial_radius: float
    trivial_split: float
    symmetry_error: float
    conjugate_error: float
    integrator_error: float
    conservation_defect: float
    error: float
    excess: float
    excess_significant: bool
    unstable: np.ndarray
    verdict: str
    method: str
    structure_error: float
    classification: str
    growth_rate: float
    finite_size_N: np.ndarray
    finite_size_excess: np.ndarray
    finite_size_error: np.ndarray
    finite_size_exponent: float
    finite_size_exponent_error: float
    finite_size_prefactor: float
    extrapolated_excess: float
    extrapolated_excess_error: float
    finite_size_checked: bool
    finite_size_s: float
    phonon_gap: float
    N: int
    V: float
    m: int
    K: int
    monodromy_s: float
    check_s: float
    eig_s: float
    elapsed_s: float
    converged: bool
    message: str
    wave: dict = field(default_factory=dict)
    route: str = "dense"
    decision: Decision | None = None

    # finite_size_exponent_error, extrapolated_excess_error, structure_error are NaN where not
    # applicable, so they are not protocol error fields (those are always finite)
    ERROR_FIELDS: ClassVar = ("error", "symmetry_error", "integrator_error", "conservation_defect")
    DERIVED: ClassVar = ("status", "n_unstable")

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def n_unstable(self) -> int:
        return int(self.unstable.size)

    def quartets(self) -> list[np.ndarray]:
        """The instability modes as quartets (μ, μ̄, 1/μ, 1/μ̄) — real pairs (μ, 1/μ) for real μ —
        one per unstable μ with Im μ ≥ 0, partners taken as the nearest multipliers."""
        mu_all = self.multipliers
        groups = []
        for mu in self.unstable:
            if mu.imag < 0:
                continue
            real = abs(mu.imag) <= 1e-12 * abs(mu)
            want = [1 / mu] if real else [np.conj(mu), 1 / np.conj(mu), 1 / mu]
            g = [mu] + [mu_all[int(np.argmin(np.abs(mu_all - x)))] for x in want]
            groups.append(np.array(g))
        return groups


def _wave_summary(r) -> dict:
    keys = (
        "kind",
        "V",
        "N",
        "w_left",
        "w_right",
        "residual",
        "dropped_residual",
        "converged",
        "iterations",
        "amplitude",
        "energy",
        "integrator_error",
        "tail_error",
        "elapsed_s",
        "message",
    )
    out = {k: getattr(r, k) for k in keys if hasattr(r, k)}
    if hasattr(r, "w_plus"):
        out["w_plus"] = r.w_plus
    return out


Points = list[tuple[int, float, float]]  # (N, max|μ| − 1, its error bar) per ring


def finite_size_window(
    base: BaseWave,
    excess: float,
    error: float,
    integrator_error: float,
    finite_size: bool,
    report: Callable[[str, float], None],
) -> tuple[Points, str, list[int]]:
    """The excess max|μ| − 1 ± error at N and, when it exceeds its bar and ``finite_size``, on the
    window of shorter rings in [N/2, N] (structured route, shortest first, stopping once an
    absent excess or a dip has decided it: :mod:`fpucore.floquet.finite_size`).  Returns (the
    points, sorted by N; why the window is incomplete, "" if it is not; the rings whose wave
    could not be rebuilt)."""
    N = base.N
    integ = integrator_error if math.isfinite(integrator_error) else 0.0
    pts = [(N, excess, error)]
    why = "finite_size=False"
    missing: list[int] = []  # rings of the window whose wave could not be rebuilt
    if finite_size and excess > error:
        lengths = chain_lengths(N, min_chain(base.r))
        why = "" if lengths else f"N = {N} is too short for a window of rings in [N/2, N]"
        for k, n_k in enumerate(lengths):
            report("shorter rings", k / len(lengths))
            r_k, reason = base_at(base.r, n_k)
            if r_k is None:
                why = reason
                missing.append(int(n_k))
                continue
            # the shorter rings only supply max|μ| − 1: the structured route (quarter size for
            # the paper's reversible waves; agreement with dense within the error bar tested)
            f_k = spectrum(r_k, m=base.m, check=False, finite_size=False, method="structured")
            pts.append((n_k, f_k.excess, max(f_k.error, integ)))
            if settled(*zip(*sorted(pts))):  # type: ignore[arg-type]  # absent or a dip: the rest cannot change it
                break
    elif finite_size:
        why = ""
    pts.sort()
    return pts, why, missing


@on_budget
def spectrum(
    r: WaveResult,
    m: int | None = None,
    trivial_radius: float | None = None,
    check: bool = True,
    finite_size: bool = True,
    method: str = DEFAULT_METHOD,
    progress: Callable[[str, float], None] | None = None,
) -> FloquetResult:
    """Floquet multipliers of the traveling wave r (paper §6, eq. linear_map), with their error
    bars, the trivial cluster at 1 and the stability decision.

    The steps (:mod:`fpucore.floquet.spectrum_steps`): prepare the base state → the monodromy 𝓜
    (and 𝓜 with 2m steps) → its 2N eigenvalues → error bars and the trivial cluster →
    convergence checks → the finite-size window (:func:`finite_size_window`) → the verdict
    (:func:`fpucore.floquet.decision.decide`).

    Parameters
    ----------
    r : WaveResult or HomogeneousState
        The base state: a wave from ``wave.solve_superkink`` / ``wave.solve_solitary`` (N sites,
        strains ``w`` (N,), rates ``wdot`` (N,), velocity V > 0) or a constant state.
    m : int, optional
        RK steps per period T = 1/V of the tangent integration, in [2, 20000]; default
        max(r.m, h·ω_max ≤ 0.12).
    trivial_radius : float, optional
        Radius (dimensionless, in the μ plane) of the disc around μ = 1 counted as the trivial
        (symmetry) cluster; default min(phonon_gap/10, max(1e-6, 100 √ε)),
        ε = max(error bar, wave residual) (a Jordan block perturbed by ε splits by ~√ε;
        typically 1e-4), phonon_gap = distance from 1 of the nearest continuous-spectrum
        multiplier of the end states (:func:`phonon_gap`).
    check : bool
        Also build 𝓜 with 2m steps and report ‖𝓜_m − 𝓜_2m‖₂ as ``integrator_error``.
    finite_size : bool
        When max|μ| − 1 exceeds the error bar, also compute the spectrum of the same wave on the
        window of five shorter rings in [N/2, N] (structured route, shortest first, stopping
        once an absent excess or a dip has decided it) and decide
        (:mod:`fpucore.floquet.finite_size`).  False: no extra spectra; an excess beyond the
        error bar is then "undetermined" and the verdict says which test was not run.
    method : {"structured", "dense"}
        "structured" (:data:`DEFAULT_METHOD`: the half-size structure-preserving route,
        :mod:`fpucore.floquet.structured`: elliptic multipliers exactly on the circle; its error
        bar comes from the measured non-symplecticity and the dropped isotropy defect,
        ``structure_error``, instead of the quartet symmetry; a base state with a centre of
        reflection, :func:`reversor_of`, takes the quarter-size reversible route,
        :mod:`fpucore.floquet.reversible`) or "dense" (LAPACK dgeev on the deflated (2N−2)²
        block, the reference).  The spectra on the shorter rings always use "structured".
    progress : callable, optional
        ``progress(stage, fraction)`` at each step: ("Floquet spectrum", 0 → 1: the monodromy,
        its check, the eigenvalues), then ("shorter rings", k / number of rings) while the
        finite-size window is computed.

    Returns
    -------
    FloquetResult
        ``multipliers`` (2N,) complex, ``error`` (absolute bar of |μ|), ``decision`` /
        ``classification`` / ``verdict``, wall times in s (see :class:`FloquetResult`).

    Raises
    ------
    ParameterError
        A bad ``method``, ``m`` or ``trivial_radius``, a base state that cannot be integrated
        (see :func:`fpucore.floquet.monodromy.base_state`) or a non-finite monodromy.
    """
    t0 = time.perf_counter()
    report = progress if progress is not None else (lambda stage, x: None)
    if method not in METHODS:
        raise ParameterError("method", method, " | ".join(repr(x) for x in METHODS))
    base = prepare(r, m)
    report("Floquet spectrum", 0.0)
    pair = monodromy_pair(base, check)
    mono, integ = pair.mono, pair.integrator_error
    report("Floquet spectrum", 0.1)  # the monodromy is cheap; the eigenvalues are the cost
    eig = eigen_solve(base, mono, method)
    report("Floquet spectrum", 1.0)
    if not np.all(np.isfinite(eig.mu_rest)):
        raise ParameterError("r", "non-finite monodromy", "a bounded base trajectory")
    bars = error_bars(base, eig, mono, integ, method, trivial_radius)
    converged, msgs = convergence(base, mono, bars)
    max_away, excess, error = bars.max_modulus_away_from_1, bars.excess, bars.error
    growth = base.V * math.log(max_away) if max_away > 0 else math.nan
    tf = time.perf_counter()
    pts, why, missing = finite_size_window(base, excess, error, integ, finite_size, report)
    fs_N = np.array([p[0] for p in pts], dtype=np.int64)
    fs_e = np.array([p[1] for p in pts])
    fs_err = np.array([p[2] for p in pts])
    decision, fit = decide(fs_N, fs_e, fs_err, growth, why, min_chain(r), missing_N=missing)
    finite_s = time.perf_counter() - tf
    msgs.insert(0, decision.sentence)
    return FloquetResult(
        multipliers=bars.mu,
        max_modulus=bars.max_modulus,
        max_modulus_away_from_1=max_away,
        trivial=bars.trivial,
        n_trivial=int(bars.trivial.size),
        trivial_radius=bars.trivial_radius,
        trivial_split=float(np.abs(bars.trivial - 1.0).max(initial=0.0)),
        symmetry_error=bars.symmetry_error,
        conjugate_error=bars.conjugate_error,
        integrator_error=integ,
        conservation_defect=eig.conservation_defect,
        error=error,
        excess=excess,
        excess_significant=bool(excess > error),
        unstable=bars.unstable,
        verdict=decision.sentence,
        method=method,
        structure_error=eig.structure_error,
        classification=decision.classification,
        growth_rate=growth,
        finite_size_N=fs_N,
        finite_size_excess=fs_e,
        finite_size_error=fs_err,
        finite_size_exponent=fit["p"],
        finite_size_exponent_error=fit["p_error"],
        finite_size_prefactor=fit["C"],
        extrapolated_excess=fit["e_inf"],
        extrapolated_excess_error=fit["e_inf_error"],
        finite_size_checked=bool(fit["checked"]),
        decision=decision,
        finite_size_s=finite_s,
        phonon_gap=bars.phonon_gap,
        N=base.N,
        V=base.V,
        m=mono.m,
        K=mono.K,
        monodromy_s=mono.elapsed_s,
        check_s=pair.check_s,
        eig_s=eig.eig_s,
        elapsed_s=time.perf_counter() - t0,
        converged=converged,
        message="; ".join(msgs),
        wave=_wave_summary(r),
        route=eig.route,
    )
