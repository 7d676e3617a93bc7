"""The quasicontinuum figures (paper §2–4): superkink, pplane, cubic, SWvelocities_cubic,
SWs_cubic, SWamp_energy_QCcubic.  Each ``fig_<label>(reduced)`` returns (panels, comparisons,
params, notes); every number comes from fpucore.qc, every reference from the paper's text.
"""

from __future__ import annotations

import math

import numpy as np

from fpucore import qc
from fpucore.paper.common import LAW, caption_speeds, roundoff
from fpucore.paper.compare import compare
from fpucore.paper.figure import Clock, Panel, series

W_PLUS = 1.0  # the paper's example state ahead (Figs. pplane, SWs_cubic, SWamp_energy_QCcubic)


def fig_superkink(reduced: bool):
    """Fig. superkink: f(w), the Rayleigh line of the superkink w₊ = 1 → w₋ = 17/3, and the
    tangent lines of slopes c₊², c₋² (eqs. Rline, zero_G, cplus, cminus)."""
    clock = Clock()
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    c_plus, _, c_minus = qc.sound_speeds(LAW, W_PLUS)
    w_s = qc.w_minus_sonic(LAW, W_PLUS)
    w = np.linspace(LAW.alpha, LAW.beta, 401)
    f_plus = float(LAW.f(W_PLUS))
    ray = f_plus + sk.V**2 * (w - W_PLUS)
    panels = (
        Panel(
            "f(w), Rayleigh line (equal areas) and sonic tangents, w₊ = 1",
            "w",
            "f(w)",
            (
                series("f(w)", w, LAW.f(w)),
                series("Rayleigh line, slope V_SK²", w, ray, "dashed"),
                series("slope c₊²", w, f_plus + c_plus**2 * (w - W_PLUS), "dashed"),
                series(
                    "slope c₋² (tangent at w₋ˢ)", w, f_plus + c_minus**2 * (w - W_PLUS), "dashed"
                ),
                series("w₊, w₋", [sk.w_plus, sk.w_minus], LAW.f([sk.w_plus, sk.w_minus]), "points"),
                series("w*", [LAW.w_star], [0.0], "vline"),
            ),
        ),
    )
    t = clock.s
    # the paper's eq. cubic_more, evaluated from its own formula
    a, b = abs(LAW.a), LAW.b
    alpha = -(math.sqrt(b * b + 3 * a) - b) / (3 * a)
    beta = (b + math.sqrt(b * b + 3 * a)) / (3 * a)
    src = "law = CubicLaw(-1, 10)"
    # (quantity, printed, paper's formula, ours, ulps of round-off, source)
    rows = [
        ("w* (eq. cubic_more)", "b/(3|a|)", b / (3 * a), LAW.w_star, 8, "law.w_star"),
        ("α (eq. cubic_more)", "−(√(b²+3|a|)−b)/(3|a|)", alpha, LAW.alpha, 64, "law.alpha"),
        ("β (eq. cubic_more)", "(b+√(b²+3|a|))/(3|a|)", beta, LAW.beta, 64, "law.beta"),
        (
            "w₋ˢ at w₊ = 1: (b − |a|w₊)/(2|a|)",
            "(b−|a|w₊)/(2|a|)",
            (b - a * W_PLUS) / (2 * a),
            w_s,
            8,
            "qc.w_minus_sonic(law, 1)",
        ),
    ]
    comps = [
        compare(
            "superkink",
            q,
            pr,
            ref,
            ours,
            roundoff(ref, ulps),
            source=f"{src}; {s}",
            elapsed_s=t,
            rounding=0,
        )
        for q, pr, ref, ours, ulps, s in rows
    ]
    # G is a difference of potentials ~Φ(w₋): its round-off scales with Φ(w₋), not with G = 0
    comps.insert(
        3,
        compare(
            "superkink",
            "driving force G at w₊ = 1 (eq. zero_G)",
            "0",
            0.0,
            sk.driving_force,
            roundoff(LAW.phi(sk.w_minus), 64),
            source="qc.superkink_from_w_plus(law, 1).driving_force",
            elapsed_s=t,
            rounding=0,
        ),
    )
    return panels, comps, {"a": LAW.a, "b": LAW.b, "w_plus": W_PLUS}, ""


PPLANE_DV = (-0.001, 0.0, 0.005)  # the caption's V − V_SK of panels (a), (b), (c)


