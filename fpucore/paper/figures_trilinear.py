"""Figures of the soft–hard–soft trilinear family (companion study, arXiv 2406.06437): the law,
the existence diagram, flat tops near the kink limit, the compact waves of the zero-modulus case
and a Floquet sweep.  Each ``fig_tri_<name>(reduced)`` returns (panels, comparisons, params,
notes) as the paper's figures do (fpucore.paper.registry); the references are the trilinear
closed forms written out here from their formulas (fpucore.qc.piecewise's docstring,
fpucore.wave.compact's derivation), independently of the code that computes ``ours``.
"""

from __future__ import annotations

import math

import numpy as np

from fpucore import floquet, qc, wave
from fpucore.law import TrilinearLaw
from fpucore.paper.common import roundoff
from fpucore.paper.compare import compare
from fpucore.paper.figure import Clock, Panel, series
from fpucore.wave.compact import compact_wave, v_max

W1, W2, E1, E2, E3 = 0.5, 1.5, 1.0, 4.0, 0.2
LAW = TrilinearLaw(W1, W2, E1, E2, E3)  # the general (E₁ > 0) example
DEGENERATE = TrilinearLaw(W1, W2, 0.0, E2, E3)  # E₁ = 0: compact slow waves
W_PLUS = 0.3  # the state ahead of the superkink / solitary waves (lower branch, w₊ < w₁)
W_B = 0.2  # the background of the compact waves (inside the zero-modulus regime)


def _f(w: float, e1: float = E1, e3: float = E3) -> float:
    """The trilinear force written out piece by piece."""
    if w <= W1:
        return e1 * w
    if w <= W2:
        return e1 * W1 + E2 * (w - W1)
    return e1 * W1 + E2 * (W2 - W1) + e3 * (w - W2)


def closed_forms(w_plus: float = W_PLUS, e1: float = E1, e3: float = E3) -> dict[str, float]:
    """w₋, V_SK, c₊, c₋ of the trilinear law for w₊ < w₁ (lower branch): the equal-area partner
    w₋ = [A w₁(w₁ − w₊) − B w₂(w₂ − w₊)] / [A(w₁ − w₊) − B(w₂ − w₊)] (A = E₂ − E₁, B = E₂ − E₃),
    V_SK² the chord slope (eq. Rline), c₊² = E₁ (eq. cplus), c₋² the chord slope to the corner
    w₂ (eq. cminus)."""
    A, B = E2 - e1, E2 - e3
    wm = (A * W1 * (W1 - w_plus) - B * W2 * (W2 - w_plus)) / (
        A * (W1 - w_plus) - B * (W2 - w_plus)
    )
    fp = _f(w_plus, e1, e3)
    return {
        "w_minus": wm,
        "V_SK": math.sqrt((_f(wm, e1, e3) - fp) / (wm - w_plus)),
        "c_plus": math.sqrt(e1),
        "c_minus": math.sqrt((_f(W2, e1, e3) - fp) / (W2 - w_plus)),
    }


NAMES = {"V_SK": "V_SK", "w_minus": "w₋", "c_plus": "c₊", "c_minus": "c₋"}
FORMULAS = {
    "w_minus": "[Aw₁(w₁−w₊) − Bw₂(w₂−w₊)]/[A(w₁−w₊) − B(w₂−w₊)]",
    "V_SK": "√((f(w₋) − f(w₊))/(w₋ − w₊))",
    "c_plus": "√E₁",
    "c_minus": "√((f(w₂) − f(w₊))/(w₂ − w₊))",
}


