"""QC diagrams: the existence diagram V vs w₊ (Fig. SWvelocities_cubic) and the solitary-wave
family curves amplitude/energy vs V for one w₊ (Fig. SWamp_energy_QCcubic).

The cubic uses its closed forms (array-valued); any other law the numerical §3 theory of
:mod:`.general`, point by point (≈ 1.5 ms per w₊ for the speeds, ≈ 15 ms per solitary wave)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.law import HardeningSofteningLaw, require_law
from fpucore.qc import closed_forms as cf
from fpucore.qc import dispatch as qc
from fpucore.qc import general as gen

N_GENERAL = 60  # points per interval of a solitary-wave family for a non-cubic law


@dataclass(frozen=True)
class ExistenceDiagram:
    """Arrays over the admissible w₊ ∈ (α, β) (n,): c₊, V_SK, c₋.  For w₊ < w* the band
    (c₊, V_SK) holds tensile waves (TSW) and (V_SK, c₋) compressive ones (CSW); for w₊ > w* the
    other way round.  Mirror V → −V for the full (symmetric) figure."""

    w_plus: np.ndarray
    c_plus: np.ndarray
    V_SK: np.ndarray
    c_minus: np.ndarray
    w_star: float
    alpha: float
    beta: float
    elapsed_s: float


def existence_diagram(law: HardeningSofteningLaw, n: int = 400) -> ExistenceDiagram:
    """c₊, V_SK, c₋ over n points of the open w₊-interval.  Cubic: eqs. cplus, cubic_cond2,
    cminus_cubic on (α, β).  Any other law: the interval is the union of the superkink ranges of
    both branches (outside it V_SK and c₋ do not exist: the partner w₋ leaves (α, β)), each point
    by :func:`fpucore.qc.general.speeds` (a piecewise-linear law's by its closed forms,
    :func:`fpucore.qc.sound_speeds`); the point at w* itself is skipped."""
    t0 = time.perf_counter()
    law = require_law(law)
    n = require_int("n", n, 3, 100_000)
    a, b, ws = law.alpha, law.beta, law.w_star
    if qc.is_closed_form(law):
        wp = a + (b - a) * (np.arange(n) + 0.5) / n  # open interval
        c2, A = float(law.df(ws)), law.abs_a
        e = (wp - ws) ** 2
        cp, vsk, cm = cf.sound_speed_plus(law, wp), np.sqrt(c2 - A * e), np.sqrt(c2 - 0.75 * A * e)
    else:
        lo = qc.superkink_w_plus_range(law, "lower")[0]
        hi = qc.superkink_w_plus_range(law, "upper")[1]
        if not math.isfinite(lo):  # α = −∞ and the partner never reaches β: show a finite window
            lo = ws - 4.0 * (hi - ws)
        wp = lo + (hi - lo) * (np.arange(n) + 0.5) / n
        wp = wp[np.abs(wp - ws) > 1e-9 * max(1.0, abs(ws))]
        if getattr(law, "breakpoints", ()):
            # a piecewise-linear law: its closed forms (the general route integrates f″, zero
            # between the corners, and drew V_SK as a staircase, up to 4 % off)
            # the hardest regime has no waves (the PL analogue of w* itself): its points are
            # skipped, as sound_speeds refuses them
            rows = []
            for w in wp:
                try:
                    rows.append((float(w), *qc.sound_speeds(law, float(w))))
                except ParameterError:
                    continue
            wp, cp, vsk, cm = np.array(rows).T
        else:
            sp = [gen.speeds(law, float(w)) for w in wp]
            cp, vsk, cm = (
                np.array([getattr(s, k) for s in sp]) for k in ("c_plus", "V_SK", "c_minus")
            )
    return ExistenceDiagram(wp, cp, vsk, cm, ws, a, b, time.perf_counter() - t0)


def classify(law: HardeningSofteningLaw, w_plus: float, V: float) -> str:
    """What lives at (w₊, V): "tensile", "compressive", "superkink" (|V| = V_SK to 1e-9) or
    raises ParameterError naming the valid intervals.  Used e.g. for clicks on the diagram."""
    law = require_law(law)
    w_plus, V = require_finite("w_plus", w_plus), abs(require_finite("V", V))
    cp, vsk, cm = qc.sound_speeds(law, w_plus)
    if abs(V - vsk) <= 1e-9 * vsk:
        return "superkink"
    return qc.solitary(law, w_plus, V).kind


@dataclass(frozen=True)
class SolitaryFamily:
    """QC solitary waves along V for one w₊: arrays for the interval below V_SK and above it."""

    w_plus: float
    V_below: np.ndarray
    amp_below: np.ndarray
    energy_below: np.ndarray
    kind_below: str
    V_above: np.ndarray
    amp_above: np.ndarray
    energy_above: np.ndarray
    kind_above: str
    c_plus: float
    V_SK: float
    c_minus: float
    sk_amplitude: float
    max_energy_error: float
    elapsed_s: float


def solitary_family(law: HardeningSofteningLaw, w_plus: float, n: int = 160) -> SolitaryFamily:
    """Amplitude (eq. SWQC_amp) and E_ren^QC (eq. Eren_QC) along both velocity intervals, with
    points clustered toward both ends (the energy diverges at V_SK).  All velocities are
    evaluated at once by :func:`fpucore.qc.solitary_closed_form` (the formulas of
    :func:`fpucore.qc.solitary`) for the cubic, one by one by :func:`fpucore.qc.general.solitary`
    otherwise; ``max_energy_error`` is the largest error bound."""
    t0 = time.perf_counter()
    law = require_law(law)
    n = require_int("n", n, 3, 100_000)
    (cp, vsk), (_, cm) = qc.solitary_intervals(law, w_plus)
    if not qc.is_closed_form(law):
        n = min(n, N_GENERAL)  # ≈ 10 ms per wave by quadrature
    t = 0.5 * (1.0 - np.cos(np.pi * (np.arange(n) + 0.5) / n))

    def closed_or_general(w_B, Vs):
        if qc.is_closed_form(law):
            return cf.solitary_closed_form(law, w_B, Vs)
        waves = []
        for v in Vs:
            try:
                waves.append(gen.solitary(law, w_plus, float(v), check=False))
            except ParameterError:  # rounds onto an end of the interval: dropped below
                waves.append(None)
        ok = np.array([sw is not None for sw in waves])
        get = lambda k: np.array([getattr(sw, k) if sw else np.nan for sw in waves])  # noqa: E731
        return get("w_M") - w_B, None, None, get("energy"), get("energy_error"), ok

    def run(lo, hi, background):
        Vs = lo + (hi - lo) * t
        w_B = background(Vs)
        dM, _, _, energy, err, ok = closed_or_general(w_B, Vs)
        ok &= (lo < Vs) & (Vs < hi) & np.isfinite(energy)  # drop points rounding onto an end
        if not np.any(ok):  # the interval (width ∝ (w₊ − w*)²) is below the rounding of V
            raise ParameterError(
                "w_plus",
                w_plus,
                f"|w_plus - w*| resolvable around w* = {law.w_star:.10g}",
                f"the velocity interval ({lo!r}, {hi!r}) holds no resolvable velocity",
            )
        kind = "tensile" if dM[ok][0] > 0 else "compressive"
        return Vs[ok], np.abs(dM[ok]), energy[ok], kind, float(np.max(err[ok]))

    Vb, ab, eb, kb, errb = run(cp, vsk, lambda Vs: np.full_like(Vs, w_plus))
    Va, aa, ea, ka, erra = run(vsk, cm, lambda Vs: qc.w_S(law, w_plus, Vs))
    sk = qc.superkink_from_w_plus(law, w_plus)
    return SolitaryFamily(
        w_plus,
        Vb,
        ab,
        eb,
        kb,
        Va,
        aa,
        ea,
        ka,
        cp,
        vsk,
        cm,
        sk.amplitude,
        max(errb, erra),
        time.perf_counter() - t0,
    )
