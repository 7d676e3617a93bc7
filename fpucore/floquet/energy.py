"""Energy criterion for solitary-wave families (Friesecke–Pego type; paper eqs. Eren_D, Eren_QC).

Along a family of solitary waves parametrised by V, a change of (linear) stability can only occur
where the renormalized energy is stationary, dE_ren/dV = 0: there the translation/velocity pair
of multipliers at μ = 1 (a Jordan block) can leave the unit circle as a real pair.  Away from
such points the stability type of the family cannot change.  :func:`energy_criterion` locates
the extrema of E_ren(V) along a discrete family (:func:`fpucore.wave.solitary_family`) and of
the QC closed form E_ren^QC(V) (:func:`fpucore.qc.solitary`), each with an error bar on V.

Location of an extremum from samples.  A sign change of successive differences E_{i+1} − E_i
brackets an extremum; the vertex of the parabola through the three samples around it gives
V*, and E″ its curvature.  Error bar on V* (both added):

* stencil: |V*(i−1, i, i+1) − V*(shifted triple)| — the parabola's truncation error;
* energy errors: with E(V) ≈ E* + ½E″(V − V*)², any V with |E − E*| ≤ 2δE is
  indistinguishable, so δV = 2√(δE/|E″|), δE = the wave's energy error bar.

QC extrema are refined by a bounded scalar minimisation inside the bracket (xatol 1e-12·V),
with the same δE term from the closed form's round-off bound.  The family's two velocity
intervals (c₊, V_SK) and (V_SK, c₋) are treated separately (E_ren diverges at V_SK).
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError, require_finite
from fpucore.floquet.energy_changes import (
    QC_DISCRETE_ALLOWANCE,
    StabilityChange,
    changes_summary,
    stability_changes,
)
from fpucore.floquet.energy_extrema import (
    locate_extrema,
    qc_energy_grid,
    qc_interval_extrema,
    wave_energy_error,
)
from fpucore.floquet.energy_result import EnergyCriterion
from fpucore.wave import Family, solitary_family
from fpucore.wave.family import require_V_values

if TYPE_CHECKING:
    from collections.abc import Sequence

    from fpucore.law.base import HardeningSofteningLaw

# public names, with those of its topic modules (callers import them from here)
__all__ = [
    "QC_SAMPLES",
    "QC_DISCRETE_ALLOWANCE",
    "EnergyCriterion",
    "StabilityChange",
    "changes_summary",
    "criterion_from_samples",
    "energy_criterion",
    "locate_extrema",
    "qc_energy_grid",
    "stability_changes",
    "wave_energy_error",
]

QC_SAMPLES = 400  # QC grid points per velocity interval (cubic: one vectorised closed form)


def _check_qc_samples(qc_samples) -> None:
    ok = isinstance(qc_samples, (int, np.integer)) and not isinstance(qc_samples, bool)
    if not (ok and (qc_samples == 0 or 5 <= qc_samples <= 100000)):
        raise ParameterError("qc_samples", qc_samples, "0 or an integer in [5, 100000]")


def energy_criterion(
    law: HardeningSofteningLaw,
    w_plus: float,
    V_values: Sequence[float] | np.ndarray | None = None,
    N: int | None = None,
    tol: float = 1e-12,
    family: Family | None = None,
    qc_samples: int = QC_SAMPLES,
) -> EnergyCriterion:
    """Extrema of E_ren(V) along the solitary-wave family of w₊ (discrete and QC), where the
    stability of the family may change (Friesecke–Pego type criterion, see module doc).

    V_values : velocities of the discrete family (sorted here; ≥ 3 per interval to locate an
    extremum), or ``family`` : an already computed :func:`fpucore.wave.solitary_family`
    (then V_values, N, tol are not used).  Neither: only the QC family is examined.
    N, tol : as in :func:`fpucore.wave.solve_solitary`.  qc_samples : QC grid per interval
    (0: skip the QC family).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ ahead of the associated superkink (selects the solitary family).
    V_values : array_like, shape (n,), or None
        Wave velocities of the discrete family, sites per unit time.
    N : int or None
        Number of sites of each discrete wave; None: automatic.
    tol : float
        Relative tolerance of each wave solve.
    family : Family or None
        An already computed solitary family (overrides V_values, N, tol).
    qc_samples : int
        QC grid points per velocity interval: 0 or an integer in [5, 100000].

    Returns
    -------
    EnergyCriterion
        Discrete and QC samples of E_ren(V), the located extrema with their errors (V in sites
        per unit time), ``stability_may_change``, run time and ``message``.

    Raises
    ------
    ParameterError
        When ``w_plus``, ``qc_samples`` or ``V_values`` is invalid, or a wave of the family
        cannot be set up.
    """
    t0 = time.perf_counter()
    w_plus = require_finite("w_plus", w_plus)
    _check_qc_samples(qc_samples)  # before any wave is solved
    if family is None and V_values is not None:
        Vs = np.sort(require_V_values(V_values))
        family = solitary_family(law, w_plus, Vs, N=N, tol=tol)
    if family is not None:
        res = family.results
        V = np.array([r.V for r in res], dtype=float)
        E = np.array([r.energy for r in res], dtype=float)
        dE = np.array([wave_energy_error(r) for r in res])
        ok = np.array([bool(r.converged) for r in res])
    else:
        V = E = dE = np.zeros(0)
        ok = np.zeros(0, dtype=bool)
    return criterion_from_samples(law, w_plus, V, E, dE, ok, qc_samples, family, t0)


def _samples(**arrays) -> list[np.ndarray]:
    """The sample arrays as 1-D arrays of one length n (``converged`` as bool), else
    ParameterError naming the first that differs (never cut to the shorter one)."""
    out: list = []
    for name, x in arrays.items():
        try:
            arr = np.atleast_1d(np.asarray(x, dtype=bool if name == "converged" else float))
        except (TypeError, ValueError, OverflowError):
            arr = None
        n = out[0].size if out else None
        if arr is None or arr.ndim != 1 or (n is not None and arr.size != n):
            shape = "not numbers" if arr is None else f"shape {arr.shape}"
            raise ParameterError(
                name, shape, "a 1-D array" + (f" of length {n}, like V" if n is not None else "")
            )
        out.append(arr)
    return out


def criterion_from_samples(
    law: HardeningSofteningLaw,
    w_plus: float,
    V: Sequence[float] | np.ndarray,
    energy: Sequence[float] | np.ndarray,
    energy_error: Sequence[float] | np.ndarray,
    converged: Sequence[bool] | np.ndarray,
    qc_samples: int = QC_SAMPLES,
    family: Family | None = None,
    t0: float | None = None,
) -> EnergyCriterion:
    """The criterion from discrete E_ren samples already computed elsewhere (e.g. the waves of
    a Floquet sweep, whose rows carry energy and energy_error): V, energy, energy_error,
    converged : (n,) arrays, any order (non-converged or non-finite samples are ignored).
    qc_samples : QC grid per interval, 0 to skip the QC family (then only the samples count).
    Costs only the parabola fits plus, with qc_samples > 0, the QC grid (cubic: ~1 ms for both
    intervals, ~8 ms with an extremum to refine; other laws ~15 ms per sample).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ of the solitary family.
    V : array_like, shape (n,)
        Wave velocities, sites per unit time.
    energy : array_like, shape (n,)
        E_ren^D at each V (eq. Eren_D), nondimensional energy.
    energy_error : array_like, shape (n,)
        Error bars of ``energy``.
    converged : array_like of bool, shape (n,)
        Whether each wave converged.
    qc_samples : int
        QC grid points per velocity interval: 0 or an integer in [5, 100000].
    family : Family or None
        The family the samples came from, kept on the result.
    t0 : float or None
        ``time.perf_counter()`` at the start of the work (for ``elapsed_s``); None: now.

    Returns
    -------
    EnergyCriterion
        The samples, the located extrema (discrete and QC) with their errors, and the verdict.

    Raises
    ------
    ParameterError
        When ``w_plus`` or ``qc_samples`` is invalid, w₊ has no solitary family, or the sample
        arrays are not 1-D of one length n.
    """
    t0 = time.perf_counter() if t0 is None else t0
    w_plus = require_finite("w_plus", w_plus)
    (a, b), (c, d) = qc.solitary_intervals(law, w_plus)
    _check_qc_samples(qc_samples)
    V, E, dE, conv = _samples(V=V, energy=energy, energy_error=energy_error, converged=converged)
    ok = conv & np.isfinite(E) & np.isfinite(dE)
    ext, qV, qE, qext = [], [], [], []
    for lo, hi in ((a, b), (c, d)):
        sel = ok & (V > lo) & (V < hi)
        if np.count_nonzero(sel) >= 3:
            order = np.argsort(V[sel])
            ext += locate_extrema(V[sel][order], E[sel][order], dE[sel][order])
        if qc_samples:
            gv, ge, ge_ext = qc_interval_extrema(law, w_plus, lo, hi, int(qc_samples))
            qV.append(gv)
            qE.append(ge)
            qext += ge_ext
    in_range = [x for x in qext if V.size and V.min() <= x[0] <= V.max()]
    may = bool(ext or (in_range if V.size else qext))
    n_bad = int(np.count_nonzero(~ok))
    msg = (
        f"{len(ext)} extremum(s) of the discrete E_ren, {len(qext)} of E_ren^QC; "
        f"{n_bad} wave(s) not converged"
    )
    col = lambda xs, k: np.array([x[k] for x in xs], dtype=float)  # noqa: E731
    cat = lambda xs: np.concatenate(xs) if xs else np.zeros(0)  # noqa: E731
    return EnergyCriterion(
        w_plus=w_plus,
        V=V,
        energy=E,
        energy_error=dE,
        wave_converged=ok,
        extrema_V=col(ext, 0),
        extrema_V_error=col(ext, 1),
        extrema_energy=col(ext, 2),
        extrema_kind=tuple(x[3] for x in ext),
        qc_V=cat(qV),
        qc_energy=cat(qE),
        qc_extrema_V=col(qext, 0),
        qc_extrema_V_error=col(qext, 1),
        qc_extrema_energy=col(qext, 2),
        qc_extrema_kind=tuple(x[3] for x in qext),
        stability_may_change=may,
        location_error=float(max([x[1] for x in ext + qext], default=0.0)),
        elapsed_s=time.perf_counter() - t0,
        converged=n_bad == 0,
        message=msg,
        family=family,
    )
