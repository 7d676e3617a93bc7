"""Quasicontinuum (QC) theory (paper §3–4): closed forms for the cubic law, the same theory
numerically for any hardening–softening law, the phase plane and the existence /
velocity–amplitude diagrams.  The modules, in import order::

    cubic_speeds (eqs. cplus, cubic_cond2, cminus_cubic, V_bounds_cubic, Rline, wS)
    → first_integrals (eq. TW_QC_gen3: H(w, w′) and its residual on an orbit)
    → closed_forms (eqs. zero_G, cubic_cond1/2, SKsoln_cubic, SWsoln_cubic, E_ren)
    → general_roots (quadrature rules, cancellation-free integrals, bracketed roots)
    → general_speeds (c₊, V_SK, c₋, partner states, existence ranges)
    → general_map (the substituted profile map ξ(s))
    → general_superkink, general_rayleigh (w_C, w_S), general_solitary (§3 for any law, with
      error bars)  → general (their public names, and the method)
    → dispatch (the public functions: closed forms for the cubic, general otherwise)
    → phase (phase plane of eq. TW_QC_gen2)  → diagram (existence region, families)
"""

from fpucore.qc import diagram, general, phase
from fpucore.qc.closed_forms import (
    EPS,
    QCSolitary,
    QCSuperkink,
    cubic_law,
    first_integral,
    require_V,
    solitary_closed_form,
    sound_speed_plus,
)
from fpucore.qc.dispatch import (
    is_closed_form,
    rayleigh_roots,
    solitary,
    solitary_intervals,
    solitary_kind,
    sound_speeds,
    superkink_from_V,
    superkink_from_w_plus,
    superkink_velocity_bounds,
    superkink_w_plus_range,
    w_minus_sonic,
    w_S,
)

__all__ = [
    "diagram",
    "general",
    "is_closed_form",
    "superkink_w_plus_range",
    "phase",
    "EPS",
    "cubic_law",
    "QCSolitary",
    "QCSuperkink",
    "first_integral",
    "rayleigh_roots",
    "require_V",
    "solitary",
    "solitary_closed_form",
    "solitary_intervals",
    "solitary_kind",
    "sound_speed_plus",
    "sound_speeds",
    "superkink_from_V",
    "superkink_from_w_plus",
    "superkink_velocity_bounds",
    "w_minus_sonic",
    "w_S",
]
