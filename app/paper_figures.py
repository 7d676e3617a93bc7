"""What a click on a paper figure (the Paper tab, or a link's ``fig=``) sets: the explorer's state
(tab, mode, w₊, V, N; the law a = −1, b = 10 throughout), the held curves of the figures that
draw families of profiles, and the Simulation scene's initial data for the simulation figures.

The velocities are those fpucore.paper's registry draws for each figure (figures_qc.py,
figures_wave.py, figures_dynamics.py: the paper's captions print no V for the families, its
plots do); the simulation runs are the paper's (captions of Figs. stabSK, Riemann1, stabSW,
SWdyn).  No panel here: app.state reads these tables to parse a link's ``fig=``.
"""

from __future__ import annotations

from fpucore import qc
from fpucore.law import CubicLaw

#: the paper's law (a = −1, b = 10)
PAPER_LAW = CubicLaw(-1.0, 10.0)


def sk_w_plus(V: float) -> float:
    """w₊ of the paper's superkink of velocity V (lower branch, w₊ < w*, as drawn in Figs.
    cubic (b), TWcubic)."""
    return qc.superkink_from_V(PAPER_LAW, V).w_plus


#: w₊ ahead of the superkink V = 5.2 (the paper's example, Figs. Floquet_example, stabSK (b)):
#: qc.superkink_from_V(CubicLaw(-1, 10), 5.2).w_plus — the state sets V = V_SK(w₊) from it
W_PLUS_5_2 = 0.6327161199294542
#: the state that shows each figure: (tab, mode, w_plus, V, N); in superkink mode V follows
#: w_plus (V = V_SK(w_plus), eq. cubic_cond2), so V is None there.
FIGURE_STATE: dict[str, tuple[str, str, float, float | None, int]] = {
    "superkink": ("force", "superkink", 1.0, None, 500),
    "pplane": ("phase", "solitary", 1.0, 5.373838498865699, 500),  # V_SK − 0.001
    "cubic": ("profiles", "superkink", sk_w_plus(4.9), None, 500),  # (b): V = 4.9 first
    "SWvelocities_cubic": ("diagram", "solitary", 1.0, 5.0, 500),
    "SWs_cubic": ("profiles", "solitary", 1.0, 5.0, 500),
    "SWamp_energy_QCcubic": ("diagram", "solitary", 1.0, 5.0, 500),
    "TWcubic": ("profiles", "superkink", W_PLUS_5_2, None, 500),
    "SWs_cubic_DvsQC": ("profiles", "solitary", 1.0, 5.2, 500),
    "SWamp_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, 500),
    "SWenergy_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, 500),
    "floquet_SK": ("floquet", "superkink", W_PLUS_5_2, None, 500),
    "Floquet_example": ("floquet", "superkink", W_PLUS_5_2, None, 500),
    # the seeded runs: the paper's wave (fpucore.paper: N = 64, tol = 1e-12, FIGURE_TOL), so
    # that the Simulation scene's measured velocity is the Paper tab's, digit for digit
    "stabSK": ("simulation", "superkink", W_PLUS_5_2, None, 64),
    "Riemann1": ("simulation", "superkink", 20.0 / 3.0 - 4.6, None, 500),  # V = 5.7209
    "floquet_cubicSW": ("floquet", "solitary", 1.0, 5.38, 500),
    "stabSW": ("simulation", "solitary", 6.0, 5.2174919476, 64),
    "SWdyn": ("simulation", "solitary", 1.0, 5.2494, 500),
}

#: the Newton tolerance of a figure's wave where it is not the explorer's default (1e-10):
#: fpucore.paper's seeded runs solve their waves at fpucore.wave's default 1e-12
FIGURE_TOL: dict[str, float] = {"stabSK": 1e-12, "stabSW": 1e-12}

#: the held curves of the figures that draw families of profiles, besides the current wave:
#: ("solitary", w₊, V) or ("superkink", w₊, None) — the rest of the family the figure draws
#: (at most app.state.MAX_HELD; the current wave is one of the family)
FIGURE_HELD: dict[str, tuple[tuple[str, float, float | None], ...]] = {
    # Fig. cubic (b): QC superkinks at V = 4.9, 5.2, 5.5, 5.8 (fpucore.paper fig_cubic)
    "cubic": tuple(("superkink", sk_w_plus(V), None) for V in (5.2, 5.5, 5.8)),
    # Fig. SWs_cubic (a) tensile 4.5, 5.0, 5.3, 5.37 and (b) compressive 5.38, 5.42, 5.46
    # at w₊ = 1 (panel (c), V_SK ∓ 1e-9 with the fronts, is the note's)
    "SWs_cubic": tuple(("solitary", 1.0, V) for V in (4.5, 5.3, 5.37, 5.38, 5.42, 5.46)),
    # Fig. TWcubic: discrete and QC superkinks at V = 4.8, 5.0, 5.2, 5.4, 5.6, 5.8
    "TWcubic": tuple(("superkink", sk_w_plus(V), None) for V in (4.8, 5.0, 5.4, 5.6, 5.8)),
    # Fig. SWs_cubic_DvsQC (a) 4.6, 5.2, 5.37 and (b) 5.38, 5.43, 5.48 at w₊ = 1
    "SWs_cubic_DvsQC": tuple(("solitary", 1.0, V) for V in (4.6, 5.37, 5.38, 5.43, 5.48)),
}

