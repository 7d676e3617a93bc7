"""Discrete-wave figures of the trilinear family: flat tops near the kink limit against QC,
the compact waves of the zero-modulus case against their explicit form, and a Floquet sweep of
superkinks.  Same contract as fpucore.paper.figures_trilinear (panels, comparisons, params,
notes).
"""

from __future__ import annotations

import math

import numpy as np

from fpucore import floquet, qc, wave
from fpucore.paper.compare import compare
from fpucore.paper.figure import Panel, series
from fpucore.paper.figures_trilinear import (
    DEGENERATE,
    E1,
    E2,
    E3,
    LAW,
    W1,
    W2,
    W_B,
    W_PLUS,
    speed_rows,
)
from fpucore.wave.compact import compact_wave, v_max

FLAT_DV = (1e-2, 1e-4, 1e-6)  # distances from V_SK of the flat tops drawn


def fig_tri_flattops(reduced: bool):
    """Solitary waves near the kink limit at w₊ = 0.3: discrete (points, period-and-shift Newton
    with located crossings, N = 64) and QC (curves, fpucore.qc.piecewise_orbit) at V_SK ∓ ΔV:
    flat tops, kink–antikink bundles whose plateau tends to w₋ as ΔV → 0.  The amplitude of both
    stays below the superkink limit |w₋ − w₊| (an upper bound, checked with the error bars)."""
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    corner = abs(sk.w_minus - sk.w_plus)
    dvs = FLAT_DV[1:2] if reduced else FLAT_DV  # 1e-6: ~7 s per wave
    panels, comps, notes = [], speed_rows("tri_flattops"), []
    for tag, sign, side in (("a", -1, "below"), ("b", 1, "above")):
        ser = []
        for dv in dvs:
            V = sk.V + sign * dv
            r = wave.solve_solitary(LAW, W_PLUS, V, N=64)
            q = qc.solitary(LAW, W_PLUS, V)
            half = int(np.max(np.abs(r.n)))
            x = np.linspace(-half, half, 10 * half + 1)
            ser += [
                series(f"discrete V_SK {'−+'[sign > 0]} {dv:g}", r.n, r.w, "points"),
                series(f"QC V_SK {'−+'[sign > 0]} {dv:g}", x, q.profile(x)),
            ]
            notes.append(
                f"{side} {dv:g}: {'converged' if r.converged else 'NOT converged'}, "
                f"amplitude {float(r.amplitude):.6g} (QC {float(q.amplitude):.6g})"
            )
            amp, err = (
                (float(r.amplitude), float(r.amplitude_error)) if r.converged else (np.nan, np.nan)
            )
            comps.append(
                compare(
                    "tri_flattops",
                    f"discrete amplitude at V_SK {'−+'[sign > 0]} "
                    f"{dv:g}, under the superkink limit",
                    "< |w₋ − w₊|",
                    corner,
                    amp,
                    err,
                    kind="upper_bound",
                    elapsed_s=r.elapsed_s,
                    source="wave.solve_solitary(law, 0.3, V, N=64).amplitude",
                )
            )
        ser.append(series("w₋ (superkink limit)", [0.0], [sk.w_minus], "hline"))
        panels.append(Panel(f"({tag}) {side} V_SK = {sk.V:.6g}", "n, x", "w", tuple(ser)))
    return tuple(panels), comps, {"w_plus": W_PLUS, "dV": dvs, "N": 64}, "; ".join(notes)


def _compact_grid(reduced: bool) -> np.ndarray:
    vm = v_max(DEGENERATE, W_B)
    # the slow end converges since the step count keeps the step below 1/ω_max (Spec.choose_m_floor)
    return (np.array([0.15, 0.3, 0.5, 0.7]) if reduced
            else np.round(np.linspace(0.1, 0.85, 7) * vm, 4))  # fmt: skip


SLOW_PROBE = 0.09  # m = 128 steps per period (the largest in M_STEPS); its status in the notes


