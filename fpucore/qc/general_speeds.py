"""Speeds and existence ranges of the general-law QC (paper §3, :mod:`fpucore.qc.general`): c₊,
V_SK, c₋ for a state ahead w₊, the partner state w₋, sonic points, solitary-wave intervals and
the superkink ranges."""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass
from typing import ClassVar

from fpucore.errors import ParameterError, fmt_interval
from fpucore.law import HardeningSofteningLaw
from fpucore.qc.closed_forms import (
    QC_CHECK,
    require_w_plus,
)
from fpucore.qc.general_roots import (
    EPS,
    bracket_to_end,
    bracketed_root,
    driving_force_g,
    far_end,
    is_smooth,
    rayleigh_slope,
    scalar_slope,
    search_direction,
    tangency_defect,
)
from fpucore.result import Result, status_of


# =============================================================================== speeds
@dataclass(frozen=True)
class QCSpeeds(Result):
    """c₊ (eq. cplus), V_SK with its partner w₋ (eqs. Rline, zero_G), w₋ˢ and c₋ (eq. cminus),
    each with an error bar (absolute)."""

    w_plus: float
    c_plus: float
    V_SK: float
    c_minus: float
    w_minus: float
    w_minus_sonic: float
    c_plus_error: float
    V_SK_error: float
    c_minus_error: float
    w_minus_error: float
    w_minus_sonic_error: float
    elapsed_s: float

    ERROR_FIELDS: ClassVar = (
        "c_plus_error",
        "V_SK_error",
        "c_minus_error",
        "w_minus_error",
        "w_minus_sonic_error",
    )
    DERIVED: ClassVar = ("converged", "status", "message")

    @property
    def converged(self) -> bool:
        """Roots found with error bars at round-off level (relative 1e-9)."""
        errs = (self.V_SK_error / self.V_SK, self.w_minus_error / max(1.0, abs(self.w_minus)))
        return bool(all(math.isfinite(e) and e <= QC_CHECK for e in errs))

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "root error bars above 1e-9"


def _partner(law, w_plus: float):
    """(w₋, error) on the far side of w* with ∫₀¹ t(1−t) f″(w₊ + tΔ) dt = 0, or None when the
    root would lie beyond α/β (no validation: also used at the ends of the superkink range)."""
    s = search_direction(law, w_plus)
    F = lambda w: driving_force_g(law, w_plus, w - w_plus)  # noqa: E731
    end = far_end(law, s)
    br = bracket_to_end(F, law.w_star, end, s, max(abs(law.w_star - w_plus), 1e-3))
    if br is None or (math.isfinite(end) and s * (max(br, key=lambda x: s * x) - end) > 0):
        return None
    a, b = br
    return bracketed_root(F, a, b, noisy=is_smooth(law))


def w_minus_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float]:
    """(w₋, error): the equal-area partner of w₊ (eq. zero_G with eq. Rline), the zero of
    ∫₀¹ t(1−t) f″(w₊ + tΔ) dt with w₋ on the other side of w*, inside (α, β)."""
    w_plus = require_w_plus(law, w_plus)
    r = _partner(law, w_plus)
    if r is None:
        lo, hi = superkink_w_plus_range(law, "lower" if w_plus < law.w_star else "upper")
        raise ParameterError(
            "w_plus",
            w_plus,
            fmt_interval(lo, hi),
            "the equal-area partner w- would leave the convex interval (alpha, beta): no superkink",
        )
    return r


def w_minus_sonic(law: HardeningSofteningLaw, w_plus: float, with_error: bool = False):
    """w₋ˢ ≠ w₊ where the line from (w₊, f(w₊)) touches f (eq. cminus; note the paper's typo: the
    slope there is f′(w₋ˢ)).  Zero of ∫₀¹ t f″(w₊ + t d) dt on the far side of w*."""
    w_plus = require_w_plus(law, w_plus)
    s = search_direction(law, w_plus)
    F = lambda w: tangency_defect(law, w_plus, w - w_plus)  # noqa: E731
    br = bracket_to_end(F, law.w_star, far_end(law, s), s, abs(law.w_star - w_plus))
    # always exists: f′(β) = 0 < chord slope (paper §3)
    a, b = br
    x, err = bracketed_root(F, a, b, noisy=is_smooth(law))
    return (x, err) if with_error else x