def speed_rows(label: str, w_plus: float = W_PLUS) -> list:
    """V_SK, w₋, c₊, c₋ at w₊ from fpucore.qc against :func:`closed_forms` (8 ulp round-off
    plus the superkink's Rayleigh residual)."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, w_plus)
    c_plus, _, c_minus = qc.sound_speeds(LAW, w_plus)
    ours = {"V_SK": sk.V, "w_minus": sk.w_minus, "c_plus": c_plus, "c_minus": c_minus}
    t = clock.s
    ref = closed_forms(w_plus)
    return [
        compare(label, f"{NAMES[k]} at w₊ = {w_plus:g}", FORMULAS[k], ref[k], ours[k],
                roundoff(ref[k], 16) + sk.rayleigh_residual, rounding=0, elapsed_s=t,
                source=f"qc.{'superkink_from_w_plus' if k in ('V_SK', 'w_minus') else 'sound_speeds'}"
                f"(law, {w_plus:g})")
        for k in ("V_SK", "w_minus", "c_plus", "c_minus")
    ]  # fmt: skip


def fig_tri_law(reduced: bool):
    """The trilinear law f(w) with its corners (w₁, f(w₁)), (w₂, f(w₂)) and the equal-area
    (Maxwell) line of the superkink from w₊ = 0.3: the Rayleigh line of slope V_SK² cutting
    equal areas.  ∫_{w₊}^{w₋}(f − R) dw is exact by the trapezoid rule on the nodes w₊, w₁, w₂, w₋
    (f − R is linear between them)."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    w = np.linspace(-0.5, 3.0, 351)
    fp = float(LAW.f(W_PLUS))
    ray = fp + sk.V**2 * (w - W_PLUS)
    corners = [W1, W2]
    panels = (
        Panel(
            f"trilinear f(w), w₁ = {W1:g}, w₂ = {W2:g}, E = ({E1:g}, {E2:g}, {E3:g})",
            "w",
            "f(w)",
            (
                series("f(w)", w, LAW.f(w)),
                series("equal-area line, slope V_SK²", w, ray, "dashed"),
                series("corners w₁, w₂", corners, LAW.f(np.array(corners)), "points"),
                series("w₊, w₋", [sk.w_plus, sk.w_minus],
                       LAW.f(np.array([sk.w_plus, sk.w_minus])), "points"),  # fmt: skip
                series("E₁ = 0 (degenerate)", w, DEGENERATE.f(w), "dashed"),
            ),
        ),
    )
    t = clock.s
    nodes = np.array([W_PLUS, W1, W2, sk.w_minus])
    gap = LAW.f(nodes) - (fp + sk.V**2 * (nodes - W_PLUS))
    area = float(np.sum(0.5 * (gap[1:] + gap[:-1]) * np.diff(nodes)))
    scale = float(np.sum(np.abs(0.5 * (gap[1:] + gap[:-1]) * np.diff(nodes))))
    comps = [
        compare("tri_law", f"f at the corner w{k + 1}", f"{form}", _f(c), float(LAW.f(c)),
                roundoff(_f(c), 8), source=f"law.f({c:g})", elapsed_s=t, rounding=0)
        for k, (c, form) in enumerate(zip(corners, ("E₁w₁", "E₁w₁ + E₂(w₂ − w₁)")))
    ]  # fmt: skip
    comps.append(compare("tri_law", "equal areas: ∫(f − R) dw from w₊ to w₋ (eq. zero_G)", "0",
                         0.0, area, roundoff(scale, 64), rounding=0, elapsed_s=t,
                         source="qc.superkink_from_w_plus(law, 0.3): V, w₋"))  # fmt: skip
    comps += speed_rows("tri_law")
    params = {"w1": W1, "w2": W2, "E1": E1, "E2": E2, "E3": E3, "w_plus": W_PLUS}
    return panels, comps, params, ""


ASYM_E3 = (0.0, 0.5, 2.0)  # E₃ of the checked rows: zero modulus, E₃ < E₁, E₃ > E₁


