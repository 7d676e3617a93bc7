"""Continuation in V for discrete traveling waves, and whole families (paper §5, Figs. TWcubic,
SWs_cubic_DvsQC, SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC).

Predictor.  From a converged wave x(V₀) the guess at V₁ is x(V₀) + [x_QC(V₁) − x_QC(V₀)]: the QC
closed form carries the large, known change of the profile (width, boundary states, w_S(V)) and
the discrete correction x − x_QC, which varies slowly in V, is carried over.  States on chains
of different N are re-centred and padded with the tail states (:func:`fpucore.wave.resize`).

:func:`continue_to` is the rescue used by ``wave.solve_*`` when Newton from the QC guess fails:
find a nearby velocity (towards the middle of the family's interval) where the QC guess converges,
then march to the target with adaptive steps (halve on failure, grow on success).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from . import qc
from .errors import ParameterError
from .wave_system import newton


def _interval(law, spec) -> tuple[float, float]:
    if spec.kind == "superkink":
        return qc.superkink_velocity_bounds(law)
    (a, b), (c, d) = qc.solitary_intervals(law, spec.w_plus)
    return (a, b) if spec.V < b else (c, d)


def _respec(law, spec, V):
    from . import wave

    if spec.kind == "superkink":
        return wave._superkink_spec(law, V, spec.branch)
    return wave._solitary_spec(law, spec.w_plus, V)


def qc_shift_predictor(law, spec_new, x_old: np.ndarray, N_old: int, spec_old):
    """Callable N ↦ predicted interleaved state at spec_new.V on N sites (see module doc)."""
    from . import wave

    def predict(N: int) -> np.ndarray:
        x = wave.resize(x_old, N_old, N, spec_old.w_left, spec_old.w_right)
        return x + wave.qc_guess(spec_new, N) - wave.qc_guess(spec_old, N)

    return predict


def _easy_end(law, spec) -> float:
    """The end of the family's V interval where the QC guess is accurate: the sonic limit for
    solitary waves (small amplitude), the upper velocity bound for superkinks (weak, wide)."""
    lo, hi = _interval(law, spec)
    if spec.kind == "superkink":
        return hi
    (a, b), _ = qc.solitary_intervals(law, spec.w_plus)
    return lo if (lo, hi) == (a, b) else hi


def continue_to(
    law, spec, tol, jacobian, budget_s, max_iter: int = 40, max_steps: int = 80, N_cap: int = 4000
):
    """March in V from a velocity where the QC guess converges to spec.V.

    Start candidates lie towards the family's easy end (:func:`_easy_end`), then towards the middle
    of the interval.  The path runs on the shortest chain that holds both ends (automatic N,
    at most N_cap sites).  Returns (x, N, note) with x the interleaved state at spec.V on N sites,
    or (None, 0, note) on failure.
    """
    from . import wave

    t0 = time.perf_counter()
    lo, hi = _interval(law, spec)
    easy, mid = _easy_end(law, spec), 0.5 * (lo + hi)
    left = lambda: budget_s - (time.perf_counter() - t0)  # noqa: E731
    scale = max(1.0, abs(spec.w_left), abs(spec.w_right))
    N_t = wave._required_N(law, spec, 0.1 * tol * scale)
    start = None
    for target, frac in ((easy, 0.3), (easy, 0.6), (easy, 0.85), (mid, 0.3), (mid, 0.7)):
        if left() <= 0:
            break
        Vs = spec.V + frac * (target - spec.V)
        if not lo < Vs < hi:
            continue
        sp = _respec(law, spec, Vs)
        N = max(N_t, wave._required_N(law, sp, 0.1 * tol * scale))
        if N > N_cap:
            continue
        x0 = wave.qc_guess(sp, N)
        m = wave._choose_m(law, sp, x0, N, tol * scale)
        K = wave._choose_K(law, sp, x0, m)
        o = newton(
            wave._system(law, sp, N, m, K), x0, tol * scale, max_iter, jacobian, max(1.0, left())
        )
        if o.converged:
            start = (sp, o.x, N, m, K)
            break
    if start is None:
        return None, 0, "continuation: no converged start velocity found"
    sp, x, N, m, K = start
    V_start = sp.V
    # march in s = log|V − V_SK| for solitary waves (the profile changes like log|V − V_SK| near
    # the superkink limit), in s = V for superkinks; secant predictor once two points exist
    if spec.kind == "superkink":
        to_s, to_V = (lambda V: V), (lambda s_: s_)
    else:
        vsk = qc.sound_speeds(law, spec.w_plus)[1]
        sgn = 1.0 if spec.V > vsk else -1.0
        to_s = lambda V: np.log(abs(V - vsk))  # noqa: E731
        to_V = lambda s_: vsk + sgn * np.exp(s_)  # noqa: E731
    s0, s_t = to_s(sp.V), to_s(spec.V)
    ds = (s_t - s0) / 4.0
    prev = None  # (s, x) of the point before the current one
    steps = 0
    while steps < max_steps and left() > 0:
        last = abs(s_t - s0) <= abs(ds)
        s1 = s_t if last else s0 + ds
        V1 = spec.V if last else float(to_V(s1))
        sp1 = _respec(law, spec, V1)
        if prev is not None:
            pred = x + (x - prev[1]) * ((s1 - s0) / (s0 - prev[0]))
        else:
            pred = qc_shift_predictor(law, sp1, x, N, sp)(N)
        o = newton(
            wave._system(law, sp1, N, m, K),
            pred,
            tol * scale,
            min(25, max_iter),
            jacobian,
            max(1.0, left()),
        )
        steps += 1
        if o.converged:
            prev = (s0, x)
            sp, x, s0 = sp1, o.x, s1
            if last:
                return x, N, f"continuation from V={V_start:.6g} in {steps} steps on N={N}"
            ds *= 1.5
        else:
            ds *= 0.5
            if abs(ds) < 1e-9 * abs(s_t - to_s(V_start)):
                break
    return None, 0, f"continuation stalled at V={sp.V:.8g} after {steps} steps"


# =============================================================================== families
@dataclass(frozen=True)
class Family:
    """A family of discrete waves over V.  kind : "superkink" | "solitary".
    results : list of WaveResult (V in the order requested); V, amplitude, energy, residual,
    qc_max_deviation : arrays; converged : bool array."""

    kind: str
    results: list
    V: np.ndarray
    converged: np.ndarray
    amplitude: np.ndarray
    energy: np.ndarray
    residual: np.ndarray
    qc_max_deviation: np.ndarray
    elapsed_s: float

    @property
    def all_converged(self) -> bool:
        return bool(np.all(self.converged))


def _check_V_values(V_values) -> np.ndarray:
    V = np.atleast_1d(np.asarray(V_values, dtype=float))
    if V.ndim != 1 or V.size == 0 or not np.all(np.isfinite(V)):
        raise ParameterError("V_values", V_values, "a non-empty 1-D array of finite velocities")
    return V


def superkink_family(
    law, V_values, branch: str = "lower", N: int | None = None, tol: float = 1e-12, progress=None
) -> Family:
    """Discrete superkinks at each V (continuation with the QC-shift predictor).  Sort V_values
    so neighbours are close; each point is solved independently if its predictor fails."""
    from . import wave

    V = _check_V_values(V_values)
    specs = [wave._superkink_spec(law, float(v), branch) for v in V]  # validates every V first

    def solve(v, pred):
        return wave.solve_superkink(law, v, branch, N, tol, predictor=pred)

    return _family_wrap(law, specs, solve, "superkink", progress)


def solitary_family(
    law, w_plus: float, V_values, N: int | None = None, tol: float = 1e-12, progress=None
) -> Family:
    """Discrete solitary waves for state w₊ at each V in (c₊, V_SK) ∪ (V_SK, c₋)."""
    from . import wave

    V = _check_V_values(V_values)
    specs = [wave._solitary_spec(law, w_plus, float(v)) for v in V]

    def solve(v, pred):
        return wave.solve_solitary(law, w_plus, v, N, tol, predictor=pred)

    return _family_wrap(law, specs, solve, "solitary", progress)


def _family_wrap(law, specs, solve, kind, progress):
    """Solve specs in order; each uses the previous converged wave (same interval) as predictor."""
    t0 = time.perf_counter()
    results, prev = [], None
    for i, sp in enumerate(specs):
        r = None
        if prev is not None and _interval(law, prev[1]) == _interval(law, sp):
            r_prev, sp_prev = prev
            x_prev = np.empty(2 * r_prev.N)
            x_prev[0::2], x_prev[1::2] = r_prev.w, r_prev.wdot
            r = solve(sp.V, qc_shift_predictor(law, sp, x_prev, r_prev.N, sp_prev))
        if r is None or not r.converged:
            r = solve(sp.V, None)
        results.append(r)
        prev = (r, sp) if r.converged else None
        if progress is not None:
            progress(i + 1, len(specs), r)
    arr = lambda k: np.array([getattr(r, k) for r in results])  # noqa: E731
    return Family(
        kind,
        results,
        arr("V"),
        arr("converged"),
        arr("amplitude"),
        arr("energy"),
        arr("residual"),
        arr("qc_max_deviation"),
        time.perf_counter() - t0,
    )