def fig_tri_compact(reduced: bool):
    """The degenerate law (E₁ = 0): compact discrete solitary waves on the background w_B = 0.2
    for slow velocities 0 < V < V_max — (a) amplitude against V, the explicit form
    |b − w_B| + |C|, C = δ/(ω(1 − a)), ω = √(2E₂)/V (fpucore.wave.compact, derived from eq.
    TW_discrete) against the period-and-shift solver; (b) profiles, solver (points) and explicit
    (curves), localizing at the lattice scale as V → 0."""
    Vs = _compact_grid(reduced)
    vm = v_max(DEGENERATE, W_B)
    Vc = np.linspace(0.02, 0.999, 200) * vm
    a_ser = [
        series(
            "explicit |b − w_B| + |C|", Vc, [compact_wave(DEGENERATE, v, W_B).amplitude for v in Vc]
        )
    ]
    b_ser, comps, amps = [], [], []
    x = np.linspace(-2.5, 2.5, 501)
    for V in Vs:
        r = wave.solve_solitary(DEGENERATE, W_B, float(V))
        cw = compact_wave(DEGENERATE, float(V), W_B)
        ok = bool(r.converged)
        amps.append(float(r.amplitude) if ok else np.nan)
        keep = np.abs(r.n) <= 3
        b_ser += [
            series(f"solver V = {V:g}", r.n[keep], r.w[keep], "points"),
            series(f"explicit V = {V:g}", x, cw.profile(x)),
        ]
        src = f"wave.solve_solitary(E1=0 law, {W_B:g}, {V:g})"
        amp, aerr = (float(r.amplitude), float(r.amplitude_error)) if ok else (np.nan, np.nan)
        mass = float(np.sum(r.w - W_B)) if ok else np.nan
        comps += [
            compare(
                "tri_compact",
                f"amplitude at V = {V:g}",
                "|b − w_B| + |δ|/(ω(1 − a))",
                cw.amplitude,
                amp,
                aerr,
                rounding=0,
                elapsed_s=r.elapsed_s,
                source=src + ".amplitude",
            ),
            # Σ(w_n − w_B) is the same at every phase of a traveling wave, hence = ∫(w − w_B)dξ
            compare(
                "tri_compact",
                f"mass Σ(w_n − w_B) at V = {V:g}",
                "δ/(1 − a)",
                cw.mass,
                mass,
                r.N * float(r.profile_error) if ok else np.nan,
                rounding=0,
                elapsed_s=r.elapsed_s,
                source=src + ": Σ(w_n − w_B)",
            ),
        ]
    a_ser += [series("solver", Vs, amps, "points"), series("V_max", [vm], [0.0], "vline")]
    panels = (
        Panel("(a) amplitude of the compact waves, E₁ = 0", "V", "max |w − w_B|", tuple(a_ser)),
        Panel("(b) profiles, solver (points) and explicit (curves)", "n, ξ", "w", tuple(b_ser)),
    )
    params = {
        "w1": W1,
        "w2": W2,
        "E1": 0.0,
        "E2": E2,
        "E3": E3,
        "w_B": W_B,
        "V": tuple(Vs.tolist()),
        "V_max": vm,
    }
    notes = f"V_max = √(2E₂)/max(π, π/2 + |δ|/h) = {vm:.10g}"
    if not reduced:
        slow = wave.solve_solitary(DEGENERATE, W_B, SLOW_PROBE)
        notes += f"; solver at V = {SLOW_PROBE:g}: {slow.message}"
    return panels, comps, params, notes


FLOQUET_V_REDUCED = (1.2, 1.6, 1.9)


def fig_tri_floquet(reduced: bool):
    """max|μ| of the Floquet multipliers of trilinear superkinks against V ∈ (√E₁, √E₂) at a
    modest N (64 reduced, 128 full), with located crossings in the monodromy.  Rows: the
    monodromy is symplectic, so Σ log|μ| = 0 (Liouville) within the multipliers' error bars; and
    max|μ| at V = 1.6 by the structured route against the dense eigensolver (a second method)."""
    N = 64 if reduced else 128
    Vs = FLOQUET_V_REDUCED if reduced else tuple(np.round(np.linspace(1.1, 1.95, 10), 4))
    mods, errs, comps, notes, rows, elapsed = [], [], [], [], [], 0.0
    for V in Vs:
        r = wave.solve_superkink(LAW, float(V), N=N)
        # finite_size=False: the finite-size test needs N >= 128 rings; N is modest on purpose
        fr = floquet.spectrum(r, finite_size=False)
        elapsed += r.elapsed_s + fr.elapsed_s
        ok = bool(r.converged and fr.converged)
        mods.append(float(fr.max_modulus) if ok else np.nan)
        errs.append(float(fr.error) if ok else np.nan)
        notes.append(
            f"V = {V:g}: max|μ| − 1 = {fr.max_modulus - 1:.3g}"
            if ok
            else f"V = {V:g}: not converged ({fr.message})"
        )
        mu = np.abs(np.asarray(fr.multipliers))
        rows.append(
            (float(np.sum(np.log(mu))), float(np.sum(fr.error / mu)), float(V))
            if ok
            else (np.nan, np.nan, float(V))
        )
    liou, liou_err, at = max(
        rows, key=lambda t: np.inf if not np.isfinite(t[0]) else abs(t[0]) - t[1]
    )
    comps.append(
        compare(
            "tri_floquet",
            f"Σ log|μ| (Liouville), worst at V = {at:g}",
            "0",
            0.0,
            liou,
            liou_err,
            rounding=0,
            elapsed_s=elapsed,
            source=f"floquet.spectrum(wave.solve_superkink(law, V, N={N}))",
        )
    )
    r = wave.solve_superkink(LAW, 1.6, N=N)
    a = floquet.spectrum(r, finite_size=False)
    b = floquet.spectrum(r, method="dense", finite_size=False)
    comps.append(
        compare(
            "tri_floquet",
            f"max|μ| at V = 1.6, structured vs dense (N = {N})",
            "dense eigensolver",
            float(b.max_modulus),
            float(a.max_modulus),
            float(a.error + b.error),
            rounding=0,
            elapsed_s=a.elapsed_s + b.elapsed_s,
            source=f"floquet.spectrum(wave.solve_superkink(law, 1.6, N={N}))",
        )
    )
    panels = (
        Panel(
            f"max |μ| of trilinear superkinks, N = {N}",
            "V",
            "max |μ|",
            (
                series("max |μ|", Vs, mods, "points"),
                series("√E₁, √E₂ (velocity bounds)", [math.sqrt(E1)], [1.0], "vline"),
                series("", [math.sqrt(E2)], [1.0], "vline"),
            ),
        ),
    )
    params = {"V": tuple(float(v) for v in Vs), "N": N, "law": LAW.expression}
    return panels, comps, params, "; ".join(notes) + f"; max error bar {np.nanmax(errs):.2g}"
