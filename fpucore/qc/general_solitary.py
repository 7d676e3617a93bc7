"""QC solitary waves of any hardening–softening law (paper §3, eqs. wB, TW_QC_gen3, Eren_QC):
w_B, w_M and w_T by bracketed roots, the profile w(ξ) by quadrature after the substitution
w = w_B + (w_M − w_B) sech²u, and E_ren^QC with its error bound (the method:
:mod:`fpucore.qc.general`)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval
from fpucore.law import HardeningSofteningLaw
from fpucore.qc.closed_forms import QCSolitary, first_integral_residual, require_V
from fpucore.qc.general_map import ProfileMap, sech_squared
from fpucore.qc.general_rayleigh import rayleigh_roots_at
from fpucore.qc.general_roots import (
    EPS,
    GL_HI,
    GL_LO,
    SECH2_HALF,
    U_MAX,
    bracketed_root,
    first_integral_J,
    gauss_legendre01,
    inner_rule,
    is_smooth,
    march_outward,
    scalar_J,
)
from fpucore.qc.general_speeds import speeds


@dataclass(frozen=True)
class QCSolitaryGeneral(QCSolitary):
    """QC solitary wave of any law: the fields of :class:`fpucore.qc.QCSolitary` plus error bars.

    ``w_M`` the turning point (w(0) = w_M), ``w_T`` the next zero of G_B beyond the other saddle
    (the w_T of eq. w_T_M for the cubic; NaN if none), ``gamma`` = √(12(V² − f′(w_B)))/V the
    decay rate (the γ of eq. SWsoln_cubic).  ``energy`` is E_ren^QC (eq. Eren_QC) by quadrature,
    ``energy_error`` its bound (quadrature order difference + tail + propagated root errors +
    round-off amplified near the ends of the velocity interval).
    """

    w_B_error: float = math.nan
    w_M_error: float = math.nan
    V_SK_error: float = math.nan
    xi_error: float = math.nan
    table: object = field(default=None, repr=False, compare=False)  # ξ(u) table

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = QCSolitary.ERROR_FIELDS + (
        "w_B_error",
        "w_M_error",
        "V_SK_error",
        "xi_error",
    )
    EXCLUDE: ClassVar[tuple[str, ...]] = QCSolitary.EXCLUDE + ("table",)

    @property
    def amplitude_error(self) -> float:
        return self.w_B_error + self.w_M_error

    def profile(self, xi):
        xi = np.asarray(xi, float)
        u = self.table.s_of_scalar(abs(float(xi))) if xi.ndim == 0 else self.table.s_of(np.abs(xi))
        return self.w_B + (self.w_M - self.w_B) * sech_squared(u)

    def dprofile(self, xi):
        """w′(ξ) = sign(ξ) (dw/du)/(dξ/du), dw/du = −2 dM sech²u tanh u."""
        xi = np.asarray(xi, float)
        u = self.table.s_of(np.abs(xi))
        dw = -2.0 * (self.w_M - self.w_B) * sech_squared(u) * np.tanh(u)
        return np.sign(xi) * dw / (self.table.scale * self.table.g(u))


def _sw_g(law, wB: float, wM: float, V2: float):
    """g(u) = |R̃(w(u))|^(−1/2), w = w_B + dM sech²u, −G_B = (w−w_B)²(w_M−w) R̃:
    near w_B (sech²u < ½) R̃ = −J(w_B, d)/(dM − d); near w_M R̃ = ∫₀¹ h_B(w_M + τ(w − w_M)) dτ/d²
    (G_B(w_M) = 0, h_B = G_B′ = f − f(w_B) − V²(· − w_B))."""
    dM = wM - wB
    fB = float(law.f(wB))
    t, wt = inner_rule(law)

    def g(u):
        u = np.asarray(u, float)
        sech2 = sech_squared(u)
        d = dM * sech2
        gap = dM * np.tanh(u) ** 2  # dM − d
        s = wM - gap[..., None] * t  # w_M + τ (w − w_M)
        hB = law.f(s) - fB - V2 * (s - wB)  # |s − w_B| ≥ |dM|/2 here: mild cancellation
        with np.errstate(invalid="ignore", divide="ignore"):  # each form is used where it is finite
            R_far = -first_integral_J(law, wB, d, V2) / gap
            R_near = np.sum(hB * wt, axis=-1) / (d * d)
            R = np.where(np.abs(u) > SECH2_HALF, R_far, R_near)
        return 1.0 / np.sqrt(np.abs(R))

    return g


def _bracket(law: HardeningSofteningLaw, w_plus: float, V: float):
    """The checks of :func:`solitary` before any profile work (its refusals, word for word):
    (speeds, interval, w_B, its error, w_near, the other saddle, w_far's error, J(w)); w_M is
    the root of J in (w_near, other), so the wave's side of w_B is that of ``other``."""
    sp = speeds(law, w_plus)
    w_plus, cp, vsk, cm = sp.w_plus, sp.c_plus, sp.V_SK, sp.c_minus
    valid = f"{fmt_interval(cp, vsk)} or {fmt_interval(vsk, cm)}"
    if V == vsk:
        raise ParameterError("V", V, valid, "V = V_SK is the superkink itself")
    V2 = V * V
    w_near, w_far, _, far_err = rayleigh_roots_at(law, w_plus, V)
    if cp < V < vsk:
        interval, wB, other, wB_err = "below", w_plus, w_far, 0.0
    elif vsk < V < cm:
        interval, wB, other, wB_err = "above", w_far, w_plus, far_err
    else:
        raise ParameterError("V", V, valid, f"solitary-wave velocities for w_plus={w_plus:.10g}")
    if not (math.isfinite(w_near) and math.isfinite(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    Jw = lambda w: scalar_J(law, wB, w - wB, V2)  # noqa: E731
    if not (Jw(w_near) < 0 < Jw(other)):
        raise ParameterError("V", V, valid, "too close to an end of the interval to resolve")
    return sp, interval, wB, wB_err, w_near, other, far_err, Jw


def solitary_kind(law: HardeningSofteningLaw, w_plus: float, V: float) -> str:
    """ "tensile" or "compressive": the :attr:`~fpucore.qc.QCSolitary.kind` of
    ``solitary(law, w_plus, V)`` and the same refusals, without its profile, energy and check
    (near a sonic end those cost up to a second for a smooth law; this costs a few root
    evaluations).  w_M lies in the bracket (w_near, other), on ``other``'s side of w_B."""
    V = require_V(V)
    _, _, wB, _, _, other, _, _ = _bracket(law, w_plus, V)
    return "tensile" if other > wB else "compressive"


def solitary(
    law: HardeningSofteningLaw, w_plus: float, V: float, check: bool = True
) -> QCSolitaryGeneral:
    """QC solitary wave for the state w₊ ahead of the associated superkink, velocity V (eq. wB):
    V ∈ (c₊, V_SK) → w_B = w₊; V ∈ (V_SK, c₋) → w_B = w_S(V).  ``check=False`` skips the
    first-integral check on the profile (a third of the cost; families need only E and w_M):
    ``first_integral_residual`` is then NaN."""
    t0 = time.perf_counter()
    V = require_V(V)
    sp, interval, wB, wB_err, w_near, other, far_err, Jw = _bracket(law, w_plus, V)
    w_plus, cp, vsk, cm = sp.w_plus, sp.c_plus, sp.V_SK, sp.c_minus
    V2 = V * V
    wM, wM_err = bracketed_root(Jw, w_near, other, noisy=is_smooth(law))
    if wB_err > 0:  # w_B = w_S carries its root error into w_M: G_B(w_M; w_B) = 0 gives
        # dw_M/dw_B = −(V² − f′(w_B))(w_M − w_B)/h_B(w_M), h_B = f − f(w_B) − V²(· − w_B)
        hM = float(law.f(wM)) - float(law.f(wB)) - V2 * (wM - wB)
        if hM != 0.0:
            wM_err += abs((V2 - float(law.df(wB))) * (wM - wB) / hM) * wB_err
    sgn = 1.0 if other > wB else -1.0
    br = march_outward(Jw, other, sgn, 0.125 * abs(other - wB), n=80)
    wT = bracketed_root(Jw, *br)[0] if br else math.nan
    dM = wM - wB
    gamma = math.sqrt(12.0 * (V2 - float(law.df(wB)))) / V

    g = _sw_g(law, wB, wM, V2)
    scale = 2.0 * V / (math.sqrt(24.0) * math.sqrt(abs(dM)))
    # grade the panels toward u = 0 when the orbit grazes the other saddle (flat top near V_SK):
    # there R̃ ≈ ε + c u², so panels must resolve u ~ √ε
    eps_rel = max(abs(wM - other) / abs(dM), 1e-300)
    J_lev = int(min(60, max(0, math.ceil(-math.log2(0.05 * math.sqrt(eps_rel))))))
    edges = np.unique(
        np.concatenate(
            [[0.0], 2.0 ** -np.arange(J_lev, 0, -1.0), np.arange(0.5, U_MAX + 0.25, 0.5)]
        )
    )
    m = ProfileMap(g, scale, edges)

    # E_ren^QC = (V² w_B + f_B) ∫d dξ + V² ∫d² dξ over the whole line (even profile)
    fB = float(law.f(wB))
    c1, c2 = V2 * wB + fB, V2
    a, b = edges[:-1], edges[1:]
    hh = (b - a)[:, None]
    vals = []
    for n in (GL_HI, GL_LO):
        x, wq = gauss_legendre01(n)
        u = a[:, None] + hh * x
        d = dM * sech_squared(u)
        jac = scale * g(u) * wq * hh
        vals.append((2.0 * np.sum(d * jac), 2.0 * np.sum(d * d * jac)))
    (I1, I2), (I1l, I2l) = vals
    t1, t2 = c1 * I1, c2 * I2
    tail = 2.0 * abs(c1 * dM) * 4.0 * math.exp(-2.0 * U_MAX) * m.slope_end
    energy = float(t1 + t2)
    # propagated root errors: near V_SK the plateau length ~ (1/λ_o) log(1/ε), ε = |w_M − other|
    # (R̃ ≈ ε + c u²), so δE ≈ |c1 dM + c2 dM²| (2/λ_o) δε/ε to first order
    lam_o = math.sqrt(max(12.0 * (V2 - float(law.df(other))), EPS)) / V
    d_eps = wM_err + (far_err if interval == "below" else 0.0) + wB_err
    prop = abs(c1 * dM + c2 * dM * dM) * 2.0 / lam_o * d_eps / max(abs(wM - other), EPS)
    # … and the level G_B(other) ≈ ½κ ε² itself is a difference of O(V² d²) terms
    d_o = other - wB
    G_o = abs(d_o * d_o * float(first_integral_J(law, wB, d_o, V2)))
    prop += abs(c1 * dM + c2 * dM * dM) / lam_o * 8 * EPS * V2 * d_o * d_o / max(G_o, 1e-300)
    energy_err = float(
        abs(c1 * (I1 - I1l))
        + abs(c2 * (I2 - I2l))
        + tail
        + prop
        + 128 * EPS * (1.0 + V2 / (V2 - float(law.df(wB)))) * (abs(t1) + abs(t2))
    )  # round-off of J ∝ f′ − V² is amplified by κ_B = V²/(V² − f′(w_B)) (near-sonic waves)

    kind = "tensile" if dM > 0 else "compressive"
    sw = QCSolitaryGeneral(
        law,  # type: ignore[arg-type]
        V,
        w_plus,
        wB,
        wT,
        wM,
        gamma,
        kind,
        interval,
        vsk,
        cp,
        cm,
        energy,
        energy_err,
        math.nan,
        0.0,
        wB_err,
        wM_err,
        sp.V_SK_error,
        m.err,
        m,
    )
    xi = np.linspace(0.0, 12.0, 32) / gamma
    fi = first_integral_residual(law, sw.profile(xi), sw.dprofile(xi), wB, V) if check else math.nan
    # xi_error includes the inverse tables' error once a profile has been evaluated (check=True)
    return replace(
        sw, first_integral_residual=fi, xi_error=m.err, elapsed_s=time.perf_counter() - t0
    )
