"""What a reproduced figure is: panels of named series (plain arrays, picklable, cacheable) and
the comparisons with the paper's printed numbers.  Plotting (fpucore.paper.plot) reads only this.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from fpucore.paper.compare import Comparison
from fpucore.result import Result

STYLES = ("line", "dashed", "points", "vline", "hline", "image", "contours")


@dataclass(frozen=True)
class Series:
    """One drawn object of a panel.

    style : "line", "dashed", "points" (x, y of equal length), "vline" / "hline" (x or y is a
        length-1 array: the position), "image" (x (nx,), y (ny,), z (ny, nx): a space–time map),
        "contours" (x, y, z as for "image"; level curves of z, e.g. the phase portrait's H).
    """

    label: str
    x: np.ndarray
    y: np.ndarray
    style: str = "line"
    z: np.ndarray | None = None


@dataclass(frozen=True)
class Panel:
    """One panel ((a), (b), …) of a figure: title, axis labels (Unicode), series."""

    title: str
    xlabel: str
    ylabel: str
    series: tuple[Series, ...]


@dataclass(frozen=True)
class FigureResult(Result):
    """A computed figure: panels, comparisons, the parameters used and whether N was reduced.

    ``converged`` holds when every comparison produced a finite value (the verdicts themselves
    are in ``comparisons``: a disagreement is a result, reported, not a failure to compute).
    """

    label: str
    params: dict
    panels: tuple[Panel, ...]
    comparisons: tuple[Comparison, ...]
    reduced: bool
    elapsed_s: float
    notes: str = ""
    extra: dict = field(default_factory=dict)

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = ("max_error",)
    DERIVED: ClassVar[tuple[str, ...]] = ("status", "n_agree", "max_error")
    EXCLUDE: ClassVar[tuple[str, ...]] = ("panels",)

    @property
    def converged(self) -> bool:
        return all(c.converged for c in self.comparisons)

    @property
    def status(self) -> str:
        return "ok" if self.converged else "not_converged"

    @property
    def message(self) -> str:
        bad = [c.quantity for c in self.comparisons if not c.agrees]
        return "all comparisons agree" if not bad else "disagrees: " + "; ".join(bad)

    @property
    def max_error(self) -> float:
        """The largest error bar among the comparisons (0 without comparisons)."""
        return max((c.error for c in self.comparisons), default=0.0)

    @property
    def n_agree(self) -> int:
        return sum(c.agrees for c in self.comparisons)


def series(label: str, x, y, style: str = "line", z=None) -> Series:
    """A :class:`Series` with float arrays (x, y at least 1-d)."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    y = np.atleast_1d(np.asarray(y, dtype=float))
    return Series(label, x, y, style, None if z is None else np.asarray(z, dtype=float))


class Clock:
    """Wall time since construction (s): ``Clock().s``."""

    def __init__(self) -> None:
        self.t0 = time.perf_counter()

    @property
    def s(self) -> float:
        return time.perf_counter() - self.t0