def fig_pplane(reduced: bool):
    """Fig. pplane: phase portraits of eq. TW_QC_gen2 at w₊ = 1, V = V_SK − 0.001, V_SK,
    V_SK + 0.005 (fpucore.qc.phase.phase_plane): the highlighted orbits and critical points."""
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    panels, regimes, resid, elapsed = [], [], 0.0, 0.0
    for tag, dv in zip("abc", PPLANE_DV):
        pp = qc.phase.phase_plane(LAW, W_PLUS, sk.V + dv, n_grid=81 if reduced else 241)
        elapsed += pp.elapsed_s
        regimes.append(pp.regime)
        resid = max(resid, pp.orbit_residual)
        ser = [series("", pp.w, pp.wp, "contours", z=pp.H)]  # the level curves of H
        ser += [series(f"{o.name}", o.w, o.wp) for o in pp.orbits]
        for cp in pp.critical_points:
            ser.append(series(f"{cp.kind} ({cp.w:.4g}, 0)", [cp.w], [0.0], "points"))
        title = (
            f"({tag}) V = V_SK {'−' if dv < 0 else '+'} {abs(dv):g}" if dv else f"({tag}) V = V_SK"
        )
        panels.append(Panel(f"{title}: {pp.regime}", "w", "w′", tuple(ser)))
    comps = caption_speeds("pplane", W_PLUS, keys=("V_SK", "w_minus"))
    notes = (
        f"highlighted orbits: {', '.join(regimes)} (paper: tensile solitary wave, superkinks, "
        f"compressive solitary wave); orbit residual max|H − H(w₊)| / range = {resid:.2g}"
    )
    return tuple(panels), comps, {"w_plus": W_PLUS, "V - V_SK": PPLANE_DV}, notes


PAPER_V_BOUNDS = (("4.78423", 4.78423), ("5.85947", 5.85947))  # §6.1, eq. V_bounds_cubic


def fig_cubic(reduced: bool):
    """Fig. cubic: (a) w± of the superkink against V_SK (eq. wpm_cubic), both branches and both
    signs of V; (b) QC superkink profiles (eq. SKsoln_cubic) at several velocities."""
    clock = Clock()
    lo, hi = qc.superkink_velocity_bounds(LAW)
    V = np.linspace(lo, hi, 200)[1:-1]
    wp = np.array([qc.superkink_from_V(LAW, v).w_plus for v in V])
    wm = np.array([qc.superkink_from_V(LAW, v).w_minus for v in V])
    a_ser = []
    for sign in (1, -1):
        a_ser += [
            series("w₊" if sign > 0 else "", sign * V, wp),
            series("w₋" if sign > 0 else "", sign * V, wm, "dashed"),
        ]
    xi = np.linspace(-6, 6, 241)
    b_ser = []
    for v in (4.9, 5.2, 5.5, 5.8):
        sk = qc.superkink_from_V(LAW, v)
        b_ser.append(series(f"V = {v:g}", xi, sk.profile(xi)))
    panels = (
        Panel("(a) limiting strains w± of a superkink", "V_SK", "w±", tuple(a_ser)),
        Panel("(b) QC superkink profiles", "ξ", "w(ξ)", tuple(b_ser)),
    )
    t = clock.s
    comps = [
        compare(
            "cubic",
            f"superkink velocity {name} bound (eq. V_bounds_cubic)",
            printed,
            value,
            ours,
            roundoff(ours),
            source="qc.superkink_velocity_bounds(law)",
            elapsed_s=t,
        )
        for name, (printed, value), ours in zip(("lower", "upper"), PAPER_V_BOUNDS, (lo, hi))
    ]
    return panels, comps, {"a": LAW.a, "b": LAW.b, "V_profiles": (4.9, 5.2, 5.5, 5.8)}, ""


def fig_SWvelocities_cubic(reduced: bool):
    """Fig. SWvelocities_cubic: c₊, V_SK, c₋ against w₊ (fpucore.qc.diagram.existence_diagram),
    mirrored to −V; the three coincide at w₊ = w* where c² = 1 + b²/(3|a|)."""
    clock = Clock()
    d = qc.diagram.existence_diagram(LAW, n=100 if reduced else 400)
    ser = []
    for sign in (1, -1):
        lab = sign > 0
        ser += [
            series("V_SK (superkink limit)" if lab else "", d.w_plus, sign * d.V_SK),
            series("c₊ (sonic)" if lab else "", d.w_plus, sign * d.c_plus, "dashed"),
            series("c₋ (sonic)" if lab else "", d.w_plus, sign * d.c_minus, "dashed"),
        ]
    panels = (Panel("velocities of solitary waves against w₊", "w₊", "V", tuple(ser)),)
    t = clock.s
    c_star = math.sqrt(1.0 + LAW.b**2 / (3.0 * abs(LAW.a)))
    c_p, v_sk, c_m = qc.sound_speeds(LAW, LAW.w_star)
    comps = caption_speeds("SWvelocities_cubic", 1.0) + caption_speeds("SWvelocities_cubic", 6.0)
    for name, ours in (("c₊", c_p), ("V_SK", v_sk), ("c₋", c_m)):
        comps.append(
            compare(
                "SWvelocities_cubic",
                f"{name} at w₊ = w*",
                "√(1 − b²/(3a))",
                c_star,
                ours,
                roundoff(ours, 64),
                source="qc.sound_speeds(law, law.w_star)",
                elapsed_s=t,
                rounding=0,
            )
        )
    return panels, comps, {"a": LAW.a, "b": LAW.b, "n": len(d.w_plus)}, ""


