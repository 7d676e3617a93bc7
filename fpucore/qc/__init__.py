"""Quasicontinuum (QC) theory (paper §3–4): closed forms for the cubic law, the phase plane and
the existence / velocity–amplitude diagrams.

    closed_forms (eqs. Rline, zero_G, cubic_cond1/2, SKsoln_cubic, SWsoln_cubic, E_ren)
    → phase (phase plane of eq. TW_QC_gen2)  → diagram (existence region, families)
"""

from fpucore.qc import diagram, phase
from fpucore.qc.closed_forms import (
    EPS,
    QCSolitary,
    QCSuperkink,
    cubic_law,
    first_integral,
    rayleigh_roots,
    require_V,
    solitary,
    solitary_closed_form,
    solitary_intervals,
    sound_speed_plus,
    sound_speeds,
    superkink_from_V,
    superkink_from_w_plus,
    superkink_velocity_bounds,
    w_minus_sonic,
    w_S,
)

__all__ = [
    "diagram",
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
    "sound_speed_plus",
    "sound_speeds",
    "superkink_from_V",
    "superkink_from_w_plus",
    "superkink_velocity_bounds",
    "w_minus_sonic",
    "w_S",
]
