"""The discrete traveling-wave figures (paper §5): TWcubic, SWs_cubic_DvsQC, SWamp_cubic_DvsQC,
SWenergy_cubic_DvsQC — fpucore.wave families against fpucore.qc closed forms.
"""

from __future__ import annotations

import numpy as np

from fpucore import qc, wave
from fpucore.paper.common import LAW, caption_speeds
from fpucore.paper.compare import compare
from fpucore.paper.figure import Clock, Panel, series

SK_VELOCITIES = (4.8, 5.0, 5.2, 5.4, 5.6, 5.8)


def fig_TWcubic(reduced: bool):
    """Fig. TWcubic: discrete superkinks w_n(0) (points) and QC superkinks w(x) (curves)."""
    clock = Clock()
    Vs = SK_VELOCITIES[::2] if reduced else SK_VELOCITIES
    fam = wave.superkink_family(LAW, list(Vs))
    ser = []
    for r in fam.results:
        sk = qc.superkink_from_V(LAW, r.V)
        keep = np.abs(r.n) <= 12
        x = np.linspace(-12, 12, 241)
        ser += [
            series(f"discrete V = {r.V:g}", r.n[keep], r.w[keep], "points"),
            series(f"QC V = {r.V:g}", x, sk.profile(x)),
        ]
    panels = (Panel("superkinks, discrete (points) and QC (curves)", "n, x", "w", tuple(ser)),)
    t = clock.s
    dropped = max(r.dropped_residual for r in fam.results)
    comps = [
        compare(
            "TWcubic",
            "the dropped equation ẇ_{N/2}(T) is satisfied (max over V)",
            "≤ 1e-13",
            1e-13,
            dropped,
            0.0,
            source="wave.superkink_family(law, V).results[i].dropped_residual",
            elapsed_s=t,
            kind="upper_bound",
        ),
    ]
    dev = max(float(r.qc_max_deviation) for r in fam.results)
    notes = (
        f"velocities {list(Vs)}, automatic N = {[r.N for r in fam.results]}; "
        f"max |w_n − w_QC(n)| = {dev:.3g} (the paper: 'barely visible difference in the transition "
        f"layer'); largest profile_error {max(r.profile_error for r in fam.results):.2g}"
    )
    return panels, comps, {"V": Vs}, notes


def _solitary_grid(w_plus: float, reduced: bool):
    """Velocities in (c₊, V_SK) and (V_SK, c₋), clustered toward V_SK (as in the paper's plots)."""
    c_plus, v_sk, c_minus = qc.sound_speeds(LAW, w_plus)
    n = 4 if reduced else 12
    s = np.linspace(0.05, 1.0, n) ** 2
    below = v_sk - (v_sk - c_plus) * s[::-1] * 0.98
    above = v_sk + (c_minus - v_sk) * s * 0.98
    return below, above, v_sk


def _families(w_plus: float, reduced: bool):
    below, above, v_sk = _solitary_grid(w_plus, reduced)
    return (
        wave.solitary_family(LAW, w_plus, list(below)),
        wave.solitary_family(LAW, w_plus, list(above)),
        v_sk,
    )


PROFILE_V = {
    1.0: ((4.6, 5.2, 5.37), (5.38, 5.43, 5.48)),
    6.0: ((4.4, 5.0, 5.21), (5.22, 5.3, 5.37)),
}


def fig_SWs_cubic_DvsQC(reduced: bool):
    """Fig. SWs_cubic_DvsQC: discrete solitary waves (points) and QC ones (curves): (a) tensile
    below and (b) compressive above V_SK at w₊ = 1; (c) compressive below, (d) tensile above at
    w₊ = 6."""
    panels, comps, conv, elapsed = [], [], [], 0.0
    tags = iter("abcd")
    for w_plus in (1.0, 6.0):
        for side, Vs in zip(("below", "above"), PROFILE_V[w_plus]):
            if reduced:
                Vs = Vs[-1:]  # type: ignore[assignment]
            fam = wave.solitary_family(LAW, w_plus, list(Vs))
            elapsed += fam.elapsed_s
            ser = []
            for r in fam.results:
                conv.append(bool(r.converged))
                q = qc.solitary(LAW, w_plus, r.V)
                half = min(int(np.max(np.abs(r.n))), 25)
                keep = np.abs(r.n) <= half
                x = np.linspace(-half, half, 10 * half + 1)
                ser += [
                    series(f"discrete V = {r.V:g}", r.n[keep], r.w[keep], "points"),
                    series(f"QC V = {r.V:g}", x, q.profile(x)),
                ]
            panels.append(
                Panel(f"({next(tags)}) w₊ = {w_plus:g}, {side} V_SK", "n, x", "w", tuple(ser))
            )
        comps += caption_speeds("SWs_cubic_DvsQC", w_plus)
    notes = f"{sum(conv)}/{len(conv)} discrete waves converged"
    return tuple(panels), comps, {"V": PROFILE_V}, notes