def fig_tri_existence(reduced: bool):
    """Existence diagram: (a) c₊, V_SK, c₋ against w₊ (fpucore.qc.diagram.existence_diagram,
    both branches); (b) the same at w₊ = 0.3 against the asymmetry E₃ of the softer regime after
    the hard one (E₃ = E₁ = 1: equal soft moduli).  Solitary waves exist for c₊ < V < V_SK and
    V_SK < V < c₋; superkinks bifurcate at w₊ → w₁ with V_SK → √E₂ (fpucore.qc.piecewise)."""
    clock = Clock()
    d = qc.diagram.existence_diagram(LAW, n=80 if reduced else 400)
    a_ser = (
        series("V_SK (superkink limit)", d.w_plus, d.V_SK),
        series("c₊ (sonic)", d.w_plus, d.c_plus, "dashed"),
        series("c₋ (sonic)", d.w_plus, d.c_minus, "dashed"),
        series("hard regime [w₁, w₂]", [W1], [0.0], "vline"),
        series("", [W2], [0.0], "vline"),
    )
    # w₊ = 0.3 has a partner while E₃ < 3.5 (w₊ > w₁ − (E₂ − E₃)(w₂ − w₁)/(E₃ − E₁))
    e3 = np.linspace(0.0, 3.4, 18 if reduced else 69)
    sp = [qc.sound_speeds(TrilinearLaw(W1, W2, E1, E2, float(e)), W_PLUS) for e in e3]
    b_ser = tuple(
        series(name, e3, [s[i] for s in sp], style)
        for i, (name, style) in enumerate((("c₊", "dashed"), ("V_SK", "line"), ("c₋", "dashed")))
    )
    panels = (
        Panel("(a) velocities of solitary waves against w₊", "w₊", "V", a_ser),
        Panel(f"(b) against the asymmetry E₃ at w₊ = {W_PLUS:g}", "E₃", "V", b_ser),
    )
    t = clock.s
    lo, hi = qc.superkink_velocity_bounds(LAW)
    comps = [
        compare("tri_existence", f"superkink velocity {name} bound, lower branch", pr, ref, ours,
                roundoff(ref, 64), source="qc.superkink_velocity_bounds(law)", elapsed_s=t,
                rounding=0)
        for name, pr, ref, ours in (("lower", "√E₁ (w₊ → −∞)", math.sqrt(E1), lo),
                                    ("upper", "√E₂ (w₊ → w₁)", math.sqrt(E2), hi))
    ]  # fmt: skip
    for e in ASYM_E3:
        law = TrilinearLaw(W1, W2, E1, E2, e)
        ours = qc.superkink_from_w_plus(law, W_PLUS)
        ref = closed_forms(W_PLUS, E1, e)["V_SK"]
        comps.append(compare("tri_existence", f"V_SK at w₊ = {W_PLUS:g}, E₃ = {e:g}",
                             FORMULAS["V_SK"], ref, ours.V,
                             roundoff(ref, 16) + ours.rayleigh_residual, rounding=0,
                             elapsed_s=t, source=f"qc.superkink_from_w_plus(E3={e:g} law, 0.3)"))
    params = {"E3": tuple(e3.tolist()), "w_plus": W_PLUS, "n": len(d.w_plus)}
    return panels, comps, params, ""


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
            ser += [series(f"discrete V_SK {'−+'[sign > 0]} {dv:g}", r.n, r.w, "points"),
                    series(f"QC V_SK {'−+'[sign > 0]} {dv:g}", x, q.profile(x))]  # fmt: skip
            notes.append(f"{side} {dv:g}: {'converged' if r.converged else 'NOT converged'}, "
                         f"amplitude {float(r.amplitude):.6g} (QC {float(q.amplitude):.6g})")  # fmt: skip
            amp, err = (float(r.amplitude), float(r.amplitude_error)) if r.converged else (
                np.nan, np.nan)  # fmt: skip
            comps.append(compare("tri_flattops", f"discrete amplitude at V_SK {'−+'[sign > 0]} "
                                 f"{dv:g}, under the superkink limit", "< |w₋ − w₊|", corner, amp,
                                 err, kind="upper_bound", elapsed_s=r.elapsed_s,
                                 source=f"wave.solve_solitary(law, 0.3, V, N=64).amplitude"))  # fmt: skip
        ser.append(series("w₋ (superkink limit)", [0.0], [sk.w_minus], "hline"))
        panels.append(Panel(f"({tag}) {side} V_SK = {sk.V:.6g}", "n, x", "w", tuple(ser)))
    return tuple(panels), comps, {"w_plus": W_PLUS, "dV": dvs, "N": 64}, "; ".join(notes)


def _compact_grid(reduced: bool) -> np.ndarray:
    vm = v_max(DEGENERATE, W_B)
    return np.array([0.3, 0.5, 0.7]) if reduced else np.round(np.linspace(0.1, 0.85, 8) * vm, 4)


