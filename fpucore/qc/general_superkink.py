"""QC superkinks of any hardening–softening law (paper §3, eqs. zero_G, Rline, TW_QC_gen3):
w₋ and V_SK by bracketed roots, the profile w(ξ) by quadrature of the first integral after the
substitution w = w_mid − (Δ/2) tanh s (the method: :mod:`fpucore.qc.general`)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval
from fpucore.law import HardeningSofteningLaw
from fpucore.qc.closed_forms import QC_CHECK, QCSuperkink, require_V
from fpucore.qc.general_map import ProfileMap, sech_squared
from fpucore.qc.general_roots import (
    EPS,
    U_MAX,
    bracketed_root,
    first_integral_J,
    is_smooth,
    rayleigh_slope,
)
from fpucore.qc.general_speeds import (
    speeds,
    superkink_velocity_bounds,
    superkink_w_plus_range,
    v_sk_of,
    w_minus_from_w_plus,
)


@dataclass(frozen=True)
class QCSuperkinkGeneral(QCSuperkink):
    """QC superkink of any law: the fields of :class:`fpucore.qc.QCSuperkink` plus error bars;
    the profile comes from the first integral by quadrature (the method: :mod:`fpucore.qc.general`).

    ``p`` = half the decay rate ahead, √(12(V² − f′(w₊)))/(2V) (the p of eq. SKsoln_cubic);
    ``p_minus`` the same behind (equal to p for the cubic only).  ``xi_error`` bounds the error
    of the tabulated ξ(s); ``rayleigh_residual``/``driving_force`` as in fpucore.qc.
    """

    p_minus: float = math.nan
    V_error: float = math.nan
    w_plus_error: float = math.nan
    w_minus_error: float = math.nan
    xi_error: float = math.nan
    tables: tuple = field(default=(), repr=False, compare=False)  # (ξ ≥ 0, ξ < 0) ξ(s) tables

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = QCSuperkink.ERROR_FIELDS + (
        "V_error",
        "w_plus_error",
        "w_minus_error",
        "xi_error",
    )
    DERIVED: ClassVar[tuple[str, ...]] = QCSuperkink.DERIVED + ("symmetry_defect", "w_center")
    EXCLUDE: ClassVar[tuple[str, ...]] = ("law", "tables")

    @property
    def w_center(self) -> float:
        """w(0) = (w₊ + w₋)/2 (= w* only for the cubic, eq. cubic_cond1)."""
        return 0.5 * (self.w_plus + self.w_minus)

    @property
    def amplitude_error(self) -> float:
        return self.w_plus_error + self.w_minus_error

    @property
    def symmetry_defect(self) -> float:
        """w₊ + w₋ − 2w* (zero for the cubic, eq. cubic_cond1; not for a general law)."""
        return self.w_plus + self.w_minus - 2.0 * self.law.w_star

    def _w_of_s(self, s):
        """w = w_mid − (Δ/2) tanh s written from the nearer end (no loss in the tails)."""
        D = self.w_minus - self.w_plus
        if np.ndim(s) == 0:
            E = math.exp(-2.0 * abs(s))
            tail = 2.0 * E / (1.0 + E)
            return np.float64(
                self.w_plus + 0.5 * D * tail if s >= 0 else self.w_minus - 0.5 * D * tail
            )
        E = np.exp(-2.0 * np.abs(s))
        tail = 2.0 * E / (1.0 + E)  # 1 − tanh|s|
        return np.where(s >= 0, self.w_plus + 0.5 * D * tail, self.w_minus - 0.5 * D * tail)

    def _s_of_xi(self, xi):
        xi = np.asarray(xi, float)
        pos, neg = self.tables  # neg tabulates g(−s): s = −s_neg for ξ < 0
        if xi.ndim == 0:
            x = float(xi)
            return np.float64(pos.s_of_scalar(x) if x >= 0 else -neg.s_of_scalar(-x))
        out = np.empty_like(xi)
        right = xi >= 0
        if right.all() or not right.any():  # one side only (scalar calls): one table
            return pos.s_of(xi) if xi.size == 0 or right.flat[0] else -neg.s_of(-xi)
        out[right] = pos.s_of(xi[right])
        out[~right] = -neg.s_of(-xi[~right])
        return out

    def profile(self, xi):
        """w(ξ), w(0) = (w₊ + w₋)/2 (= w* only for the cubic)."""
        return self._w_of_s(self._s_of_xi(xi))

    def dprofile(self, xi):
        """w′(ξ) = −(Δ/2) sech²s · ds/dξ."""
        s = self._s_of_xi(xi)
        D = self.w_minus - self.w_plus
        g = _sk_g(self.law, self.w_plus, self.w_minus, self.V * self.V)
        return -0.5 * D * sech_squared(s) / (self.tables[0].scale * g(s))

    @property
    def converged(self) -> bool:
        """Residuals at round-off and the ξ(s) table accurate (relative 1e-9 of the width)."""
        return bool(super().converged and self.xi_error * self.p <= QC_CHECK)


def _sk_g(law, wp: float, wm: float, V2: float):
    """g(s) = Q(w(s))^(−1/2), −G = (w−w₊)²(w₋−w)² Q; Q from the expansion about the nearer end
    (−J about w₊ for s ≥ 0, about w₋ for s < 0) so nothing cancels."""
    D = wm - wp

    def g(s):
        s = np.asarray(s, float)
        E = np.exp(-2.0 * np.abs(s))
        near = 0.5 * D * 2.0 * E / (1.0 + E)  # distance to the nearer end (signed like D)
        far = D - near
        dp = np.where(s >= 0, near, far)  # w − w₊
        dm = np.where(s >= 0, -far, -near)  # w − w₋
        with np.errstate(divide="ignore", invalid="ignore"):  # the branch not taken may be 0/0
            Q = np.where(
                s >= 0,
                -first_integral_J(law, wp, dp, V2) / (dm * dm),
                -first_integral_J(law, wm, dm, V2) / (dp * dp),
            )
        return 1.0 / np.sqrt(Q)

    return g


def _build_superkink(law, V, wp, wm, branch, t0, wp_err, wm_err, V_err):
    V2 = V * V
    D = wm - wp
    g = _sk_g(law, wp, wm, V2)
    scale = 2.0 * abs(V) / (math.sqrt(24.0) * abs(D))  # 2/(k|Δ|)
    edges = np.arange(0.0, U_MAX + 0.25, 0.5)
    pos, neg = ProfileMap(g, scale, edges), ProfileMap(lambda s: g(-s), scale, edges)
    fp, fm = float(law.f(wp)), float(law.f(wm))
    rscale = abs(fp) + abs(fm) + V2 * abs(D)
    ray = abs(fp - fm - V2 * (wp - wm)) / rscale
    G = float(law.phi(wp) - law.phi(wm)) - 0.5 * (wp - wm) * (fp + fm)
    G_scale = abs(float(law.phi(wp))) + abs(float(law.phi(wm))) + rscale * abs(wp)
    lam = lambda w: math.sqrt(max(12.0 * (V2 - float(law.df(w))), 0.0)) / V  # noqa: E731
    return QCSuperkinkGeneral(
        law,
        V,
        wp,
        wm,
        0.5 * lam(wp),
        branch,
        ray,
        abs(G) / G_scale,
        time.perf_counter() - t0,
        0.5 * lam(wm),
        V_err,
        wp_err,
        wm_err,
        max(pos.table_err(), neg.table_err()),
        (pos, neg),
    )


def superkink_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> QCSuperkinkGeneral:
    """Superkink with state w₊ ahead: w₋ from eq. zero_G, V_SK² = S(w₊, w₋) (eq. Rline)."""
    t0 = time.perf_counter()
    sp = speeds(law, w_plus)
    branch = "lower" if sp.w_plus < law.w_star else "upper"
    return _build_superkink(
        law,
        sp.V_SK,
        sp.w_plus,
        sp.w_minus,
        branch,
        t0,
        4 * EPS * abs(sp.w_plus),
        sp.w_minus_error,
        sp.V_SK_error,
    )


def superkink_from_V(
    law: HardeningSofteningLaw, V: float, branch: str = "lower"
) -> QCSuperkinkGeneral:
    """Superkink with velocity V: w₊ solves V_SK(w₊) = V on the branch ("lower": w₊ < w* < w₋,
    a front with w′ < 0; "upper": w₊ > w* > w₋), w₋ its equal-area partner."""
    t0 = time.perf_counter()
    V = require_V(V)
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    lo, hi = superkink_velocity_bounds(law, branch)
    if not lo < V < hi:
        raise ParameterError(
            "V", V, fmt_interval(lo, hi), f"superkink velocities on the {branch} branch"
        )
    wlo, whi = superkink_w_plus_range(law, branch)
    F = lambda wp: v_sk_of(law, wp) ** 2 - V * V  # noqa: E731
    a, b = (wlo, law.w_star) if branch == "lower" else (law.w_star, whi)
    wp, wp_err = bracketed_root(F, a, b, noisy=is_smooth(law))
    wm, wm_err = w_minus_from_w_plus(law, wp)
    V2 = float(rayleigh_slope(law, wp, wm - wp))
    dwm = abs(V2 - float(law.df(wp))) / abs(V2 - float(law.df(wm)))  # |dw₋/dw₊| (implicit fn.)
    return _build_superkink(
        law,
        math.sqrt(V2),
        wp,
        wm,
        branch,
        t0,
        wp_err,
        wm_err + dwm * wp_err,
        abs(math.sqrt(V2) - V) + 8 * EPS * V,
    )