#: a run that takes longer than this (measured, see FIGURE_SCENARIO) waits for "Run simulation"
RUN_ON_CLICK_S = 3.0
_T50_SK = 50.0 * (1.0 / 5.2)  # 50 periods T = 1/V: fpucore.simulate.seeded's default t_end
_T50_SW = 50.0 * (1.0 / 5.2174919476)  # (computed as it computes it, to the last bit)
#: the Simulation scene's initial data of the simulation figures (fpucore.paper
#: figures_dynamics), with ``run_s``: the longest click-to-drawn time measured for it in the
#: app (Explorer, paper click, the run in a warm worker process, with the tracked sites' waves;
#: 2 cores shared with ~10 other processes, 2026-11-26; a server's first run adds the JIT
#: load) — the click starts the run when run_s <= RUN_ON_CLICK_S.
FIGURE_SCENARIO: dict[str, dict] = {
    # seeded with the current superkink V = 5.2 (panel (b)) for 50 periods; L = fpucore's
    # default chain for N = 64 (N + ⌈V t_end⌉ + 2·100 sites): fpucore.paper's run exactly
    "stabSK": {
        "kind": "seeded",
        "L": 314,
        "t_end": _T50_SK,
        "guard": "convex",
        "probes": (),
        "run_s": 0.4,
    },
    # Riemann data w^l = 4.6, w^r = 0, L = 3600 to t = 300, tracked sites 100, 200, 3000
    "Riemann1": {
        "kind": "riemann",
        "w_left": 4.6,
        "w_right": 0.0,
        "L": 3600,
        "t_end": 300.0,
        "guard": "convex",
        "probes": (100, 200, 3000),
        "run_s": 2.7,
    },
    # seeded with the tensile wave V = 5.2174919476 at w₊ = 6 (panel (b)) for 50 periods
    "stabSW": {
        "kind": "seeded",
        "L": 314,
        "t_end": _T50_SW,
        "guard": "convex",
        "probes": (),
        "run_s": 2.2,
    },
    # Gaussian data (a): w_B = 1, A = 6, L = 2400, t = 200 (leaves (α, β): guard "bounded")
    "SWdyn": {
        "kind": "gaussian",
        "w_B": 1.0,
        "A": 6.0,
        "L": 2400,
        "t_end": 200.0,
        "guard": "bounded",
        "probes": (),
        "run_s": 0.5,
    },
}

#: the part of a figure its scene computes only on demand elsewhere (a button), computed as part
#: of the click while the view is the figure's: the discrete dots of Figs. SWamp/SWenergy_cubic_
#: DvsQC (the diagram's "Add discrete points") and the Floquet sweeps of Figs. floquet_SK and
#: floquet_cubicSW (the Floquet scene's "Sweep max |μ| against V", its default 12 velocities)
FIGURE_PARTS: dict[str, str] = {
    "SWamp_cubic_DvsQC": "discrete",
    "SWenergy_cubic_DvsQC": "discrete",
    "floquet_SK": "sweep",
    "floquet_cubicSW": "sweep",
}

#: what of a figure the view does not show at once (another panel's parameters), in one line
FIGURE_NOTE: dict[str, str] = {
    "cubic": "Fig. cubic (a), w± against V_SK, is in the Paper tab's image only (no scene).",
    "pplane": "Fig. pplane (b), (c): V = V_SK and V = V_SK + 0.005 (type V).",
    "SWs_cubic": "Fig. SWs_cubic (c): V = V_SK ∓ 1e-9 with the kink and antikink fronts.",
    "SWs_cubic_DvsQC": (
        "Fig. SWs_cubic_DvsQC (c), (d) at w₊ = 6: V = 4.4, 5.0, 5.21 and 5.22, 5.3, 5.37."
    ),
    "stabSK": "Fig. stabSK (a): the superkink V = 4.8 (type V, then Run simulation).",
    "stabSW": "Fig. stabSW (a): the compressive wave V = 5.21749194749 (type V, then Run).",
    "SWdyn": "Fig. SWdyn (b): Gaussian, w_B = 6, A = −6, L = 3000, t_end = 250 (then Run).",
}


def scenario_runs(label: str) -> bool:
    """Whether a click on ``label`` starts its simulation (its measured cost is small)."""
    sc = FIGURE_SCENARIO.get(label)
    return sc is not None and sc["run_s"] <= RUN_ON_CLICK_S