def fig_tri_compact(reduced: bool):
    """The degenerate law (E₁ = 0): compact discrete solitary waves on the background w_B = 0.2
    for slow velocities 0 < V < V_max — (a) amplitude against V, the explicit form
    |b − w_B| + |C|, C = δ/(ω(1 − a)), ω = √(2E₂)/V (fpucore.wave.compact, derived from eq.
    TW_discrete) against the period-and-shift solver; (b) profiles, solver (points) and explicit
    (curves), localizing at the lattice scale as V → 0."""
    Vs = _compact_grid(reduced)
    vm = v_max(DEGENERATE, W_B)
    Vc = np.linspace(0.02, 0.999, 200) * vm
    a_ser = [series("explicit |b − w_B| + |C|", Vc,
                    [compact_wave(DEGENERATE, v, W_B).amplitude for v in Vc])]  # fmt: skip
    b_ser, comps, amps = [], [], []
    x = np.linspace(-2.5, 2.5, 501)
    for V in Vs:
        r = wave.solve_solitary(DEGENERATE, W_B, float(V))
        cw = compact_wave(DEGENERATE, float(V), W_B)
        ok = bool(r.converged)
        amps.append(float(r.amplitude) if ok else np.nan)
        keep = np.abs(r.n) <= 3
        b_ser += [series(f"solver V = {V:g}", r.n[keep], r.w[keep], "points"),
                  series(f"explicit V = {V:g}", x, cw.profile(x))]  # fmt: skip
        src = f"wave.solve_solitary(E1=0 law, {W_B:g}, {V:g})"
        amp, aerr = (float(r.amplitude), float(r.amplitude_error)) if ok else (np.nan, np.nan)
        mass = float(np.sum(r.w - W_B)) if ok else np.nan
        comps += [
            compare("tri_compact", f"amplitude at V = {V:g}", "|b − w_B| + |δ|/(ω(1 − a))",
                    cw.amplitude, amp, aerr, rounding=0, elapsed_s=r.elapsed_s,
                    source=src + ".amplitude"),
            # Σ(w_n − w_B) is the same at every phase of a traveling wave, hence = ∫(w − w_B)dξ
            compare("tri_compact", f"mass Σ(w_n − w_B) at V = {V:g}", "δ/(1 − a)", cw.mass, mass,
                    r.N * float(r.profile_error) if ok else np.nan, rounding=0,
                    elapsed_s=r.elapsed_s, source=src + ": Σ(w_n − w_B)"),
        ]  # fmt: skip
    a_ser += [series("solver", Vs, amps, "points"), series("V_max", [vm], [0.0], "vline")]
    panels = (
        Panel("(a) amplitude of the compact waves, E₁ = 0", "V", "max |w − w_B|", tuple(a_ser)),
        Panel("(b) profiles, solver (points) and explicit (curves)", "n, ξ", "w", tuple(b_ser)),
    )
    params = {"w1": W1, "w2": W2, "E1": 0.0, "E2": E2, "E3": E3, "w_B": W_B,
              "V": tuple(Vs.tolist()), "V_max": vm}  # fmt: skip
    return panels, comps, params, f"V_max = √(2E₂)/max(π, π/2 + |δ|/h) = {vm:.10g}"


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
        notes.append(f"V = {V:g}: max|μ| − 1 = {fr.max_modulus - 1:.3g}" if ok
                     else f"V = {V:g}: not converged ({fr.message})")  # fmt: skip
        mu = np.abs(np.asarray(fr.multipliers))
        rows.append((float(np.sum(np.log(mu))), float(np.sum(fr.error / mu)), float(V)) if ok
                    else (np.nan, np.nan, float(V)))  # fmt: skip
    liou, liou_err, at = max(rows, key=lambda t: np.inf if not np.isfinite(t[0])
                             else abs(t[0]) - t[1])  # fmt: skip
    comps.append(compare("tri_floquet", f"Σ log|μ| (Liouville), worst at V = {at:g}", "0", 0.0,
                         liou, liou_err, rounding=0, elapsed_s=elapsed,
                         source=f"floquet.spectrum(wave.solve_superkink(law, V, N={N}))"))  # fmt: skip
    r = wave.solve_superkink(LAW, 1.6, N=N)
    a = floquet.spectrum(r, finite_size=False)
    b = floquet.spectrum(r, method="dense", finite_size=False)
    comps.append(compare("tri_floquet", f"max|μ| at V = 1.6, structured vs dense (N = {N})",
                         "dense eigensolver", float(b.max_modulus), float(a.max_modulus),
                         float(a.error + b.error), rounding=0, elapsed_s=a.elapsed_s + b.elapsed_s,
                         source=f"floquet.spectrum(wave.solve_superkink(law, 1.6, N={N}))"))  # fmt: skip
    panels = (
        Panel(f"max |μ| of trilinear superkinks, N = {N}", "V", "max |μ|", (
            series("max |μ|", Vs, mods, "points"),
            series("√E₁, √E₂ (velocity bounds)", [math.sqrt(E1)], [1.0], "vline"),
            series("", [math.sqrt(E2)], [1.0], "vline"),
        )),
    )  # fmt: skip
    params = {"V": tuple(float(v) for v in Vs), "N": N, "law": LAW.expression}
    return panels, comps, params, "; ".join(notes) + f"; max error bar {np.nanmax(errs):.2g}"
