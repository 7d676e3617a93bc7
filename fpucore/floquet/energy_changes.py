"""Cross-check of a sweep's Floquet classifications against the energy criterion: each change
across the stable/unstable line between neighbouring velocities, and whether an extremum of
E_ren explains it (paper §6)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError, require_finite
from fpucore.floquet.finite_size import CLASSES

if TYPE_CHECKING:
    from collections.abc import Sequence

    from fpucore.floquet.energy_result import EnergyCriterion
    from fpucore.law.base import HardeningSofteningLaw


#: allowance on V (relative) when a QC extremum stands in for the discrete one: measured
#: |V*_QC − V*_D| / V* ≈ 0.9 % on the soft family w₊ = −0.04 (tests/floquet/test_energy_criterion)
QC_DISCRETE_ALLOWANCE = 0.02


@dataclass(frozen=True)
class StabilityChange:
    """A change of the Floquet classification between two neighbouring velocities of one
    velocity interval, across the stable/unstable line ("stable" and "finite_size" both mean
    stable for the infinite chain).  explained : an extremum of E_ren lies in
    [V_from, V_to] within its error bar (QC extrema also within QC_DISCRETE_ALLOWANCE·V*);
    extremum_V : that extremum (NaN if none)."""

    V_from: float
    V_to: float
    class_from: str
    class_to: str
    explained: bool
    extremum_V: float


def stability_changes(
    law: HardeningSofteningLaw,
    w_plus: float,
    V: Sequence[float] | np.ndarray,
    classification: Sequence[str],
    criterion: EnergyCriterion,
) -> list[StabilityChange]:
    """Cross-check of a sweep's classifications (fpucore.atlas.sweep rows, any order) against
    the energy criterion: every change across the stable/unstable line between neighbouring
    classified velocities of one interval, and whether an extremum of E_ren explains it.  A
    change no extremum explains is not a change of stability through the translation mode:
    an oscillatory instability (a complex quartet needs no extremum) or a finite-size effect
    the window did not resolve (paper §6: the spurious oscillatory instabilities), to be
    checked at a larger N.  Returns a list of
    :class:`StabilityChange`, in order of V.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ of the solitary family.
    V : array_like, shape (n,)
        Velocities of the sweep's rows, sites per unit time.
    classification : sequence of str, length n
        Floquet class of each row (one of :data:`CLASSES`; others are ignored).
    criterion : EnergyCriterion
        The energy criterion of the same family (:func:`energy_criterion`).

    Returns
    -------
    list of StabilityChange
        Changes across the stable/unstable line, in order of V, per velocity interval.

    Raises
    ------
    ParameterError
        When ``w_plus`` is not finite, ``classification`` does not have one class per velocity,
        or w₊ has no solitary family.
    """
    w_plus = require_finite("w_plus", w_plus)
    V = np.atleast_1d(np.asarray(V, dtype=float))
    cls = np.array([str(c) for c in classification])
    if cls.size != V.size:
        raise ParameterError("classification", cls.size, f"one class per velocity ({V.size})")
    marks = [(v, dv) for v, dv in zip(criterion.extrema_V, criterion.extrema_V_error)]
    marks += [
        (v, dv + QC_DISCRETE_ALLOWANCE * abs(v))
        for v, dv in zip(criterion.qc_extrema_V, criterion.qc_extrema_V_error)
    ]
    out = []
    for lo, hi in qc.solitary_intervals(law, w_plus):
        # an undetermined velocity has no class to change from or to
        sel = (V > lo) & (V < hi) & np.isin(cls, CLASSES) & (cls != "undetermined")
        order = np.argsort(V[sel])
        v, c = V[sel][order], cls[sel][order]
        for i in range(v.size - 1):
            if (c[i] == "unstable") == (c[i + 1] == "unstable"):
                continue
            near = [x for x, dx in marks if v[i] - dx <= x <= v[i + 1] + dx]
            x0 = float(near[0]) if near else math.nan
            out.append(
                StabilityChange(
                    float(v[i]), float(v[i + 1]), str(c[i]), str(c[i + 1]), bool(near), x0
                )
            )
    return out


def changes_summary(changes: list[StabilityChange]) -> str:
    """The cross-check of a sweep against the energy criterion in one line (plain text).

    Parameters
    ----------
    changes : list of StabilityChange
        The changes found by :func:`stability_changes`.

    Returns
    -------
    str
        One sentence: no change, or how many changes lie at an extremum of E_ren (with their V).
    """
    k = len(changes)
    if k == 0:
        return (
            "No change between stable and unstable along the sweep: consistent with the "
            "energy criterion."
        )
    at = [c for c in changes if c.explained]
    what = f"{k} change{'s' if k > 1 else ''} of class across the stable/unstable line"
    # an "unstable" row has passed the window test (present on every ring, converged), so an
    # unexplained change is not called a finite-size effect: it is no change through the
    # translation mode, and an oscillatory (complex-quartet) instability needs no extremum
    other = (
        "not through the translation mode (that needs dE_ren/dV = 0): an oscillatory "
        "instability or an unresolved finite-size effect - check those rows at 2N"
    )
    if not at:
        return f"{what}, none at an extremum of E_ren: {other}."
    where = ", ".join(f"{c.extremum_V:.6g}" for c in at)
    rest = k - len(at)
    return (
        f"{what}, {len(at)} at an extremum of E_ren (V = {where}): consistent with a change "
        "of stability there" + (f"; {rest} elsewhere: {other}." if rest else ".")
    )
