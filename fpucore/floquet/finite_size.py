"""Is an excess |μ| − 1 a property of the wave or of the finite ring?  (paper §6)

The paper reports mild oscillatory instabilities (max |μ| − 1 ≈ 1e-4 … 5e-3 at N = 500) whose
size "decreases as the chain size is increased" and calls them a spurious artefact of the finite
chain.  Mechanism: the continuous spectrum of the ring.  Phonon multipliers are spaced by ~2π/N
on the unit circle; when two of opposite Krein signature collide near the wave's frequency they
split off the circle by an amount ∝ their spacing, ∝ 1/N — and which pair collides changes with
N, so at fixed V the excess e(N) = max|μ| − 1 is a *sawtooth* in N under a ~1/N envelope, absent
on some rings and present on others.  A genuine instability of the wave is a mode localized on
its core: once the ring is much longer than the core (every ring the wave solver accepts — its
tails are ≤ 1e-6 at the cut) the mode and its growth are the same on every ring, up to
exponentially small corrections.  A positive control: a constant state with f′ < 0 (growth
rate 2√(−f′) per unit time at every even N).

Evidence (:func:`chain_lengths`, :func:`base_at`, :func:`classify`): e(N_k) on a *window* of
``WINDOW`` = 6 chain lengths evenly spaced in [N/2, N] (the requested N last), each on the
structured route (quarter-size for the paper's reversible waves), and three physical tests:

1. presence — is the excess beyond its error bar on every ring of the window?  A mode of the wave
   cannot vanish on a ring in [N/2, N] and reappear at N; a phonon collision does (measured:
   superkink V = 5.6 at N = 500: 250: 4.0e-5, 292: 0 (on the circle), 334: 7.2e-5, …, 500: 6.2e-5).
   Likewise a dip: the excess falling below ``DIP`` = ½ of larger values on both sides of it
   (V = 5.55: 376: 1.4e-4, 416: 3.1e-5, 500: 1.2e-4) — the largest |μ| of a converged mode plus
   any resonance above it cannot fall below the mode's own growth, so the dip also bounds any
   instability of the wave itself (printed).
2. the upper envelope — the points above every later one, on their concave upper hull in
   (log N, log e) (:func:`upper_envelope`), fitted by e ∝ N^−p: a ring resonance's envelope
   decays (p ≈ 1; measured p = 0.98 for the superkink V = 4.8, e·N = 1.90 … 1.93 over
   250 … 500), a converged mode's does not (p ≈ 0).
3. convergence — the spread (max e − min e)/e(N) over the window: ≤ ``CONVERGED_SPREAD`` (10 %)
   for a mode that has converged to its growth rate (the f′ < 0 control: 0 to round-off).

Decision (:func:`classify`; the record :class:`fpucore.floquet.decision.Decision` and its
words live in :mod:`fpucore.floquet.decision`): "stable" if e(N) is within its error bar;
"finite_size" if the excess is absent on a ring of the window or dips (1), or its envelope decays
(2): p ≥ ``DECAY_P`` = 0.5, the excess at N at most (N_first/N)^0.5 (71 % at N_first = N/2)
of the largest on the window — a drop no converged mode shows — and the envelope starting in the
first half of the window (log N): a fall over the last rings after a rise is no trend (measured:
superkink V = 5.6 at N = 500 rises from 4.0e-5 at 250 to 9.7e-5 at 450, then 6.2e-5 at 500;
"undetermined" there, "decays" at N = 1000); "unstable" only if the excess is present on every
ring and has converged (3) and no ring of the window is missing (a wave that could not be
rebuilt on one: "undetermined", reason "missing_rings"); otherwise — and whenever fewer than
``MIN_POINTS`` lengths could be computed — "undetermined", with the computation that would
decide it ("compute at N ≥ 2N": a resonance's envelope halves, a mode's growth stays).
Every "unstable" therefore rests on an excess that did not change by more than 10 % while the
ring doubled in length.

Limitation: a genuine instability weaker than a coexisting ring resonance hides under it until
N is large enough for the resonance to fall below it (the envelope then flattens at its growth).

Why not the earlier three-point fit e = e∞ + C/N over 0.4N, 0.6N, N: on a sawtooth three points
are not a trend (its "unstable" fallback labelled 16 of the 44 rows of the paper's superkinks
at N = 200 and 500 "unstable", every one a finite-size artefact by the paper), and the 1/N law
has O(1/N²) curvature (e·N rises 1.90 → 1.93 for V = 4.8), so e∞ came out "significantly
positive" for a pure resonance.
Why not the eigenvectors' localization: a phonon multiplier colliding with the wave's internal
mode has an eigenvector partly on the core and partly on the ring, so a core fraction needs its
own threshold and an inverse iteration on the 2N × 2N monodromy per multiplier — the window
answers the same question (does it depend on the ring?) directly.
The energy criterion (:mod:`fpucore.floquet.energy`) is the consistency check of a sweep: a
change of stability through the translation mode needs an extremum of E_ren(V); a change of
class elsewhere is an oscillatory instability or a finite-size effect the window did not resolve,
to be checked at 2N (:func:`fpucore.floquet.energy.stability_changes`, summarised in one line by
:func:`fpucore.floquet.energy.changes_summary`).

Cost (benchmarks/bench_floquet.py, part D): the five shorter spectra are Σ(N_k/N)³ ≈ 1.9
eigenvalue calls of the requested size on the structured route plus their monodromies and wave
re-solves; the rings are computed shortest first and the window stops as soon as an absent
excess or a dip has decided it (:func:`settled`).  Measured: seven lengths cost 1.4–1.6 × one
dense spectrum in total (structured spectrum + decision, load 8–14) and decide all 44 rows of
the README superkink sweep (N = 200 and 500); six cost 1.2 × and leave 2 "undetermined"
(V = 5.3 at N = 200, V = 5.55 at N = 500: the excess falls 27 % from its largest value, short
of the 29 % drop); six it is, within the 1.5 × budget, the open rows saying what decides them.

Smaller-N waves.  A wave result is re-solved on N_k sites with the converged wave truncated to
its central N_k sites as the Newton predictor (:func:`fpucore.wave.resize`): the truncation is
the N_k-site wave up to its tails at the cut (≤ 1e-6 of the amplitude, the solver's own
N-admissibility test), and one or two Newton steps make it the exact fixed point of the N_k ring,
so every point is the spectrum of a converged wave of its own chain length.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from fpucore.errors import ParameterError, require_int
from fpucore.floquet.checks import HomogeneousState
from fpucore.wave import resize, solve_solitary, solve_superkink
from fpucore.wave.tails import N_MIN as WAVE_N_MIN

WINDOW = 6  # chain lengths in [N/2, N], the requested N included
MIN_POINTS = 4  # fewer computed lengths: "undetermined"
CONVERGED_SPREAD = 0.1  # (max e − min e)/e(N) of a converged mode over the window
DECAY_P = 0.5  # envelope exponent above which the excess decays with N
DIP = 0.5  # an excess below DIP × the larger values on both sides of it is a dip
N_MIN = 8
CLASSES = ("stable", "finite_size", "unstable", "undetermined")
#: the longest sentence a Decision writes (the atlas stores it in a field of this width)
SENTENCE_CHARS = 640


def chain_lengths(N: int, n_min: int = N_MIN) -> list[int]:
    """The shorter even chain lengths of the window: WINDOW − 1 lengths evenly spaced in
    [max(N/2, n_min), N), ascending; [] when the window would be narrower than [3N/4, N] or hold
    fewer than MIN_POINTS − 1 distinct lengths (N too short for the test).

    Parameters
    ----------
    N : int
        Sites of the full chain, in [2, 10⁷].
    n_min : int
        Shortest chain length allowed, in [2, 10⁷] (default N_MIN).

    Returns
    -------
    list of int
        The shorter even chain lengths (sites), ascending; possibly empty.

    Raises
    ------
    ParameterError
        When ``N`` or ``n_min`` is out of range.
    """
    N, n_min = require_int("N", N, 2, 10**7), require_int("n_min", n_min, 2, 10**7)
    lo = max(0.5 * N, float(n_min + (n_min % 2)))
    if lo > 0.75 * N:
        return []
    out: list[int] = []
    for j in range(WINDOW - 1):
        n = 2 * int(round(0.5 * (lo + (N - lo) * j / (WINDOW - 1))))
        if max(n_min, N_MIN) <= n < N and n not in out:
            out.append(n)
    return out if len(out) >= MIN_POINTS - 1 else []


def min_window_N(n_min: int) -> int:
    """The smallest N whose window [N/2, N] starts at or above n_min (an even integer)."""
    return 2 * max(n_min, N_MIN)


def min_chain(r) -> int:
    """The smallest chain the base state can be rebuilt on (wave solver's N_MIN for waves)."""
    return N_MIN if isinstance(r, HomogeneousState) else WAVE_N_MIN


def base_at(r, N_k: int):
    """The base state of r on a ring of N_k sites, or (None, reason).

    HomogeneousState: the same constant state on N_k sites (exact).  Wave results: re-solved at
    N_k with the truncated converged wave as predictor (see module doc).  Anything else: None.
    """
    if isinstance(r, HomogeneousState):
        return dataclasses.replace(r, N=int(N_k)), ""
    kind = getattr(r, "kind", None)
    if kind is None or not hasattr(r, "w_plus"):
        return None, f"no way to rebuild a {type(r).__name__} on {N_k} sites"
    x = np.empty(2 * r.N)
    x[0::2], x[1::2] = r.w, r.wdot

    def predictor(n: int) -> np.ndarray:
        return resize(x, r.N, n, r.w_left, r.w_right)

    try:
        if kind == "superkink":
            rk = solve_superkink(r.law, r.V, r.branch or "lower", int(N_k), predictor=predictor)
        else:
            rk = solve_solitary(r.law, r.w_plus, r.V, int(N_k), predictor=predictor)
    except ParameterError as exc:  # N_k too short for the wave's tails
        return None, f"N={N_k}: {exc}"
    if not rk.converged:
        return None, f"N={N_k}: wave not converged ({rk.message})"
    return rk, ""


def fit_power_law(N: np.ndarray, e: np.ndarray, err: np.ndarray) -> tuple[float, float]:
    """(p, σ_p): least-squares fit log e = log C − p log N over ≥ 2 points.

    e is floored at its error bar (a point within the error is "at most err").  σ_p is the
    standard error of the slope from the residual (n − 2 degrees of freedom) combined with the
    relative point errors; NaN for two points (no degree of freedom: an exact line through two
    points says nothing about its own uncertainty, and "± 0" would claim it is exact).
    """
    x = np.log(np.asarray(N, float))
    y = np.log(np.maximum(np.asarray(e, float), np.maximum(err, 1e-300)))
    xm = x - x.mean()
    sxx = float(xm @ xm)
    slope = float(xm @ (y - y.mean())) / sxx
    res = y - y.mean() - slope * xm
    dof = x.size - 2
    if dof <= 0:  # a line through two points has no scatter to measure: no error bar
        return -slope, math.nan
    s2 = float(res @ res) / dof
    rel = float(np.max(np.asarray(err, float) / np.maximum(np.asarray(e, float), 1e-300)))
    return -slope, math.sqrt(s2 / sxx + 2.0 * rel * rel / sxx)


def extrapolate(N: np.ndarray, e: np.ndarray, err: np.ndarray) -> tuple[float, float]:
    """(e∞, σ∞): least-squares fit e = e∞ + C/N; σ∞ from the residual and the point error bars."""
    x = 1.0 / np.asarray(N, float)
    y = np.asarray(e, float)
    xm = x - x.mean()
    sxx = float(xm @ xm)
    slope = float(xm @ (y - y.mean())) / sxx
    e_inf = float(y.mean() - slope * x.mean())
    res = y - (e_inf + slope * x)
    dof = x.size - 2
    s2 = float(res @ res) / dof if dof > 0 else 0.0
    lever = math.sqrt(1.0 / x.size + x.mean() ** 2 / sxx)
    return e_inf, math.sqrt(s2) * lever + float(np.max(err)) * lever


def settled(N: np.ndarray, e: np.ndarray, err: np.ndarray) -> bool:
    """True when the points computed so far (N ascending, the requested N included) already
    decide "finite_size" whatever the remaining rings show: an absent excess stays absent, and a
    dip stays a dip (more points only raise the maxima on its sides).  The window stops there."""
    N, e, err = (np.asarray(a, float) for a in (N, e, err))
    if not e[-1] > err[-1]:
        return False
    if np.any(e <= err):
        return True
    return any(e[k] < DIP * min(e[:k].max(), e[k + 1 :].max()) for k in range(1, N.size - 1))


def upper_envelope(N: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Indices of the upper envelope of a decaying sawtooth, N ascending (e > 0): the points that
    exceed every point at a larger N (a point below a later one lies in a trough and says nothing
    about the envelope), reduced to the vertices of their concave upper hull in (log N, log e).
    A sequence that grows with N has only its last point here (no decay to fit)."""
    x, y = np.log(np.asarray(N, float)), np.log(np.asarray(e, float))
    keep = [i for i in range(x.size) if i == x.size - 1 or y[i] > y[i + 1 :].max()]
    hull: list[int] = []
    for i in keep:
        while len(hull) >= 2:
            a, b = hull[-2], hull[-1]
            # b lies on or below the chord a → i: not a vertex of the upper hull
            if (y[b] - y[a]) * (x[i] - x[a]) <= (y[i] - y[a]) * (x[b] - x[a]):
                hull.pop()
            else:
                break
        hull.append(i)
    return np.asarray(hull, dtype=np.int64)


def classify(N: np.ndarray, e: np.ndarray, err: np.ndarray) -> dict:
    """The decision from the window's points (N_k, e_k ± err_k), N ascending, the requested N
    last (module doc).  Returns classification, reason ("within_error" | "absent" | "dips" |
    "decays" | "persists" | "unresolved" | "few_lengths"), absent_N (lengths where the excess is
    within its error bar), dip_N (lengths where it falls below DIP × larger values on both
    sides), p ± p_error and C (envelope e ≈ C N^−p, NaN with < 2 hull points; p_error NaN with
    2), envelope_N, envelope_early (the envelope starts by √(N_first·N)), peak_N (where e is
    largest), drop = 1 − e(N)/max e and drop_needed = 1 − (N_first/N)^DECAY_P, spread,
    e_inf ± e_inf_error (e∞ + C/N over the window, reported only), checked (≥ MIN_POINTS
    lengths), shrinks (the decay test passed) and intermittent (an absent excess or a dip)."""
    N = np.asarray(N, float)
    e = np.asarray(e, float)
    err = np.asarray(err, float)
    nan = math.nan
    out = {
        "p": nan,
        "p_error": nan,
        "C": nan,
        "e_inf": nan,
        "e_inf_error": nan,
        "spread": nan,
        "absent_N": [],
        "dip_N": [],
        "envelope_N": [],
        "shrinks": False,
        "intermittent": False,
        "checked": N.size >= MIN_POINTS,
        "peak_N": int(N[-1]),
        "drop": 0.0,
        "drop_needed": nan,
        "envelope_early": False,
    }
    if not e[-1] > err[-1]:
        out["classification"], out["reason"] = "stable", "within_error"
        return out
    present = e > err
    out["absent_N"] = [int(n) for n in N[~present]]
    out["spread"] = float((e.max() - e.min()) / e[-1])
    if N.size >= 2:
        out["e_inf"], out["e_inf_error"] = extrapolate(N, e, err)
    if present.all() and N.size >= 2:
        hull = upper_envelope(N, e)
        out["envelope_N"] = [int(n) for n in N[hull]]
        if hull.size >= 2:
            out["p"], out["p_error"] = fit_power_law(N[hull], e[hull], err[hull])
            ly = np.log(e[hull])
            out["C"] = float(np.exp(ly.mean() + out["p"] * np.log(N[hull]).mean()))
    # a dip: between larger excesses on both sides the excess falls below half of them; the max
    # of a converged mode of the wave (plus any resonance above it) cannot fall below the mode
    dips = [k for k in range(1, N.size - 1) if e[k] < DIP * min(e[:k].max(), e[k + 1 :].max())]
    out["dip_N"] = [int(N[k]) for k in dips]
    out["intermittent"] = bool(out["absent_N"] or dips)
    out["checked"] = bool(out["checked"] or out["intermittent"])  # conclusive at any count
    # decays: the envelope falls like N^-p, p ≥ DECAY_P, the excess at N is that far below the
    # largest one on the window (a measured drop, not only a fitted slope), and the envelope
    # starts in the first half of the window (log N): a fall over the last rings alone, after a
    # rise (superkink V = 5.6, N = 500: 250: 4.0e-5 … 450: 9.7e-5, 500: 6.2e-5), is no decay
    k_max = int(np.argmax(e))
    out["peak_N"] = int(N[k_max])
    out["drop"] = float(1.0 - e[-1] / e[k_max])
    out["drop_needed"] = float(1.0 - (N[0] / N[-1]) ** DECAY_P)
    env0 = out["envelope_N"][0] if out["envelope_N"] else N[-1]  # type: ignore[index]
    out["envelope_early"] = bool(env0 <= math.sqrt(N[0] * N[-1]) * (1.0 + 1e-12))
    drop = out["drop"] >= out["drop_needed"] * (1.0 - 1e-12)  # type: ignore[operator]
    out["shrinks"] = bool(out["p"] >= DECAY_P and drop and out["envelope_early"])  # type: ignore[operator]
    if not out["checked"]:
        cls, why = "undetermined", "few_lengths"
    elif out["absent_N"]:
        cls, why = "finite_size", "absent"
    elif out["intermittent"]:
        cls, why = "finite_size", "dips"
    elif out["shrinks"]:
        cls, why = "finite_size", "decays"
    elif out["spread"] <= CONVERGED_SPREAD:  # type: ignore[operator]
        cls, why = "unstable", "persists"
    else:
        cls, why = "undetermined", "unresolved"
    out["classification"], out["reason"] = cls, why
    return out
