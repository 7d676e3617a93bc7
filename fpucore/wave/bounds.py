"""A-posteriori error bounds of a discrete traveling wave against the exact wave of the infinite
chain (paper §5, eqs. nonlin_system, fixedBCs, Eren_D), and E_ren^D summed so that it does not
degrade with N.

Let x be the computed state (w_n(0), ẇ_n(0)) on N sites, F_m the equations of eq. nonlin_system
with m RK steps per period, J their Jacobian (banded LU kept by Newton) and x* the exact infinite
chain's wave restricted to the N sites (same pinning).  To first order

    x − x*  ≈  J⁻¹ F_2m(x)                    Newton stopping point + RK error of the period map
              + J⁻¹ (F_2m − F_m)(x) / 2^p      RK error left in the 2m map (order p = 8)
              + J⁻¹ n                          round-off n in the evaluated F
              + J⁻¹ c_L τ_L + J⁻¹ c_R τ_R      truncation by finite N

where c_{L,R} = ∂F/∂w_{left,right} (one-sided differences of the boundary strain) and τ_{L,R} the
deviation of the exact wave from its far-field state at the chain's ends, extrapolated from the
computed tail with the discrete decay rate λ (:func:`fpucore.wave.tails.decay_rate`).  The first
two terms are *signed* estimates (sharp).  Round-off is *sampled*, not bounded by norms: the
worst case ‖P_w J⁻¹ diag(n)‖∞ (Hager's estimator with the calibrated row levels of
:meth:`WaveSystem.roundoff_rows`) was measured 100–10⁴× above the true error, because the real
round-off does not align with J's weak directions.  Three realisations of it are solved with J:
the second difference F(x+η) − 2F(x) + F(x−η) (the random part) and F_2m − F_{2m+k}, k = 1, 2
(maps of the same accuracy rounded differently: the systematic part, e.g. the rounded RK
increments, which the second difference cancels); the largest, × NOISE_FACTOR, is the round-off
term.  The functionals (amplitude = w at n = 0, energy) use one transposed solve each,
gᵀJ⁻¹b = (J⁻ᵀg)ᵀb.  SAFETY covers the first-order linearisation and the chord factorisation.
Measured against an 80-bit reference (tests/wave/test_error_bounds.py): bound/true error 1–85
over the extreme suite.  Cost: three extra 2m period maps (one shared with the step-doubling
integrator error), four m-step maps and ~8 banded triangular solves — no new Jacobian.

E_ren^D is summed relative to the background: with v_p = −V w_B + u_p (u_p = Σ_{k≤p} ẇ_k, in long
double) the summand ½v² − ½V²w_B² is −V w_B u + ½u², and Φ(w) − Φ(w_B) is integrated by 3-point
Gauss–Legendre on [w_B, w] (exact for the cubic law's quartic Φ), so no term is a difference of
large numbers; the terms are added exactly (math.fsum); the far field beyond the chain is added
as the geometric tail of the summand at rate e^{−λ} and counted in full in the error bar.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import replace as _replace

import numpy as np

from fpucore.wave import tails as wt
from fpucore.wave.setup import strain_scale
from fpucore.wave.system import WaveSystem, solve_with

SAFETY = 2.0  # on the first-order terms (linearisation, chord Jacobian, tail extrapolation)
NOISE_FACTOR = 4.0  # a sampled round-off effect, to its likely largest realisation
_EPS = np.finfo(float).eps
_GL_X = np.array([0.5 - 0.5 * math.sqrt(0.6), 0.5, 0.5 + 0.5 * math.sqrt(0.6)])  # on [0, 1]
_GL_W = np.array([5.0, 8.0, 5.0]) / 18.0


@dataclass(frozen=True)
class WaveBounds:
    """Bounds (absolute) of one wave; NaN where the quantity is not defined.

    profile : max_n |w_n(0) − w_n*(0)|.  amplitude : |Δ amplitude| (solitary waves; 0 for
    superkinks, whose amplitude |w₋ − w₊| is exact).  energy : |Δ E_ren^D| (solitary waves).
    energy_value : E_ren^D summed as in the module doc (NaN for superkinks).
    integrator_error : step-doubling max|Φ_m − Φ_2m| (w and ẇ).  newton, roundoff, truncation :
    the profile bound's parts (for the record and the tests)."""

    profile: float
    amplitude: float
    energy: float
    energy_value: float
    integrator_error: float
    newton: float
    roundoff: float
    truncation: float


