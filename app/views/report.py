"""What a render reports: an :class:`Info` beside its plot (what is shown, error estimates,
model differences, timings, notes), or a :class:`SceneMessage` instead of it; and the status
Markdown written from an Info.

Kept apart from the Scene machinery (:mod:`.scene`): every scene's ``render`` fills an Info or
raises a SceneMessage, and that contract is all a scene module needs to import from here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..compute import Computed
from .formatting import fmt_time, fmt_timing
from .untrusted import md_literal


class SceneMessage(Exception):
    """Shown in the scene instead of a plot (an invalid combination, a missing module ...)."""

    def __init__(self, text: str, kind: str = "warning"):
        super().__init__(text)
        self.kind = kind


@dataclass
class Info:
    """What a render reports next to its plot."""

    #: Markdown: user-supplied parts (a path, an exception's text) go through md_literal
    shown: str = ""
    errors: list[tuple[str, float]] = field(default_factory=list)
    #: differences between two models (e.g. max |discrete − QC|): physics, not numerical error
    differences: list[tuple[str, float]] = field(default_factory=list)
    timings: list[tuple[str, Computed | float]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warning: str | None = None  # shown above the plot (e.g. "current V out of range")
    #: the parameters the render used, when they are not the state's (state_stamp): a scene
    #: whose result depends on its own inputs (the Simulation scene's run) names them
    stamp: str = ""

    def time(self, label: str, c: Computed | float) -> None:
        self.timings.append((label, c))

    def error(self, label: str, value) -> None:
        _append_finite(self.errors, label, value)

    def difference(self, label: str, value) -> None:
        """A model difference (shown on its own line, never under "Error")."""
        _append_finite(self.differences, label, value)


def _append_finite(rows: list[tuple[str, float]], label: str, value) -> None:
    try:
        v = float(value)
    except (TypeError, ValueError):
        return
    if math.isfinite(v):
        rows.append((label, v))


def status_markdown(info: Info, server_s: float, stamp: str, partial: bool = False) -> str:
    """The scene's "Error and time" text: what is shown, its errors, model differences, the
    timings (``server_s``: the whole render on the server), notes and the parameters used
    (``stamp``, shown literally)."""
    lines = []
    if info.shown:
        lines.append(f"**Shown:** {info.shown}")
    if info.errors:
        errs = " · ".join(f"{k} {v:.2e}" for k, v in info.errors)
        lines.append(f"**Error:** {errs}")
    if info.differences:
        diffs = " · ".join(f"{k} {v:.2e}" for k, v in info.differences)
        lines.append(f"**Model difference:** {diffs}")
    tparts = [fmt_timing(label, c) for label, c in info.timings]
    tparts.append(f"server {fmt_time(server_s)}")
    lines.append("**Time:** " + " · ".join(tparts))
    lines.extend(f"_{n}_" for n in info.notes)
    if partial:
        lines.append("_computing the rest ..._")
    lines.append(f"<small>Parameters: {md_literal(stamp)}</small>")
    return "\n\n".join(lines)