@functools.lru_cache(maxsize=256)  # laws are frozen and hashable: asked many times per state
def speeds(law: HardeningSofteningLaw, w_plus: float) -> QCSpeeds:
    """All speeds for the state w₊ ahead, with error bars; c₊ < V_SK < c₋ for w₊ ≠ w*.
    Memoised per (law, w₊): sound_speeds, solitary_intervals, solitary and solitary_kind of one
    state share one computation (``elapsed_s`` is that computation's)."""
    t0 = time.perf_counter()
    w_plus = require_w_plus(law, w_plus)
    wm, wm_err = w_minus_from_w_plus(law, w_plus)
    ws, ws_err = w_minus_sonic(law, w_plus, with_error=True)
    cp = math.sqrt(float(law.df(w_plus)))
    V2 = float(rayleigh_slope(law, w_plus, wm - w_plus))
    V = math.sqrt(V2)
    dV2 = abs(float(law.df(wm)) - V2) / abs(wm - w_plus) * wm_err  # ∂S/∂w₋ · δw₋
    cm = math.sqrt(float(law.df(ws)))
    return QCSpeeds(
        w_plus,
        cp,
        V,
        cm,
        wm,
        ws,
        4 * EPS * cp,
        dV2 / (2 * V) + 8 * EPS * V,
        abs(float(law.ddf(ws))) * ws_err / (2 * cm) + 8 * EPS * cm,
        wm_err,
        ws_err,
        time.perf_counter() - t0,
    )


def sound_speeds(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float, float]:
    """(c₊, V_SK, c₋) as in :func:`fpucore.qc.sound_speeds`."""
    sp = speeds(law, w_plus)
    return sp.c_plus, sp.V_SK, sp.c_minus


def solitary_intervals(law: HardeningSofteningLaw, w_plus: float):
    """((c₊, V_SK), (V_SK, c₋)): velocity intervals of the solitary waves for w₊ (eq. wB)."""
    cp, vsk, cm = sound_speeds(law, w_plus)
    return (cp, vsk), (vsk, cm)


# =============================================================================== superkink range
@functools.lru_cache(maxsize=256)  # a property of the law (laws are frozen, hashable)
def superkink_w_plus_range(law: HardeningSofteningLaw, branch: str = "lower"):
    """Open w₊-interval of superkinks on a branch: (w₊_min, w*) ("lower") or (w*, w₊_max)
    ("upper"); its outer end is α (β) or the w₊ whose partner w₋ reaches β (α)."""
    if branch not in ("lower", "upper"):
        raise ParameterError("branch", branch, "'lower' (w_plus < w*) or 'upper' (w_plus > w*)")
    s = 1.0 if branch == "lower" else -1.0
    near, far = law.w_star, far_end(law, s)  # far: where w₋ may go
    own = far_end(law, -s)  # own end: where w₊ may go
    if not math.isfinite(far):
        return (own, near) if s > 0 else (near, own)
    K = lambda wp: driving_force_g(law, wp, far - wp)  # noqa: E731
    br = bracket_to_end(K, near, own, -s, abs(far - near))
    x = bracketed_root(K, *br)[0] if br is not None else own
    if math.isfinite(own) and s * (own - x) > 0:  # root beyond α/β: the w₊ end binds
        x = own
    return (x, near) if s > 0 else (near, x)


def v_sk_of(law, w_plus: float) -> float:
    """V_SK(w₊) without validation: c_max at w*, the limiting chord at the range ends."""
    if abs(w_plus - law.w_star) <= 4 * EPS * max(1.0, abs(law.w_star)):
        return law.c_max
    r = _partner(law, w_plus)
    wm = r[0] if r is not None else far_end(law, search_direction(law, w_plus))
    return math.sqrt(scalar_slope(law, w_plus, wm - w_plus))


@functools.lru_cache(maxsize=256)
def superkink_velocity_bounds(law: HardeningSofteningLaw, branch: str = "lower"):
    """(V_lo, V_hi = c_max) of superkinks on a branch (eq. V_bounds_cubic for the cubic, where
    both branches agree; for a general law they differ).  V_lo is V_SK at the outer end of
    :func:`superkink_w_plus_range` (NaN if that end is −∞)."""
    lo, hi = superkink_w_plus_range(law, branch)
    end = lo if branch == "lower" else hi
    return (v_sk_of(law, end) if math.isfinite(end) else math.nan), law.c_max