# =============================================================================== energy
def phi_increment(law, w_B: float, w: np.ndarray) -> np.ndarray:
    """Φ(w) − Φ(w_B) = ∫_{w_B}^{w} f, 3-point Gauss–Legendre (exact for f of degree ≤ 5); a
    smooth law (``law.interval``) integrates its represented f exactly (``law.phi``)."""
    if getattr(law, "interval", None):
        w = np.asarray(w, dtype=float)
        return law.phi(w) - law.phi(np.float64(w_B))
    d = np.asarray(w, dtype=float) - w_B
    f = law.f(w_B + d[:, None] * _GL_X[None, :])
    return d * (f @ _GL_W)


def energy_terms(law, w, wdot, V, w_B):
    """Summand of E_ren^D per particle p = −N/2−1 … N/2−1 (N+1 values), background-relative, and
    the particle-velocity deviations u_p = v_p + V w_B (float64 from a long-double prefix sum)."""
    u = np.zeros(w.size + 1)
    u[1:] = np.cumsum(np.asarray(wdot, dtype=np.longdouble)).astype(float)
    dphi = np.concatenate([[0.0], phi_increment(law, w_B, w), [0.0]])  # boundary springs = w_B
    terms = -V * w_B * u + 0.5 * u * u + 0.5 * (dphi[:-1] + dphi[1:])
    return terms, u


def far_field(law, terms: np.ndarray, V: float, w_B: float, k: int = 3) -> float:
    """Sum of the summand beyond both ends of the chain: geometric continuation, at the discrete
    decay rate λ(w_B, V), of the term k particles in from each end."""
    lam = wt.decay_rate(law, w_B, V)
    if not math.isfinite(lam) or terms.size < 2 * k + 2:
        return 0.0
    r = math.exp(-lam)
    return (terms[k] + terms[-1 - k]) * r ** (k + 1) / (1.0 - r)


def energy(law, w, wdot, V, w_B) -> tuple[float, float]:
    """(E_ren^D including the far field, bound on the summation's own error: the far-field term
    counted in full plus rounding of the summands)."""
    terms, u = energy_terms(law, w, wdot, V, w_B)
    ff = far_field(law, terms, V, w_B)
    scale = np.abs(V * w_B * u) + u * u + np.abs(terms)
    rounding = 8.0 * _EPS * float(math.fsum(scale))
    return float(math.fsum(terms)) + ff, abs(ff) + rounding


def energy_gradient(law, w, wdot, V, w_B) -> np.ndarray:
    """∂E_ren^D/∂x (2N, interleaved): ∂/∂w_n = f(w_n) (each spring is shared by two particles
    with weight ½); ∂/∂ẇ_k = Σ_{p ≥ k} v_p (ẇ_k enters every particle velocity to its right)."""
    _, u = energy_terms(law, w, wdot, V, w_B)
    v = u - V * w_B
    g = np.empty(2 * w.size)
    g[0::2] = law.f(w)
    g[1::2] = np.cumsum(v[::-1])[::-1][1:]  # suffix sums over particles p ≥ k + 1 (array index)
    return g