def _amp_energy(label: str, reduced: bool, quantity: str):
    """Shared by SWamp_cubic_DvsQC (quantity 'amplitude') and SWenergy_cubic_DvsQC ('energy')."""
    clock = Clock()
    panels, comps, notes = [], [], []
    for tag, w_plus in zip("ab", (1.0, 6.0)):
        fam_b, fam_a, v_sk = _families(w_plus, reduced)
        qfam = qc.diagram.solitary_family(LAW, w_plus, n=60 if reduced else 160)
        qy_b = qfam.amp_below if quantity == "amplitude" else qfam.energy_below
        qy_a = qfam.amp_above if quantity == "amplitude" else qfam.energy_above
        ser = [
            series(f"QC {qfam.kind_below}", qfam.V_below, qy_b),
            series(f"QC {qfam.kind_above}", qfam.V_above, qy_a),
        ]
        for fam, kind in ((fam_b, qfam.kind_below), (fam_a, qfam.kind_above)):
            ok = np.asarray(fam.wave_converged, bool)
            y = fam.amplitude if quantity == "amplitude" else fam.energy
            ser.append(
                series(f"discrete {kind}", np.asarray(fam.V)[ok], np.asarray(y)[ok], "points")
            )
            notes.append(f"w₊ = {w_plus:g}: {int(ok.sum())}/{ok.size} discrete {kind} converged")
        ser.append(series("V_SK", [v_sk], [0.0], "vline"))
        ylabel = "w_amp = |w(0) − w₊|" if quantity == "amplitude" else "E_ren"
        panels.append(Panel(f"({tag}) w₊ = {w_plus:g}", "V", ylabel, tuple(ser)))
        comps += caption_speeds(label, w_plus)
        if quantity == "amplitude":
            comps.append(_sk_limit_amplitude(label, w_plus, v_sk, clock))
    return tuple(panels), comps, {"w_plus": (1.0, 6.0)}, "; ".join(notes)


SK_LIMIT_DV = (1e-4, 1e-6, 1e-8, 1e-10)  # distances below V_SK of the discrete waves used


def _aitken(a) -> float:
    """Limit of a sequence a_k converging geometrically (Aitken's Δ², the rate measured)."""
    d1, d2 = a[1] - a[0], a[2] - a[1]
    return a[2] + d2 * d2 / (d1 - d2)


def _sk_limit_amplitude(label: str, w_plus: float, v_sk: float, clock: Clock):
    """§4/§5: at the superkink limit the amplitude reaches |w₋ − w₊| (the corner of the
    amplitude plot), in the discrete chain as in the QC model (w± obey the same Rankine–Hugoniot
    and zero-G conditions).  The discrete amplitudes at V_SK − 1e-4 … 1e-10 approach it like
    ΔV^p (p ≈ 1/2 measured); ours is Aitken's extrapolation of the last three, its error bar the
    change from the extrapolation of the first three plus the last wave's amplitude_error."""
    sk = qc.superkink_from_w_plus(LAW, w_plus)
    corner = abs(sk.w_minus - sk.w_plus)
    rs = [wave.solve_solitary(LAW, w_plus, v_sk - dv) for dv in SK_LIMIT_DV]
    elapsed = sum(r.elapsed_s for r in rs)
    num = {1.0: "14/3", 6.0: "16/3"}[w_plus]
    src = f"wave.solve_solitary(law, {w_plus:g}, V_SK − ΔV).amplitude, ΔV = 1e-4 … 1e-10, Aitken"
    if not all(r.converged for r in rs):
        ours, err = np.nan, np.nan
    else:
        amp = [float(r.amplitude) for r in rs]
        ours = _aitken(amp[1:])
        err = abs(ours - _aitken(amp[:3])) + float(rs[-1].amplitude_error)
    return compare(
        label,
        f"discrete amplitude in the SK limit V → V_SK⁻, w₊ = {w_plus:g}",
        f"|w₋ − w₊| = {num}",
        corner,
        ours,
        err,
        source=src,
        elapsed_s=elapsed,
        rounding=0,
    )


def fig_SWamp_cubic_DvsQC(reduced: bool):
    """Fig. SWamp_cubic_DvsQC: amplitude against V, discrete (dots) and QC (curves), w₊ = 1, 6."""
    return _amp_energy("SWamp_cubic_DvsQC", reduced, "amplitude")


def fig_SWenergy_cubic_DvsQC(reduced: bool):
    """Fig. SWenergy_cubic_DvsQC: E_ren (eqs. Eren_D, Eren_QC) against V, w₊ = 1, 6."""
    return _amp_energy("SWenergy_cubic_DvsQC", reduced, "energy")
