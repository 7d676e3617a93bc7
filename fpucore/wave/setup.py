"""What a discrete-wave solve is set up from (paper §5): :class:`Spec`, the wave fixed by
(law, kind, w₊ or branch, V), and what derives from it alone.

A Spec holds the law, the boundary strains w_left, w_right of eq. fixedBCs, the pinning and the
QC wave (eqs. SKsoln_cubic, SWsoln_cubic; quadrature for a general law); it is built by
:func:`spec_of` from (kind, row, V).  It owns: the strain scale and the :class:`Tolerances` of a
solve, the QC guess, the chain length N from the tail decay (:mod:`.tails`), the RK step count
m by step doubling, the tangent window K, the Newton system (:class:`.system.WaveSystem`), the
velocity interval of its family (eq. V_bounds_cubic; (c₊, V_SK) or (V_SK, c₋), eqs. cplus,
cminus) and the QC-shift predictor from a converged neighbour.  Units: strains w and velocities
V in the law's units, ẇ in strain per unit time, N and K in sites, m in RK steps per period
T = 1/V.

Shared by the solve (:mod:`.attempt`, :mod:`.driver`), continuation (:mod:`.continuation`),
families (:mod:`.family`) and the atlas; it imports none of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError, fmt_interval
from fpucore.law import require_law
from fpucore.law.scale import require_discrete
from fpucore.wave import period_map as pm
from fpucore.wave import tails as wt
from fpucore.wave.compact import compact_wave
from fpucore.wave.system import WaveSystem
from fpucore.wave.tails import fmt_N, resize
from fpucore.wave.tolerances import FLOOR_FACTOR, Tolerances, strain_scale

if TYPE_CHECKING:
    from collections.abc import Callable

    from fpucore.law import HardeningSofteningLaw

M_STEPS = (6, 8, 10, 12, 14, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128)
"""Candidate RK steps per period, tried in order by :meth:`Spec.choose_m`."""


@dataclass(frozen=True)
class Spec:
    """Everything fixed by (law, kind, w₊ or branch, V); see the module doc.

    law : the force law f(w).  kind : "superkink" | "tensile" | "compressive".  V : velocity.
    w_left, w_right : boundary strains w_{−N/2−1}, w_{N/2} (eq. fixedBCs: w₋, w₊ of a
    superkink, w_B twice for a solitary wave).  w_plus : the state ahead of the superkink.
    pin, pin_value : "w" with w_1(T) = pin_value (superkink: the QC profile's centre w(0)) or
    "wd" with ẇ_1(T) = 0 (solitary wave).  qcw : the QC wave (``profile``, ``dprofile``).
    amplitude_qc : its amplitude.  branch : a superkink's "lower" | "upper" (None otherwise).
    """

    law: HardeningSofteningLaw
    kind: str
    V: float
    w_left: float
    w_right: float
    w_plus: float
    pin: str
    pin_value: float
    qcw: Any
    amplitude_qc: float
    branch: str | None

    @property
    def row(self) -> str | float | None:
        """What fixes the family besides V: the branch of a superkink, w₊ of a solitary wave
        (:func:`spec_of`'s ``row``, an atlas row)."""
        return self.branch if self.kind == "superkink" else self.w_plus

    @property
    def scale(self) -> float:
        """The strain scale (:func:`strain_scale`) of the boundary states."""
        return strain_scale(self.w_left, self.w_right)

    @property
    def v_sk(self) -> float:
        """V_SK(w₊): the velocity of the superkink whose state ahead is w₊, the limit between a
        solitary family's two intervals (a superkink's own V)."""
        return qc.sound_speeds(self.law, self.w_plus)[1]

    def at(self, V: float) -> Spec:
        """The same wave (law, kind, branch or w₊) at another velocity."""
        return spec_of(self.law, self.kind, self.row, V)

    def tolerances(self, tol: float) -> Tolerances:
        """Every tolerance of a solve to the relative ``tol`` (:class:`Tolerances`)."""
        return Tolerances.of(self, tol)

    # ------------------------------------------------------------------ velocities
    def intervals(self) -> tuple[tuple[float, float], ...]:
        """The open V intervals where the family exists: the superkink interval of the branch
        (eq. V_bounds_cubic for the cubic; branches differ for a general law), or (c₊, V_SK)
        and (V_SK, c₋) for solitary waves (eqs. cplus, cminus)."""
        if self.kind == "superkink":
            return (qc.superkink_velocity_bounds(self.law, self.branch),)  # type: ignore[arg-type]
        return qc.solitary_intervals(self.law, self.w_plus)

    def interval(self) -> tuple[float, float]:
        """The interval of :meth:`intervals` that holds V."""
        iv = self.intervals()
        return iv[0] if len(iv) == 1 or self.V < iv[0][1] else iv[1]

    def valid_V(self) -> str:
        """:meth:`intervals` as the valid range of a ParameterError."""
        return " or ".join(fmt_interval(a, b) for a, b in self.intervals())

    def easy_end(self) -> float:
        """The end of V's interval where the QC guess is accurate: the sonic limit for solitary
        waves (small amplitude: c₊ below V_SK, c₋ above), the upper velocity bound for
        superkinks (weak, wide).  A piecewise-linear law's solitary waves: the superkink limit
        V_SK, where the QC kink–antikink profile is close to the discrete flat top (measured:
        Newton from the QC guess converges at 1.75–1.85 for the trilinear law w₁ = 0.5, w₂ = 1.5,
        E = 1, 4, 0.2, w₊ = 0.3, V_SK = 1.769, and fails at 1.02–1.6: the sonic limit keeps an
        amplitude through the hard regime there, no small-amplitude wave)."""
        lo, hi = self.interval()
        if self.kind == "superkink":
            return hi
        if hasattr(self.law, "breakpoints"):
            return hi if (lo, hi) == self.intervals()[0] else lo
        return lo if (lo, hi) == self.intervals()[0] else hi

    # ------------------------------------------------------------------ initial states
    def qc_guess(self, N: int) -> np.ndarray:
        """Interleaved (w_n, ẇ_n) on N sites from the QC profile (ansatz ξ = n − Vt):
        w_n(0) = w_QC(n), ẇ_n(0) = −V w_QC′(n)."""
        n = (np.arange(N) - N // 2).astype(float)
        x = np.empty(2 * N)
        with np.errstate(over="ignore"):  # cosh overflow far in the tails → w′ = 0 there
            x[0::2] = self.qcw.profile(n)
            x[1::2] = -self.V * np.nan_to_num(self.qcw.dprofile(n))
        return x

    def first_guess(self, N: int) -> tuple[np.ndarray, str]:
        """The start of a solve without predictor, and its name: the explicit compact wave
        (:mod:`fpucore.wave.compact`, an exact solution of eq. TW_discrete) for a solitary wave
        on the zero-modulus regime of a degenerate PL law at V below its v_max — there the QC
        profile is far from the discrete wave (measured 0.08 off at V = 0.5 for an amplitude of
        0.35, and Newton stalls from it) — else the QC profile (:meth:`qc_guess`)."""
        if self.kind != "superkink" and hasattr(self.law, "breakpoints"):
            try:
                cw = compact_wave(self.law, self.V, self.w_left)
            except ParameterError:
                cw = None
            if cw is not None and cw.converged:
                x = np.empty(2 * N)
                x[0::2], x[1::2] = cw.lattice(np.arange(N) - N // 2)
                return x, "compact-guess"
        return self.qc_guess(N), "qc-guess"

    def shifted(self, x_old: np.ndarray, N_old: int, old: Spec) -> Callable[[int], np.ndarray]:
        """The QC-shift predictor: callable N ↦ the state x_old (N_old sites, converged at
        ``old``, the same family at another V) carried to this V as
        x_old + [x_QC(V) − x_QC(V_old)] on N sites.  The QC closed form carries the large,
        known change of the profile (width, boundary states, w_S(V)); the discrete correction
        x − x_QC varies slowly in V and is kept.  Chains of different N are re-centred and
        padded with the tail states (:func:`resize`)."""

        def predict(N: int) -> np.ndarray:
            x = resize(x_old, N_old, N, old.w_left, old.w_right)
            return x + self.qc_guess(N) - old.qc_guess(N)

        return predict

    def neighbour_predictor(
        self, prev: tuple[Any, Spec] | None
    ) -> Callable[[int], np.ndarray] | None:
        """:meth:`shifted` from the converged neighbour prev = (wave, its spec), or None when
        there is none or it lies on another velocity interval of the family."""
        if prev is None:
            return None
        r_prev, sp_prev = prev
        if sp_prev.interval() != self.interval():
            return None
        x_prev = np.empty(2 * r_prev.N)
        x_prev[0::2], x_prev[1::2] = r_prev.w, r_prev.wdot
        return self.shifted(x_prev, r_prev.N, sp_prev)

    # ------------------------------------------------------------------ chain length N
    def required_N(self, tail_tol: float) -> int:
        """The chain (sites) on which the QC tails decay to within tail_tol (strain units) of
        the boundary states at both ends (:mod:`.tails`)."""
        L = wt.required_half_width(
            self.law,
            self.V,
            self.qcw.profile,
            self.w_left,
            self.w_right,
            self.amplitude_qc,
            tail_tol,
        )
        return wt.auto_N(L)

    def auto_N(self, tol: float) -> int:
        """The chain ``N=None`` chooses: tails resolved to the solve's tail tolerance."""
        return self.required_N(self.tolerances(tol).tail_tol)

    def smallest_N(self) -> int:
        """The shortest chain accepted for the wave: its tails cut at 1e-6 of the amplitude."""
        return self.required_N(1e-6 * self.amplitude_qc)

    def choose_N(self, N: int | None, tol: float) -> int:
        """Automatic N (``N=None``: :meth:`auto_N`), or the user's N validated against the
        wave's width (an even integer in [N_MIN, N_MAX], at least :meth:`smallest_N`)."""
        if N is None:
            N_auto = self.auto_N(tol)
            if N_auto > wt.N_MAX:
                raise ParameterError(
                    "V",
                    self.V,
                    self.valid_V(),
                    f"the wave is too wide here: its tails need N = {fmt_N(N_auto)} sites "
                    f"(> N_MAX = {wt.N_MAX}); move V away from the sonic / superkink limit",
                )
            return N_auto
        if isinstance(N, bool) or not isinstance(N, (int, np.integer)):
            raise ParameterError("N", N, "an even integer")
        N = int(N)
        if N % 2 or not (wt.N_MIN <= N <= wt.N_MAX):
            raise ParameterError("N", N, f"an even integer in [{wt.N_MIN}, {wt.N_MAX}]")
        N_fit = self.smallest_N()
        if N < N_fit:
            raise ParameterError(
                "N",
                N,
                f"N >= {fmt_N(N_fit)} for this wave",
                "N too small for the wave width (tails would be cut at > 1e-6 of the amplitude); "
                "use N=None for automatic N",
            )
        return N

    # ------------------------------------------------------------------ steps m, window K
    def choose_m(self, x: np.ndarray, int_tol: float, m_min: int = 6) -> int:
        """Smallest m in M_STEPS (≥ m_min) whose step-doubling error of the period map at x
        (eq. nonlin_map; max |Φ_m − Φ_2m|, strain units) is ≤ int_tol."""
        w, wd = x[0::2], x[1::2]
        for m in M_STEPS:
            if m < m_min:
                continue
            e = pm.step_doubling_error(self.law, w, wd, 1.0 / self.V, m, self.w_left, self.w_right)
            if e <= int_tol:
                return m
        return M_STEPS[-1]

    def choose_m_floor(self, x: np.ndarray, int_tol: float, m_min: int = 6) -> int:
        """Smallest m in M_STEPS (≥ m_min) whose step-doubling error at x is ≤ max(int_tol,
        FLOOR_FACTOR × round-off level of the map).  A piecewise-linear law's m must also pass
        with the next m, and its step stay below 1/ω_max, ω_max = 2√(max E): a step as long as
        a bond's passage through a regime gives m and 2m the same wrong map by accident (a
        compact wave at V = 0.15, m = 6: estimate 5e-15, true error 1e-6; at V = 0.09 m = 8
        and 10 both agree).  Smooth laws keep the plain rule (their estimate is asymptotic)."""
        w, wd = x[0::2], x[1::2]
        T = 1.0 / self.V
        slopes = getattr(self.law, "slopes", None)
        piecewise = slopes is not None
        if slopes is not None:
            m_min = max(m_min, math.ceil(2.0 * T * math.sqrt(max(slopes))))
        ms = [m for m in M_STEPS if m >= m_min]
        for m, m_next in zip(ms, ms[1:] + [None]):
            checked = (m, m_next) if piecewise and m_next is not None else (m,)
            if all(self._doubling_ok(w, wd, T, k, int_tol) for k in checked):
                return m
        return M_STEPS[-1]

    def _doubling_ok(self, w, wd, T: float, m: int, int_tol: float) -> bool:
        e = pm.step_doubling_error(self.law, w, wd, T, m, self.w_left, self.w_right)
        floor = max(pm.roundoff_level(self.law, w, wd, T, 2 * m))
        return bool(e <= max(int_tol, FLOOR_FACTOR * floor))

    def choose_K(self, x: np.ndarray, m: int) -> int:
        """Tangent window half-width K (sites): how far a perturbation at x spreads in one
        period (tangent entries above 1e-18), plus 2."""
        res = pm.integrate(
            self.law, x[0::2], x[1::2], 1.0 / self.V, m, self.w_left, self.w_right, store_df=True
        )
        return pm.spread_radius(res, level=1e-18) + 2

    def system(self, N: int, m: int, K: int) -> WaveSystem:
        """The 2N equations of eq. nonlin_system for this wave on N sites (m RK steps per
        period, tangent window K)."""
        return WaveSystem(
            self.law, self.V, N, self.w_left, self.w_right, self.pin, self.pin_value, m, K
        )


def spec_of(law: HardeningSofteningLaw, kind: str, row: Any, V: float) -> Spec:
    """The wave of ``kind`` at velocity V on the family ``row`` (the branch of a superkink, w₊
    of a solitary wave).  Raises ParameterError outside the existence region.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    kind : str
        ``"superkink"``; any other value gives a solitary wave.
    row : str or float
        The branch (``"lower"``/``"upper"``) of a superkink, or the strain w₊ of a solitary wave.
    V : float
        Wave velocity, sites per unit time.

    Returns
    -------
    Spec
        The wave's specification (law, V, boundary strains, pinning, QC predictor).

    Raises
    ------
    ParameterError
        Outside the existence region (V, branch or w₊ invalid), or for a law refused by the
        discrete solver.
    """
    if kind == "superkink":
        return superkink_spec(law, V, row)
    return solitary_spec(law, row, V)


def superkink_spec(law: HardeningSofteningLaw, V: float, branch: str) -> Spec:
    """The superkink of ``branch`` at V: w_left = w₋, w_right = w₊ (eq. wpm_cubic for the
    cubic), pinned at the QC profile's centre.

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    V : float
        Wave velocity, sites per unit time, in the superkink interval (eq. V_bounds_cubic).
    branch : {"lower", "upper"}
        Which superkink of the pair at V.

    Returns
    -------
    Spec
        Pinned by w(0) = w_center (w* for the cubic, (w₊ + w₋)/2 for a general law).

    Raises
    ------
    ParameterError
        When ``law``, ``V`` or ``branch`` is invalid.
    """
    require_discrete(require_law(law))  # a law whose f' has no digits left is refused first
    sk = qc.superkink_from_V(law, V, branch)  # validates V and branch
    return Spec(
        law,
        "superkink",
        sk.V,
        sk.w_minus,
        sk.w_plus,
        sk.w_plus,
        "w",
        sk.w_center,  # w(0): w* for the cubic, (w₊ + w₋)/2 for a general law
        sk,
        sk.amplitude,
        branch,
    )


def solitary_spec(law: HardeningSofteningLaw, w_plus: float, V: float) -> Spec:
    """The solitary wave for w₊ at V: w_left = w_right = w_B (w₊ below V_SK, w_S(V) above:
    eq. wB), pinned by ẇ_1(T) = 0 (the extremum at n = 0).

    Parameters
    ----------
    law : HardeningSofteningLaw
        The spring law f(w).
    w_plus : float
        Strain w₊ ahead of the associated superkink.
    V : float
        Wave velocity, sites per unit time, in (c₊, V_SK) ∪ (V_SK, c₋).

    Returns
    -------
    Spec
        The solitary wave's specification (w_left = w_right = w_B).

    Raises
    ------
    ParameterError
        When ``law``, ``w_plus`` or ``V`` is invalid.
    """
    require_discrete(require_law(law))
    sw = qc.solitary(law, w_plus, V)  # validates w_plus and V
    return Spec(law, sw.kind, sw.V, sw.w_B, sw.w_B, sw.w_plus, "wd", 0.0, sw, sw.amplitude, None)