# =============================================================================== profile
def tail_deviation(law, w, wd, w_inf, V, side: int) -> float:
    """τ: deviation of the exact wave from w_∞ at the boundary spring, extrapolated from the
    computed tail (sites 1–3 in from the end, away from the clamp) at rate λ, and from the rates
    |ẇ| = Vλ|w − w_∞| of a pure exponential tail."""
    lam = wt.decay_rate(law, w_inf, V)
    idx = np.arange(4) if side < 0 else w.size - 1 - np.arange(4)
    d = np.abs(w[idx] - w_inf)
    if not math.isfinite(lam) or lam <= 0:
        return float(np.max(d) + np.max(np.abs(wd[idx])) / V)
    k = np.arange(4)
    ext = np.max(d[1:] * np.exp(-lam * (k[1:] + 1)))
    ext_rate = np.max(np.abs(wd[idx]) / (V * lam) * np.exp(-lam * (k + 1)))
    return float(max(ext, ext_rate, d[0] * math.exp(-lam)))


def embedded(b: WaveBounds, law, w, wd, V: float, w_left: float, w_right: float) -> WaveBounds:
    """Bounds of a wave solved on fewer sites (w, wd: that solution) and padded with its
    background states to a longer chain: on the padded sites the exact wave lies within the
    tail deviation τ at the short chain's ends (it decays further outward), elsewhere the short
    chain's bounds hold unchanged (they already include its truncation by finite N)."""
    tau = max(tail_deviation(law, w, wd, w_left, V, -1), tail_deviation(law, w, wd, w_right, V, 1))
    return _replace(b, profile=max(b.profile, SAFETY * tau), truncation=max(b.truncation, tau))


def noise_sample(S: WaveSystem, x: np.ndarray, F: np.ndarray, seed: int = 12345) -> np.ndarray:
    """One realisation of the round-off in the evaluated F at x (2N, row order): the second
    difference (F(x+η) − 2F(x) + F(x−η))/√6 cancels the linear part exactly and the quadratic
    part is ~|η|²|F″| ≈ 1e-18 (|η| ≈ 1e-9 in strain units, random signs, fixed seed), so what
    remains are three independent round-off patterns (variance 6σ²)."""
    s = strain_scale(S.w_left, S.w_right)
    rng = np.random.default_rng(seed)
    eta = 1e-9 * s * rng.choice([-1.0, 1.0], size=x.size)
    eta[1::2] *= S.V  # ẇ in strain per period time
    Fp, _ = S.residual(x + eta)
    Fm, _ = S.residual(x - eta)
    return (Fp - 2.0 * F + Fm) / math.sqrt(6.0)


def _boundary_column(S: WaveSystem, x: np.ndarray, F: np.ndarray, side: str) -> np.ndarray:
    """∂F/∂w_left or ∂F/∂w_right by a one-sided difference (relative error ~1e-7: enough for a
    bound)."""
    w0 = S.w_left if side == "left" else S.w_right
    h = 1e-7 * max(1.0, abs(w0))
    Sp = _replace(S, **{f"w_{side}": w0 + h})  # type: ignore[arg-type]
    Fp, _ = Sp.residual(x)
    return (Fp - F) / h


def representation_residuals(S: WaveSystem) -> list[np.ndarray]:
    """Residual perturbations of the size the law's representation error can cause (a smooth
    law, ``law.representation_error``; else []): over one period T = 1/V, |δf| ≤ e_f changes
    ẇ_n by ≤ 4 e_f T and w_n by ≤ 2 e_f T² (eq. FPUstrain).  Three sign patterns (all +,
    alternating, random): their effects through J⁻¹ are sampled like the round-off."""
    rep = getattr(S.law, "representation_error", None)
    if rep is None:
        return []
    T = 1.0 / S.V
    base = np.empty(2 * S.N)
    base[0::2] = 2.0 * rep.f * T * T
    base[1::2] = 4.0 * rep.f * T
    rng = np.random.default_rng(2024)
    alt = np.repeat(np.where(np.arange(S.N) % 2 == 0, 1.0, -1.0), 2)
    return [base, base * alt, base * rng.choice([-1.0, 1.0], size=2 * S.N)]


