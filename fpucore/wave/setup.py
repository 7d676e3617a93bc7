"""What a discrete-wave solve is set up from (paper §5): the wave's specification (boundary
states, pinning, QC guess, eqs. fixedBCs, SKsoln_cubic, SWsoln_cubic; built by :func:`spec_of`
from (kind, row, V)), its strain scale and the tolerances derived from it (:class:`Tolerances`),
the chain length N from the tail decay, the RK step count m by step doubling, the tangent window
K, and the Newton system.

Shared by the driver (:mod:`.driver`), continuation (:mod:`.continuation`), families and the
Floquet sweep; it imports none of them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError, fmt_interval
from fpucore.wave import period_map as pm
from fpucore.wave import tails as wt
from fpucore.wave.system import WaveSystem

M_STEPS = (6, 8, 10, 12, 14, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128)
"""Candidate RK steps per period, tried in order by :func:`choose_m`."""
FLOOR_FACTOR = 4.0  # accept residuals / step-doubling errors up to this × the round-off level


def strain_scale(w_left: float, w_right: float) -> float:
    """s = max(1, |w_left|, |w_right|): the round-off of eq. nonlin_system grows with |w|, so
    every tolerance of a solve is relative to s (:class:`Tolerances`)."""
    return max(1.0, abs(w_left), abs(w_right))


@dataclass(frozen=True)
class Spec:
    """Everything fixed by (law, kind, w_plus/branch, V): boundary states, pinning, QC guess."""

    kind: str
    V: float
    w_left: float
    w_right: float
    w_plus: float
    pin: str
    pin_value: float
    qcw: object  # QC object with profile/dprofile
    amplitude_qc: float
    branch: str | None

    @property
    def row(self):
        """What fixes the family besides V: the branch of a superkink, w₊ of a solitary wave
        (:func:`spec_of`'s ``row``, an atlas row)."""
        return self.branch if self.kind == "superkink" else self.w_plus

    @property
    def scale(self) -> float:
        """The strain scale (:func:`strain_scale`) of the boundary states."""
        return strain_scale(self.w_left, self.w_right)


def spec_of(law, kind: str, row, V: float) -> Spec:
    """The wave of ``kind`` at velocity V on the family ``row`` (the branch of a superkink, w₊
    of a solitary wave).  Raises ParameterError outside the existence region."""
    if kind == "superkink":
        return superkink_spec(law, V, row)
    return solitary_spec(law, row, V)


def superkink_spec(law, V, branch) -> Spec:
    sk = qc.superkink_from_V(law, V, branch)  # validates V and branch
    return Spec(
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


def solitary_spec(law, w_plus, V) -> Spec:
    sw = qc.solitary(law, w_plus, V)  # validates w_plus and V
    return Spec(sw.kind, sw.V, sw.w_B, sw.w_B, sw.w_plus, "wd", 0.0, sw, sw.amplitude, None)


def qc_guess(spec: Spec, N: int) -> np.ndarray:
    """Interleaved (w_n, ẇ_n) from the QC profile: ẇ_n(0) = −V w′(n)."""
    n = (np.arange(N) - N // 2).astype(float)
    x = np.empty(2 * N)
    with np.errstate(over="ignore"):  # cosh overflow far in the tails → w′ = 0 there
        x[0::2] = spec.qcw.profile(n)
        x[1::2] = -spec.V * np.nan_to_num(spec.qcw.dprofile(n))
    return x


def resize(x: np.ndarray, N_old: int, N_new: int, w_left: float, w_right: float) -> np.ndarray:
    """Re-centre an interleaved state on a chain of N_new sites (pad with the tail states)."""
    n_new = np.arange(N_new) - N_new // 2
    y = np.empty(2 * N_new)
    y[0::2] = np.where(n_new < 0, w_left, w_right)
    y[1::2] = 0.0
    idx = n_new + N_old // 2
    ok = (idx >= 0) & (idx < N_old)
    y[0::2][ok] = x[0::2][idx[ok]]
    y[1::2][ok] = x[1::2][idx[ok]]
    return y


def required_N(law, spec: Spec, tail_tol: float) -> int:
    L = wt.required_half_width(
        law, spec.V, spec.qcw.profile, spec.w_left, spec.w_right, spec.amplitude_qc, tail_tol
    )
    return wt.auto_N(L)


def auto_N(law, spec: Spec, tol: float) -> int:
    """The chain ``N=None`` chooses: tails resolved to the solve's tail tolerance."""
    return required_N(law, spec, Tolerances.of(spec, tol).tail_tol)


def smallest_N(law, spec: Spec) -> int:
    """The shortest chain accepted for the wave: its tails cut at 1e-6 of the amplitude."""
    return required_N(law, spec, 1e-6 * spec.amplitude_qc)


def choose_N(law, spec: Spec, N, tol) -> int:
    """Automatic N, or validate the user's N against the wave's width."""
    if N is None:
        N_auto = auto_N(law, spec, tol)
        if N_auto > wt.N_MAX:
            raise ParameterError(
                "V",
                spec.V,
                valid_V(law, spec),
                f"the wave is too wide here: its tails need N = {fmt_N(N_auto)} sites "
                f"(> N_MAX = {wt.N_MAX}); move V away from the sonic / superkink limit",
            )
        return N_auto
    if isinstance(N, bool) or not isinstance(N, (int, np.integer)):
        raise ParameterError("N", N, "an even integer")
    N = int(N)
    if N % 2 or not (wt.N_MIN <= N <= wt.N_MAX):
        raise ParameterError("N", N, f"an even integer in [{wt.N_MIN}, {wt.N_MAX}]")
    N_fit = smallest_N(law, spec)
    if N < N_fit:
        raise ParameterError(
            "N",
            N,
            f"N >= {fmt_N(N_fit)} for this wave",
            "N too small for the wave width (tails would be cut at > 1e-6 of the amplitude); "
            "use N=None for automatic N",
        )
    return N


def fmt_N(N: int) -> str:
    return str(N) if N < 10**9 else "unbounded"


def valid_V(law, spec: Spec) -> str:
    if spec.kind == "superkink":
        return fmt_interval(*qc.superkink_velocity_bounds(law, spec.branch))
    (a, b), (c, d) = qc.solitary_intervals(law, spec.w_plus)
    return f"{fmt_interval(a, b)} or {fmt_interval(c, d)}"


def choose_m(law, spec: Spec, x: np.ndarray, N: int, int_tol: float, m_min: int = 6) -> int:
    """Smallest m in M_STEPS (≥ m_min) whose step-doubling error at x is ≤ int_tol."""
    w, wd = x[0::2], x[1::2]
    for m in M_STEPS:
        if m < m_min:
            continue
        e = pm.step_doubling_error(law, w, wd, 1.0 / spec.V, m, spec.w_left, spec.w_right)
        if e <= int_tol:
            return m
    return M_STEPS[-1]


def choose_m_floor(law, spec: Spec, x: np.ndarray, int_tol: float, m_min: int = 6) -> int:
    """Smallest m in M_STEPS (≥ m_min) whose step-doubling error at x is ≤ max(int_tol,
    FLOOR_FACTOR × round-off level of the map): no more steps once round-off dominates."""
    w, wd = x[0::2], x[1::2]
    T = 1.0 / spec.V
    for m in M_STEPS:
        if m < m_min:
            continue
        e = pm.step_doubling_error(law, w, wd, T, m, spec.w_left, spec.w_right)
        floor = max(pm.roundoff_level(law, w, wd, T, 2 * m))
        if e <= max(int_tol, FLOOR_FACTOR * floor):
            return m
    return M_STEPS[-1]


def choose_K(law, spec: Spec, x: np.ndarray, m: int) -> int:
    res = pm.integrate(
        law, x[0::2], x[1::2], 1.0 / spec.V, m, spec.w_left, spec.w_right, store_df=True
    )
    return pm.spread_radius(res, level=1e-18) + 2


@dataclass(frozen=True)
class Tolerances:
    """Every tolerance of one solve (absolute unless said), from the user's relative ``tol``.

    scale     strain scale s = max(1, |w_left|, |w_right|) (:func:`strain_scale`): round-off of
              eq. nonlin_system grows with |w| (b = 100 or a = −0.01 stagnate at ~3e-14·s).
    res_tol   Newton accepts max-norm residual ≤ res_tol = tol·s (raised to the round-off
              level of the system where that is larger: see :class:`.attempt.WaveSolve`).
    step_tol  Newton keeps stepping until its next correction (strain units, max(|δw|, T|δẇ|))
              is ≤ step_tol = tol·s, or the corrections stop shrinking (round-off).
    int_tol   step count m: step-doubling error of the period map ≤ int_tol = tol·s.
    tail_tol  automatic N: the tails decay to tail_tol = 0.1·tol·s at the chain's ends.
    tail_ok   a converged wave whose tails miss the boundary states by more than
              1e-5·A_QC + 1e3·tol·s is another wave (rejected).
    """

    tol: float
    scale: float
    res_tol: float
    step_tol: float
    int_tol: float
    tail_tol: float
    tail_ok: float

    @classmethod
    def of(cls, spec: Spec, tol: float) -> Tolerances:
        s = spec.scale
        t = tol * s
        return cls(tol, s, t, t, t, 0.1 * t, 1e-5 * spec.amplitude_qc + 1e3 * t)


def build_system(law, spec: Spec, N: int, m: int, K: int) -> WaveSystem:
    return WaveSystem(law, spec.V, N, spec.w_left, spec.w_right, spec.pin, spec.pin_value, m, K)
