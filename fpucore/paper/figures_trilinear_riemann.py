"""The degenerate trilinear law's Riemann runs (E₁ = 0: no force below w₁, a "sonic vacuum";
companion study arXiv 2406.06437): ``fig_tri_riemann(reduced)`` returns (panels, comparisons,
params, notes) as the other trilinear figures (fpucore.paper.registry_trilinear).

* A velocity jump (:func:`fpucore.simulate.impact.velocity_jump`: strain w_B everywhere, the left
  half pulled away with v_left < 0) sends out to each side a periodic train of compact solitary
  waves — a Whitham shock into the state at rest — tracked by
  :func:`fpucore.simulate.trains.track_train`.  Rows: every tracked wave's crest against the
  EXPLICIT compact wave of its measured V (fpucore.wave.compact, from eq. TW_discrete); the
  train's V against the mass balance V M(V) = P |v_left|/2 at spacing P = 2
  (:func:`fpucore.simulate.trains.train_velocity`, closed form); the spacing against 2; the
  count against the excess strain behind the train over one wave's mass; the energy drift; the
  breakpoint crossings all located (no step taken unlocated).
* Riemann data at rest, w = 0.6 | 0 (the strain jump of eq. Riemann_data): a front moves into
  the sonic vacuum and a modulated train of pulses follows it; those pulses are faster than the
  explicit waves' range and overlap, so they are drawn, not compared (docs/guide/trilinear.md).
"""

from __future__ import annotations

import numpy as np

from fpucore import simulate
from fpucore.paper.compare import compare
from fpucore.paper.figure import Panel, series
from fpucore.paper.figures_trilinear import DEGENERATE, E2, E3, W1, W2, W_B
from fpucore.simulate.impact import velocity_jump
from fpucore.simulate.trains import track_train, train_velocity
from fpucore.wave.compact import compact_wave

V_LEFT = -0.2  # the left half pulled away (strain per unit time)
AT_REST = (0.6, 0.0)  # Riemann data at rest: hard regime | sonic vacuum
FIG = "tri_riemann"


def _sizes(reduced: bool) -> tuple[int, float]:
    return (200, 60.0) if reduced else (600, 200.0)


def _crest_slope(V: float, h: float = 1e-6) -> float:
    a, b = compact_wave(DEGENERATE, V + h, W_B), compact_wave(DEGENERATE, V - h, W_B)
    return ((a.b + a.C) - (b.b + b.C)) / (2 * h)


