"""Quasicontinuum (QC) results for the scenes: cheap closed forms or quadratures, computed in
the server process and cached exactly (:mod:`app.compute.cache`).

The QC superkink or solitary wave, the QC solitary family and the existence diagram (§3–4), the
phase plane, and the chain size a discrete wave needs (from the QC tails).
"""

from __future__ import annotations

from fpucore import qc, wave
from fpucore.qc import diagram, phase

from .cache import CACHE, Computed, exact
from .laws import law_key

__all__ = [
    "qc_method",
    "qc_wave",
    "qc_family",
    "phase_plane",
    "phase_orbit",
    "existence_diagram",
    "spec_of",
    "n_needed",
]


def qc_method(lw) -> str:
    """How fpucore computes this law's QC waves: "closed form" (the cubic, paper §4) or
    "quadrature" (any other law, §3) — for the timing labels."""
    return "closed form" if qc.is_closed_form(lw) else "quadrature"


def qc_wave(lw, mode: str, w_plus: float, V: float) -> Computed:
    """QC superkink (mode "superkink": from w_plus) or solitary wave (mode "solitary")."""
    if mode == "superkink":
        return CACHE.get(
            ("qc_sk", law_key(lw), exact(w_plus)),
            lambda: qc.superkink_from_w_plus(lw, w_plus),
        )
    return CACHE.get(
        ("qc_sw", law_key(lw), exact(w_plus), exact(V)),
        lambda: qc.solitary(lw, w_plus, V),
    )


def qc_family(lw, w_plus: float, n: int = 160) -> Computed:
    """fpucore.qc.diagram.solitary_family: amplitude (eq. SWQC_amp) and E_ren (eq. Eren_QC)
    of the QC solitary waves along both velocity intervals for fixed w_plus."""
    return CACHE.get(
        ("qc_family", law_key(lw), exact(w_plus), n),
        lambda: diagram.solitary_family(lw, w_plus, n=n),
    )


def phase_plane(lw, w_plus: float, V: float, n_grid: int = 241) -> Computed:
    """fpucore.qc.phase.phase_plane for the current parameters."""
    return CACHE.get(
        ("phase", law_key(lw), exact(w_plus), exact(V), n_grid),
        lambda: phase.phase_plane(lw, w_plus, V, n_grid=n_grid),
    )


def phase_orbit(lw, w_plus: float, V: float, w0: float, wp0: float, window) -> Computed:
    """fpucore.qc.phase.orbit_through: the orbit through a clicked point (w0, w0′)."""
    lo, hi = (float(x) for x in window)
    return CACHE.get(
        ("phase_orbit", law_key(lw), exact(w_plus), exact(V), exact(w0), exact(wp0),
         exact(lo), exact(hi)),
        lambda: phase.orbit_through(lw, w_plus, V, w0, wp0, (lo, hi)),
    )  # fmt: skip


def existence_diagram(lw, n: int = 400) -> Computed:
    """fpucore.qc.diagram.existence_diagram: arrays w_plus, c_plus, V_SK, c_minus."""
    return CACHE.get(("diagram", law_key(lw), n), lambda: diagram.existence_diagram(lw, n=n))


def spec_of(lw, mode, w_plus, V) -> wave.Spec:
    """fpucore.wave's description (Spec, with its law) of the wave the parameters define."""
    if mode == "superkink":  # the scene's w₊ fixes V and the branch
        sk = qc.superkink_from_w_plus(lw, w_plus)
        return wave.spec_of(lw, "superkink", sk.branch, sk.V)
    return wave.spec_of(lw, "solitary", w_plus, V)


def n_needed(lw, mode, w_plus, V, tol: float) -> int:
    """The chain size fpucore would choose itself for this wave (``N=None``: tails resolved to
    0.1·tol·scale, eq. fixedBCs), at least the smallest N it accepts (tails cut at 1e-6 of the
    amplitude).  Closed-form QC tails only: cheap."""
    spec = spec_of(lw, mode, w_plus, V)
    return int(max(spec.auto_N(tol), spec.smallest_N()))
