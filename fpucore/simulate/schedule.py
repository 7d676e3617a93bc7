"""The output schedule of a chain simulation: the times of its snapshots, of its tracking window
and of extra full-resolution profiles, merged into the stops of the stepper."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Schedule:
    """Output times of a run: t_out (n_snapshots,) from 0 to t_end; t_trk (n_track,) the tracking
    window [t_end (1 − late_fraction), t_end]; t_extra full-resolution profiles; ``stops`` the
    sorted union of them (> 0), each a stop of the stepper; out/trk/ext map a stop to its row."""

    t_out: np.ndarray
    t_trk: np.ndarray
    t_extra: np.ndarray
    stops: np.ndarray
    out: dict
    trk: dict
    ext: dict


def output_schedule(
    t_end: float,
    n_snapshots: int,
    late_fraction: float,
    n_track: int,
    track: bool,
    extra_times: Sequence[float] = (),
) -> Schedule:
    """The stops of a run.  An extra time within rounding of t_end (relative 1e-12: e.g. K·(1/V)
    for t_end = K/V, one ulp above it for ~9 % of velocities) is taken at t_end; one beyond it,
    or ≤ 0, is an error of the caller (ValueError), never silently dropped."""
    t_out = np.linspace(0.0, t_end, n_snapshots)
    t_a = t_end * (1.0 - late_fraction)
    t_trk = np.linspace(t_a, t_end, n_track) if track else np.empty(0)
    extra = []
    for x in extra_times:
        x = float(x)
        if x > t_end and x <= t_end * (1.0 + 1e-12):
            x = t_end
        if not (0.0 < x <= t_end):
            raise ValueError(f"extra output time {x!r} outside (0, t_end = {t_end!r}]")
        extra.append(x)
    t_extra = np.asarray(sorted(extra), dtype=float)
    stops = np.unique(np.concatenate([t_out[1:], t_trk, t_extra]))
    stops = stops[stops > 0]
    return Schedule(
        t_out, t_trk, t_extra, stops,
        {float(x): k for k, x in enumerate(t_out)},
        {float(x): k for k, x in enumerate(t_trk)},
        {float(x): k for k, x in enumerate(t_extra)},
    )  # fmt: skip
