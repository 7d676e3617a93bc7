"""The Simulation scene's words: what a run found (the tracker's waves, their velocities ± their
errors), the wave that passed a tracked site last, and the run's parameter line."""

from __future__ import annotations

import math

import numpy as np

from .formatting import fmt_num

MAX_PROBES = 3  # tracked-site panels drawn (the paper's (c), (d), (e))
SHORT_NAMES = {"dsw_edge": "DSW edge", "solitary": "solitary wave"}  # panel titles

KIND_WORDS = {
    "seeded": "the current traveling wave (TW-seeded)",
    "riemann": "Riemann data",
    "gaussian": "a Gaussian bump",
}
#: the tracker's kinds in plain words, with a one-line explanation (paper §6)
WAVE_NAMES = {
    "superkink": (
        "superkink",
        "a supersonic front between two states on opposite sides of w*, moving steadily",
    ),
    "solitary": ("solitary wave", "a single pulse on a uniform background, moving steadily"),
    "dsw_edge": (
        "edge of the dispersive shock",
        "the leading pulse of a spreading train of oscillations; not a steady wave, so its "
        "speed depends on when it is measured (included in the ±)",
    ),
    "front": ("front", "a jump between two states on the same side of w*"),
}


def last_to_pass(waves, site: int, t_end: float):
    """The tracked wave that passed ``site`` last before t_end (its straight path through
    ``position`` at t_end, at its measured velocity), or None: the wave a site's history ends
    with (Fig. Riemann1: site 200 sees the superkink, then the left DSW edge)."""
    best, t_best = None, -np.inf
    for w in waves:
        if not (np.isfinite(w.velocity) and w.velocity != 0 and np.isfinite(w.position)):
            continue
        t = t_end + (site - w.position) / w.velocity
        if 0.0 <= t <= t_end and t > t_best:
            best, t_best = w, t
    return best


def run_stamp(state_line: str, req) -> str:
    """The parameter line of a simulation: the state's (state_stamp), then the run's inputs
    exactly ("; run: riemann L=3600 t_end=300.0 … w_left=4.6 w_right=0.0")."""
    run = " ".join(f"{k}={v!r}" for k, v in req.params().items())
    return f"{state_line}; run: {req.kind} {run}"


def fmt_pm(x: float, err: float) -> str:
    """x ± err with x rounded to the error's second significant digit ("± 0": no spread)."""
    if not math.isfinite(err):
        return f"{x:.8g} ± ?"
    if err <= 0.0:
        return f"{x:.8g} ± 0"
    d = min(12, max(0, 1 - math.floor(math.log10(err))))
    return f"{x:.{d}f} ± {err:.1e}"


def tracked_velocities(waves, k: int = 4) -> str:
    """The status line's velocities: each with its error bar and digits (a DSW edge's V is
    known to ~1e-4, not to the 6 digits printed before), the count when more are tracked."""
    if not waves:
        return "tracked velocities: none"
    shown = ", ".join(fmt_pm(wv.velocity, wv.velocity_error) for wv in waves[:k])
    more = f" (and {len(waves) - k} more in the table)" if len(waves) > k else ""
    return f"tracked velocities: {shown}{more}"


def wave_table(waves) -> str:
    """Markdown table of the tracked waves: plain name, V ± error, w_B ± error, the states;
    then one line per kind present saying what it is and what the ± contains."""
    if not waves:
        return "_no waves tracked_"
    rows = [
        "| wave | velocity V ± error | state ahead w_B ± error | amplitude | strain left | "
        "strain right |",
        "|---|---|---|---|---|---|",
    ]
    for wv in waves:
        name = WAVE_NAMES.get(wv.kind, (wv.kind, ""))[0]
        rows.append(
            f"| {name} | {fmt_pm(wv.velocity, wv.velocity_error)} | "
            f"{fmt_pm(wv.background, wv.background_error)} | {fmt_num(wv.amplitude, 5)} | "
            f"{fmt_num(wv.left_state, 5)} | {fmt_num(wv.right_state, 5)} |"
        )
    kinds = dict.fromkeys(wv.kind for wv in waves)
    lines = [f"- **{WAVE_NAMES[k][0]}**: {WAVE_NAMES[k][1]}" for k in kinds if k in WAVE_NAMES]
    lines.append(
        "- ± of V: the fit's standard error plus the measured spread over fit windows and "
        "tracking thresholds; ± of w_B: its spread over the window and the thresholds"
    )
    return "**Waves found by the tracker**\n\n" + "\n".join(rows) + "\n\n" + "\n".join(lines)