def error_bounds(S: WaveSystem, x: np.ndarray, fact: tuple, solitary: bool, order: int = 8):
    """:class:`WaveBounds` of the wave x (2N interleaved) solved on system S with factorisation
    ``fact`` (:func:`fpucore.wave.system.solve_with`); ``solitary`` selects amplitude/energy."""
    N, law, V = S.N, S.law, S.V
    w, wd = x[0::2], x[1::2]
    r_m = S.integrate(x)
    r_2m = S.integrate(x, m=2 * S.m)
    ierr = float(max(np.max(np.abs(r_m.w - r_2m.w)), np.max(np.abs(r_m.wd - r_2m.wd))))
    F_m, _ = S.residual_from(x, r_m)
    F_2m, _ = S.residual_from(x, r_2m)
    delta = solve_with(fact, F_2m)  # x − x*_2m to first order
    rest = np.abs(solve_with(fact, F_2m - F_m)) / 2.0**order  # RK error left in the 2m map
    noise = noise_sample(S, x, F_m)
    rho = solve_with(fact, noise)  # a realisation of the round-off's effect on x
    # maps of the same accuracy, differently rounded: their differences sample the round-off
    # including its systematic part (rounded RK increments), which the second difference misses
    model = [F_2m - S.residual(x, m=2 * S.m + k)[0] for k in (1, 2)]
    rho_model = [solve_with(fact, n_k) for n_k in model]
    tau_L = tail_deviation(law, w, wd, S.w_left, V, -1)
    tau_R = tail_deviation(law, w, wd, S.w_right, V, 1)
    c_L = _boundary_column(S, x, F_m, "left")
    c_R = _boundary_column(S, x, F_m, "right")
    t_L, t_R = solve_with(fact, c_L), solve_with(fact, c_R)
    trunc = np.abs(t_L[0::2]) * tau_L + np.abs(t_R[0::2]) * tau_R
    newton_w = np.abs(delta[0::2]) + rest[0::2]
    roundoff = NOISE_FACTOR * max(float(np.max(np.abs(r[0::2]))) for r in [rho, *rho_model])
    reps = representation_residuals(S)  # a smooth law: the kernels' f differs from the exact f
    rep_w = max((float(np.max(np.abs(solve_with(fact, b)[0::2]))) for b in reps), default=0.0)
    roundoff += NOISE_FACTOR * rep_w
    profile = SAFETY * (float(np.max(newton_w + trunc)) + roundoff)
    if not solitary:
        return WaveBounds(
            profile,
            0.0,
            math.nan,
            math.nan,
            ierr,
            float(np.max(newton_w)),
            roundoff,
            float(np.max(trunc)),
        )
    c = N // 2
    e_c = np.zeros(2 * N)
    e_c[2 * c] = 1.0
    z_c = solve_with(fact, e_c, trans=1)
    amp_noise = max(abs(float(z_c @ n_k)) for n_k in [noise, *model, *reps])
    amp = SAFETY * (newton_w[c] + trunc[c] + NOISE_FACTOR * amp_noise)
    w_B = S.w_left
    E, e_sum = energy(law, w, wd, V, w_B)
    g = energy_gradient(law, w, wd, V, w_B)
    z = solve_with(fact, g, trans=1)  # J⁻ᵀg: gᵀJ⁻¹b = zᵀb
    dE = (
        abs(float(z @ F_2m))
        + float(np.abs(z) @ (np.abs(F_2m - F_m) / 2.0**order))
        + NOISE_FACTOR * max(abs(float(z @ n_k)) for n_k in [noise, *model, *reps])
        + abs(float(z @ c_L)) * tau_L
        + abs(float(z @ c_R)) * tau_R
    )
    rep = getattr(law, "representation_error", None)
    if rep is not None:  # Φ of the represented f: |ΔΦ(w) − ΔΦ(w_B)| ≤ e_f |w − w_B| per spring
        dE += float(np.sum(np.abs(w - w_B))) * rep.f
    return WaveBounds(
        profile,
        amp,
        SAFETY * dE + e_sum,
        E,
        ierr,
        float(np.max(newton_w)),
        roundoff,
        float(np.max(trunc)),
    )