def _train_rows(r, tr) -> list:
    src = f"simulate.trains.track_train(velocity_jump(E1=0 law, {W_B:g}, {W_B:g}, {V_LEFT:g}))"
    el = r.elapsed_s + tr.elapsed_s
    # the wave whose crest is farthest from its explicit crest, measured in its own error bar
    rows = []
    for V, dV, c, dc in zip(tr.velocities, tr.velocity_errors, tr.crests, tr.crest_errors):
        cw = compact_wave(DEGENERATE, float(V), W_B)
        err = float(dc + abs(_crest_slope(float(V))) * dV)
        rows.append((abs(cw.b + cw.C - c) / err, float(V), cw.b + cw.C, float(c), err))
    _, V, ref, c, err = max(rows)
    cw = compact_wave(DEGENERATE, tr.velocity, W_B)
    excess = float(np.sum(r.final_w[r.L // 2 :] - W_B))
    return [
        compare(
            FIG,
            f"crest of the train's waves (worst, V = {V:.8g})",
            "w₁ + δ/(ω(1 − a))",
            ref,
            c,
            err,
            rounding=0,
            source=src,
            elapsed_s=el,
        ),
        compare(
            FIG,
            "train velocity V",
            "V M(V) = P|v_left|/2, P = 2",
            train_velocity(DEGENERATE, W_B, V_LEFT),
            tr.velocity,
            tr.velocity_error,
            rounding=0,
            source=src,
            elapsed_s=el,
        ),
        compare(
            FIG,
            "spacing of the train (sites)",
            "2",
            2.0,
            tr.spacing,
            tr.spacing_error,
            rounding=0,
            source=src,
            elapsed_s=el,
        ),
        # the wave straddling the jump is counted whole or not: ±1
        compare(
            FIG,
            "waves in the right train",
            "Σ(w_n − w_B)/M, M = δ/(1 − a)",
            excess / cw.mass,
            tr.n_waves,
            1.0,
            rounding=0,
            source=src,
            elapsed_s=el,
        ),
    ]


def _run_rows(r, what: str) -> list:
    src = f"simulate.{what}"
    return [
        compare(
            FIG,
            f"energy drift, {what}",
            "< 1e-10",
            1e-10,
            r.energy_drift,
            0.0,
            source=src,
            elapsed_s=r.elapsed_s,
            kind="upper_bound",
        ),
        compare(
            FIG,
            f"steps taken unlocated at a breakpoint, {what}",
            "0 (< 0.5)",
            0.5,
            r.details.get("unlocated_tangencies", 0),
            0.0,
            source=src,
            elapsed_s=r.elapsed_s,
            kind="upper_bound",
        ),
    ]


def _explicit_train(tr, x: np.ndarray, origin: float) -> np.ndarray:
    """The superposed explicit compact waves at the tracked positions (lead − kP), w_B elsewhere:
    exact while the supports overlap only in the zero-modulus regime (P ≥ 1 + 2a)."""
    cw = compact_wave(DEGENERATE, tr.velocity, W_B)
    w = np.full_like(x, W_B)
    for k in range(tr.n_waves):
        c = tr.lead_position - k * tr.spacing
        if c > origin:
            w += cw.profile(x - c) - W_B
    return w


def fig_tri_riemann(reduced: bool):
    """(a) space–time strain of the velocity-jump run; (b) its final profile with the explicit
    train; (c) the crests of the tracked waves against the explicit crest curve; (d) the
    Riemann run at rest, w = 0.6 | 0 (module docstring)."""
    L, T = _sizes(reduced)
    probes = list(range(L // 2 + 4, L // 2 + 16))
    r = velocity_jump(
        DEGENERATE,
        W_B,
        W_B,
        V_LEFT,
        L,
        T,
        guard="bounded",
        probes=probes,
        n_probe_t=int(T * 100) + 1,
        max_sites_out=L,
    )
    tr = track_train(r, DEGENERATE, side=1)
    comps = _run_rows(r, "velocity_jump") + (_train_rows(r, tr) if tr.converged else [])
    rest = simulate.riemann(DEGENERATE, *AT_REST, L, T / 2, guard="bounded", max_sites_out=L)
    comps += _run_rows(rest, "riemann at rest")
    origin = L / 2 + 0.5
    n = np.arange(1, L + 1, dtype=float)
    right = n > origin - 2
    x = np.linspace(origin - 2, min(tr.lead_position + 4, L), 4000)
    Vs = np.linspace(0.8, 1.2, 101) * tr.velocity
    cc = [compact_wave(DEGENERATE, float(v), W_B) for v in Vs]
    panels = (
        Panel(
            f"(a) velocity jump v_left = {V_LEFT:g} on w_B = {W_B:g}, E₁ = 0",
            "n",
            "t",
            (series("w_n(t)", r.sites, r.t, "image", z=r.snapshots),),
        ),
        Panel(
            f"(b) right train at t = {r.t_final:g}: chain (points), explicit waves (curve)",
            "n",
            "w",
            (
                series("w_n", n[right], r.final_w[right], "points"),
                series("explicit compact train", x, _explicit_train(tr, x, origin)),
                series("w₁", [W1], [0.0], "hline"),
            ),
        ),
        Panel(
            "(c) crests of the tracked waves against V",
            "V",
            "crest",
            (
                series("explicit w₁ + δ/(ω(1 − a))", Vs, [c.b + c.C for c in cc]),
                series("tracked waves", tr.velocities, tr.crests, "points"),
            ),
        ),
        Panel(
            f"(d) Riemann data at rest, w = {AT_REST[0]:g} | {AT_REST[1]:g}: front and pulses",
            "n",
            "t",
            (series("w_n(t)", rest.sites, rest.t, "image", z=rest.snapshots),),
        ),
    )
    params = {
        "w1": W1,
        "w2": W2,
        "E1": 0.0,
        "E2": E2,
        "E3": E3,
        "w_B": W_B,
        "v_left": V_LEFT,
        "L": L,
        "t_end": T,
        "at_rest": AT_REST,
    }
    fronts = ", ".join(f"{w.kind} V = {w.velocity:.4g}" for w in rest.waves if w.velocity > 0)
    notes = (
        f"velocity jump: {tr.message}; crossings located "
        f"{r.details.get('breakpoint_crossings', 0)}.  At rest {AT_REST[0]:g} | "
        f"{AT_REST[1]:g} (t = {T / 2:g}): {fronts or 'no right-moving wave tracked'}, "
        "a modulated train of pulses behind it, not compared"
    )
    return panels, comps, params, notes
