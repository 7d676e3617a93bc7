"""Runge–Kutta tableaux as data, validated when built, in one registry.

    dop853_data (coefficients)  →  rk (explicit RK: DOP853, RK4)  →  embedded (adaptive pairs:
    DOP853 8(5,3), DOPRI5 5(4))  →  rkn (Runge–Kutta–Nyström pairs: RKN12(10), RKN8(6); their
    exact order conditions are test support, tests/support/rkn_order.py)

``get(family, name)`` is the one lookup: family ``"rk"`` (fixed-step, used by the period map and
the Floquet tangent flow), ``"embedded"`` (adaptive first-order chain steppers) or ``"rkn"``
(adaptive second-order chain steppers).
"""

from fpucore.errors import ParameterError
from fpucore.tableaux.embedded import DOP853E, DOPRI5, EMBEDDED, EmbeddedTableau
from fpucore.tableaux.rk import DOP853, RK4, TABLEAUX, Tableau, check_consistency
from fpucore.tableaux.rkn import DPRKN8, DPRKN12, RKN, RKNTableau

REGISTRY: dict[str, dict] = {"rk": TABLEAUX, "embedded": EMBEDDED, "rkn": RKN}


def get(family: str, name: str) -> Tableau | EmbeddedTableau | RKNTableau:
    """The tableau ``name`` of ``family`` ("rk" | "embedded" | "rkn")."""
    if family not in REGISTRY:
        raise ParameterError("family", family, " | ".join(REGISTRY))
    table = REGISTRY[family]
    if name not in table:
        raise ParameterError("method", name, " | ".join(table))
    return table[name]


__all__ = [
    "REGISTRY",
    "get",
    "Tableau",
    "EmbeddedTableau",
    "RKNTableau",
    "check_consistency",
    "DOP853",
    "RK4",
    "DOP853E",
    "DOPRI5",
    "DPRKN8",
    "DPRKN12",
    "TABLEAUX",
    "EMBEDDED",
    "RKN",
]
