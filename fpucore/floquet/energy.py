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

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from scipy.optimize import minimize_scalar

from fpucore import qc
from fpucore.errors import ParameterError, require_finite
from fpucore.floquet.finite_size import CLASSES
from fpucore.result import Result
from fpucore.wave import Family, solitary_family
from fpucore.wave.family import require_V_values

if TYPE_CHECKING:
    from collections.abc import Sequence

    from fpucore.law.base import HardeningSofteningLaw

QC_SAMPLES = 400  # QC grid points per velocity interval (cubic: one vectorised closed form)
_END_MARGIN = 1e-4  # relative distance from the interval ends (sonic / V_SK) on the QC grid


@dataclass(frozen=True)
class EnergyCriterion(Result):
    """Extrema of E_ren(V) along a solitary-wave family, discrete and QC.

    V, energy, energy_error : (n,) the discrete family (energy_error: the wave's own bound,
    ``WaveResult.energy_error`` where present, else a residual-based indicator, see
    :func:`wave_energy_error`); wave_converged : (n,) bool.
    extrema_V, extrema_V_error, extrema_energy : (k,) located extrema of the discrete E_ren;
    extrema_kind : ("min" | "max", …).
    qc_V, qc_energy : (m,) the QC closed form on a grid over both intervals;
    qc_extrema_V, qc_extrema_V_error, qc_extrema_energy, qc_extrema_kind : the same for E_ren^QC.
    stability_may_change : True where any extremum was found (in the discrete family, or in the
    QC family inside the sampled V range); the criterion is necessary, not sufficient.
    location_error : the largest error bar on V of all extrema found (0 when none).
    """

    w_plus: float
    V: np.ndarray
    energy: np.ndarray
    energy_error: np.ndarray
    wave_converged: np.ndarray
    extrema_V: np.ndarray
    extrema_V_error: np.ndarray
    extrema_energy: np.ndarray
    extrema_kind: tuple
    qc_V: np.ndarray
    qc_energy: np.ndarray
    qc_extrema_V: np.ndarray
    qc_extrema_V_error: np.ndarray
    qc_extrema_energy: np.ndarray
    qc_extrema_kind: tuple
    stability_may_change: bool
    location_error: float
    elapsed_s: float
    converged: bool
    message: str
    family: Family | None = field(default=None, repr=False)

    ERROR_FIELDS: ClassVar = ("location_error",)
    DERIVED: ClassVar = ("status",)
    EXCLUDE: ClassVar = ("family",)

    @property
    def status(self) -> str:
        return "ok" if self.converged else "not_converged"


def wave_energy_error(r) -> float:
    """The wave's E_ren error bar: ``r.energy_error`` when the result carries one, else the
    indicator N·δw·(1 + max|f(w)| + max|v|), δw = max(residual, tail_error, integrator_error)
    (each of the N summands of eq. Eren_D moves by ≤ (|f| + |v|)·δw)."""
    e = float(getattr(r, "energy_error", math.nan))
    if math.isfinite(e):
        return e
    dw = max(float(r.residual), float(r.tail_error), float(r.integrator_error or 0.0))
    scale = 1.0 + float(np.max(np.abs(r.law.f(r.w)))) + float(np.max(np.abs(r.v)))
    return r.N * dw * scale


def _vertex(v: np.ndarray, e: np.ndarray) -> tuple[float, float]:
    """(V*, E″) of the parabola through three points."""
    c2, c1, _ = np.polyfit(v - v[1], e, 2)
    return float(v[1] - c1 / (2.0 * c2)), float(2.0 * c2)


def locate_extrema(V: np.ndarray, E: np.ndarray, dE: np.ndarray) -> list[tuple]:
    """Extrema of sampled E(V) (V ascending, one velocity interval): list of
    (V*, δV*, E*, "min" | "max") from sign changes of successive differences (see module doc)."""
    out = []
    d = np.diff(E)
    for i in range(1, V.size - 1):
        if d[i - 1] == 0.0 or np.sign(d[i - 1]) == np.sign(d[i]):
            continue
        sl = slice(i - 1, i + 2)
        v_star, e2 = _vertex(V[sl], E[sl])
        alts = []
        if i + 2 < V.size:
            alts.append(_vertex(V[i : i + 3], E[i : i + 3])[0])
        if i - 2 >= 0:
            alts.append(_vertex(V[i - 2 : i + 1], E[i - 2 : i + 1])[0])
        stencil = max((abs(a - v_star) for a in alts), default=float(V[i + 1] - V[i - 1]))
        noise = 2.0 * math.sqrt(float(np.max(dE[sl])) / abs(e2)) if e2 != 0 else math.inf
        e_star = float(np.polyval(np.polyfit(V[sl] - V[i], E[sl], 2), v_star - V[i]))
        # kind from the curvature (a tie d[i] == 0 next to the extremum must not flip it)
        out.append((v_star, stencil + noise, e_star, "min" if e2 > 0 else "max"))
    return out


def qc_energy_grid(law, w_plus: float, lo: float, hi: float, n: int):
    """(V, E_ren^QC, its error bound) on n points of (lo, hi) (one velocity interval, the ends
    moved in by _END_MARGIN of its width).  The cubic: all at once by the closed form
    (:func:`fpucore.qc.solitary_closed_form`, the formulas of :func:`fpucore.qc.solitary`;
    background w₊ below V_SK, w_S(V) above it); other laws point by point."""
    span = hi - lo
    V = np.linspace(lo + _END_MARGIN * span, hi - _END_MARGIN * span, n)
    if qc.is_closed_form(law):
        v_sk = qc.sound_speeds(law, w_plus)[1]
        w_B = np.full_like(V, w_plus) if hi <= v_sk else qc.w_S(law, w_plus, V)
        _, _, _, E, dE, ok = qc.solitary_closed_form(law, w_B, V)
        if np.all(ok):
            return V, np.asarray(E, float), np.asarray(dE, float)
    sols = [qc.solitary(law, w_plus, float(v)) for v in V]
    return V, np.array([s.energy for s in sols]), np.array([s.energy_error for s in sols])


def _qc_interval(law, w_plus: float, lo: float, hi: float, n: int):
    """QC grid on (lo, hi) and its refined extrema."""
    V, E, dE = qc_energy_grid(law, w_plus, lo, hi, n)
    ext = []
    for v0, _, _, kind in locate_extrema(V, E, dE):
        j = int(np.clip(np.searchsorted(V, v0), 1, V.size - 1))
        a, b = float(V[max(j - 2, 0)]), float(V[min(j + 1, V.size - 1)])
        sgn = 1.0 if kind == "min" else -1.0
        res = minimize_scalar(
            lambda v, s=sgn: s * qc.solitary(law, w_plus, v).energy,
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-12 * b},
        )
        h = 1e-3 * (b - a)
        es = [qc.solitary(law, w_plus, float(res.x) + k * h).energy for k in (-1, 0, 1)]
        e2 = (es[0] - 2 * es[1] + es[2]) / (h * h)
        de = qc.solitary(law, w_plus, float(res.x)).energy_error
        dv = 1e-12 * b + (2.0 * math.sqrt(de / abs(e2)) if e2 != 0 else math.inf)
        ext.append((float(res.x), dv, float(es[1]), kind))
    return V, E, ext


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
            gv, ge, ge_ext = _qc_interval(law, w_plus, lo, hi, int(qc_samples))
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