def _qc_profiles(w_plus: float, velocities, xi):
    return tuple(
        series(f"V = {v:.10g}", xi, qc.solitary(LAW, w_plus, v).profile(xi)) for v in velocities
    )


def fig_SWs_cubic(reduced: bool):
    """Fig. SWs_cubic: QC solitary waves (eq. SWsoln_cubic) at w₊ = 1: (a) tensile, c₊ < V < V_SK;
    (b) compressive, V_SK < V < c₋; (c) just below / above V_SK with the kink and antikink."""
    c_plus, v_sk, c_minus = qc.sound_speeds(LAW, W_PLUS)
    xi = np.linspace(-15, 15, 601)
    below = (4.5, 5.0, 5.3, 5.37)
    above = (5.38, 5.42, 5.46)
    sk = qc.superkink_from_w_plus(LAW, W_PLUS)
    xi_c = np.linspace(-40, 40, 801)
    near = (v_sk - 1e-9, v_sk + 1e-9)
    c_ser = list(_qc_profiles(W_PLUS, near, xi_c))
    shift = 0.5 * qc.solitary(LAW, W_PLUS, near[0]).width
    c_ser.append(series("kink (shifted)", xi_c, sk.profile(xi_c - shift), "dashed"))
    c_ser.append(series("antikink (shifted)", xi_c, sk.profile(-xi_c - shift), "dashed"))
    panels = (
        Panel("(a) tensile waves, c₊ < V < V_SK", "ξ", "w", _qc_profiles(W_PLUS, below, xi)),
        Panel("(b) compressive waves, V_SK < V < c₋", "ξ", "w", _qc_profiles(W_PLUS, above, xi)),
        Panel("(c) V_SK ∓ 1e-9 with kink and antikink", "ξ", "w", tuple(c_ser)),
    )
    comps = caption_speeds("SWs_cubic", W_PLUS)
    return panels, comps, {"w_plus": W_PLUS, "V_a": below, "V_b": above, "V_c": near}, ""


def fig_SWamp_energy_QCcubic(reduced: bool):
    """Fig. SWamp_energy_QCcubic: amplitude (eq. SWQC_amp) and E_ren^QC (eq. Eren_QC) against V
    at w₊ = 1 (fpucore.qc.diagram.solitary_family); the corner at V_SK is |w₋ − w₊| = 14/3."""
    clock = Clock()
    fam = qc.diagram.solitary_family(LAW, W_PLUS, n=60 if reduced else 160)
    vline = series("V_SK", [fam.V_SK], [0.0], "vline")
    panels = tuple(
        Panel(
            title,
            "V",
            ylabel,
            (
                series(fam.kind_below, fam.V_below, below),
                series(fam.kind_above, fam.V_above, above),
                vline,
            ),
        )
        for title, ylabel, below, above in (
            ("(a) amplitude", "w_amp", fam.amp_below, fam.amp_above),
            ("(b) renormalized energy", "E_ren^QC", fam.energy_below, fam.energy_above),
        )
    )
    t = clock.s
    comps = caption_speeds("SWamp_energy_QCcubic", W_PLUS, keys=("V_SK", "c_plus", "c_minus"))
    comps.append(
        compare(
            "SWamp_energy_QCcubic",
            "amplitude at the SK corner |w₋ − w₊|",
            "17/3 − 1 = 14/3",
            14.0 / 3.0,
            fam.sk_amplitude,
            roundoff(fam.sk_amplitude),
            source="qc.diagram.solitary_family(law, 1).sk_amplitude",
            elapsed_s=t,
            rounding=0,
        )
    )
    notes = f"largest E_ren^QC error bound along the family: {fam.max_energy_error:.2g}"
    return panels, comps, {"w_plus": W_PLUS, "n": len(fam.V_below)}, notes
