"""The public QC functions for any law: the cubic keeps its closed forms (paper §4,
:mod:`.closed_forms`); every other hardening–softening law goes through the numerical §3 theory
(:mod:`.general`).  Same signatures and result types (the general results subclass the cubic
ones), so callers — phase plane, diagrams, discrete waves, the CLI, the explorer — never branch
on the law.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeGuard

import numpy as np

from fpucore.errors import ParameterError
from fpucore.law import CubicLaw, HardeningSofteningLaw, require_law
from fpucore.qc import closed_forms as cf
from fpucore.qc import general as gen
from fpucore.qc import piecewise, piecewise_orbit

if TYPE_CHECKING:
    from fpucore.law.base import Strain

BRANCHES = ("lower", "upper")


def _pl(law):
    """The closed-form module for a piecewise-linear law (fpucore.qc.piecewise*), else None:
    the general route integrates f″, which is zero between breakpoints."""
    if hasattr(require_law(law), "hard_regime"):
        return piecewise, piecewise_orbit
    return None


def is_closed_form(law: HardeningSofteningLaw) -> TypeGuard[CubicLaw]:
    """True when the closed forms of paper §4 apply (the cubic law object); ParameterError
    naming ``law`` when it is no law at all (None, a string ...)."""
    return isinstance(require_law(law), CubicLaw)


def sound_speeds(law: HardeningSofteningLaw, w_plus: float) -> tuple[float, float, float]:
    """(c₊, V_SK, c₋) for the state w₊ ahead (eqs. cplus, Rline + zero_G, cminus)."""
    if pl := _pl(law):
        sp = pl[0].speeds(law, w_plus)
        return sp.c_plus, sp.V_SK, sp.c_minus
    if is_closed_form(law):
        return cf.sound_speeds(law, w_plus)
    return gen.sound_speeds(law, w_plus)


def solitary_intervals(
    law: HardeningSofteningLaw, w_plus: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """((c₊, V_SK), (V_SK, c₋)): the two velocity intervals of solitary waves for w₊."""
    if pl := _pl(law):
        return pl[0].solitary_intervals(law, w_plus)
    if is_closed_form(law):
        return cf.solitary_intervals(law, w_plus)
    return gen.solitary_intervals(law, w_plus)


def w_minus_sonic(law: HardeningSofteningLaw, w_plus: float) -> float:
    """w₋ˢ, the tangency point of the c₋ Rayleigh line (eq. cminus)."""
    if pl := _pl(law):
        return pl[0].c_minus_sonic(law, pl[0].require_state(law, w_plus))[1]
    if is_closed_form(law):
        return cf.w_minus_sonic(law, w_plus)
    return gen.w_minus_sonic(law, w_plus)


def rayleigh_roots(law: HardeningSofteningLaw, w_plus: float, V: Strain) -> tuple[Strain, Strain]:
    """(w_near, w_far): the other intersections of f with the Rayleigh line (V may be an array,
    each V in (0, c₋]; ParameterError naming V otherwise, where NaN was once returned)."""
    if pl := _pl(law):
        w_plus = pl[0].require_state(law, w_plus)
        out = []
        for v in np.ravel(cf.finite_array("V", V)):
            side = [
                x
                for x in pl[0].rayleigh_roots(law, w_plus, float(v))
                if (x > w_plus) == (w_plus < law.w_star)
            ]
            if len(side) < 2 or not v > 0:
                cm = pl[0].c_minus_sonic(law, w_plus)[0]
                raise ParameterError("V", float(v), f"(0, {cm:.10g})", "no centre and saddle")
            side.sort(key=lambda x: abs(x - w_plus))
            out.append(side[:2])
        arr = np.array(out)
        if np.ndim(V):
            return arr[:, 0].reshape(np.shape(V)), arr[:, 1].reshape(np.shape(V))
        return float(arr[0, 0]), float(arr[0, 1])
    if is_closed_form(law):
        return cf.rayleigh_roots(law, w_plus, V)
    cm = gen.sound_speeds(law, w_plus)[2]
    Va = cf.finite_array("V", V)
    roots = gen.rayleigh_roots(law, w_plus, Va if np.ndim(V) else float(Va))
    missing = ~(np.isfinite(roots[0]) & np.isfinite(roots[1])) | (Va <= 0)
    if np.any(missing):
        bad = float(np.broadcast_to(Va, missing.shape)[missing].flat[0])
        raise ParameterError("V", bad, f"(0, {cm:.10g}]", "Rayleigh roots exist for 0 < V <= c-")
    return roots


def w_S(law: HardeningSofteningLaw, w_plus: float, V: Strain) -> Strain:
    """Saddle w_S(V) ≠ w₊ of eq. wS, the far Rayleigh root (V in (0, c₋], may be an array)."""
    if pl := _pl(law):
        if np.ndim(V):
            return np.array([pl[0].w_S(law, w_plus, float(v)) for v in np.ravel(V)]).reshape(
                np.shape(V)
            )
        return pl[0].w_S(law, w_plus, V)
    return rayleigh_roots(law, w_plus, V)[1]


def superkink_velocity_bounds(
    law: HardeningSofteningLaw, branch: str = "lower"
) -> tuple[float, float]:
    """(V_lo, V_hi) of superkinks on a branch.  The cubic's two branches share eq.
    V_bounds_cubic; for a general law they may differ."""
    if pl := _pl(law):
        return pl[0].superkink_velocity_bounds(law, branch)
    if is_closed_form(law):
        return cf.superkink_velocity_bounds(law)
    return gen.superkink_velocity_bounds(law, branch)


def superkink_w_plus_range(
    law: HardeningSofteningLaw, branch: str = "lower"
) -> tuple[float, float]:
    """Open w₊-interval of superkinks on a branch ((α, w*) or (w*, β) for the cubic, whose
    convex interval is symmetric about w*)."""
    if pl := _pl(law):
        return pl[0].superkink_w_plus_range(law, branch)
    if is_closed_form(law):
        if branch not in BRANCHES:
            return gen.superkink_w_plus_range(law, branch)  # raises the ParameterError
        return (law.alpha, law.w_star) if branch == "lower" else (law.w_star, law.beta)
    return gen.superkink_w_plus_range(law, branch)


def superkink_from_V(law: HardeningSofteningLaw, V: float, branch: str = "lower") -> cf.QCSuperkink:
    """Superkink with velocity V on a branch (eq. wpm_cubic for the cubic)."""
    if pl := _pl(law):
        return pl[1].superkink(law, pl[0].w_plus_of_V(law, V, branch))
    if is_closed_form(law):
        return cf.superkink_from_V(law, V, branch)
    return gen.superkink_from_V(law, V, branch)


def superkink_from_w_plus(law: HardeningSofteningLaw, w_plus: float) -> cf.QCSuperkink:
    """Superkink with state w₊ ahead (eqs. Rline, zero_G)."""
    if pl := _pl(law):
        return pl[1].superkink(law, w_plus)
    if is_closed_form(law):
        return cf.superkink_from_w_plus(law, w_plus)
    return gen.superkink_from_w_plus(law, w_plus)


def solitary(law: HardeningSofteningLaw, w_plus: float, V: float) -> cf.QCSolitary:
    """QC solitary wave for the state w₊ ahead of the associated superkink, velocity V."""
    if pl := _pl(law):
        return pl[1].solitary(law, w_plus, V)
    if is_closed_form(law):
        return cf.solitary(law, w_plus, V)
    return gen.solitary(law, w_plus, V)


def solitary_kind(law: HardeningSofteningLaw, w_plus: float, V: float) -> str:
    """``solitary(law, w_plus, V).kind`` ("tensile" or "compressive") with the same refusals,
    without the profile and E_ren^QC of the general route (which near a sonic end cost up to a
    second for a smooth law): for a sidebar's or a scene's "is this a wave, and which"."""
    if _pl(law) or is_closed_form(law):
        return solitary(law, w_plus, V).kind  # closed forms: the whole wave is cheap
    return gen.solitary_kind(law, w_plus, V)
