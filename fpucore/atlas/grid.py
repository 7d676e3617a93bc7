"""The atlas grid: rows (w₊ for solitary waves, the branch for superkinks) × velocities V, and
its chunks (contiguous runs of V along one row: the unit of work, of continuation and of storage).

``"LO:HI:K"`` means K values from LO to HI inclusive; ``"K"`` alone (V only) means K velocities
spanning the union of the existence intervals over the rows — (min c₊, max c₋) over w₊ for
solitary waves (paper eqs. cplus, cminus_cubic), the bounds of eq. V_bounds_cubic for
superkinks — end points excluded (sonic limits, where no wave of finite width exists).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError

if TYPE_CHECKING:
    from collections.abc import Sequence

    from fpucore.law.base import HardeningSofteningLaw

KINDS = ("solitary", "superkink")
BRANCHES = ("lower", "upper")
MAX_POINTS = 1_000_000


@dataclass(frozen=True)
class Grid:
    """kind; row_dim ("w_plus" | "branch"); rows (n_rows,) floats or branch names; V (n_V,);
    chunk: points per chunk along V (a grid line is split into ceil(n_V / chunk) chunks)."""

    kind: str
    row_dim: str
    rows: tuple
    V: np.ndarray
    chunk: int

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), self.V.size

    @property
    def size(self) -> int:
        return len(self.rows) * self.V.size

    def chunks(self) -> list[tuple[int, int, int]]:
        """(row index, first V index, end V index) of every chunk, in grid order."""
        n = self.V.size
        return [
            (i, j, min(j + self.chunk, n))
            for i in range(len(self.rows))
            for j in range(0, n, self.chunk)
        ]


def parse_values(
    name: str, spec: str | Sequence[float] | np.ndarray | int, allow_count: bool = False
) -> np.ndarray | int:
    """``"LO:HI:K"`` → K values, ``"x"`` or a list → those values, ``"K"`` (allow_count) → K."""
    if isinstance(spec, (list, tuple, np.ndarray)):
        vals = np.asarray(spec, dtype=float).ravel()
    else:
        s = str(spec).strip()
        parts = s.split(":")
        try:
            if len(parts) == 3:
                lo, hi, k = float(parts[0]), float(parts[1]), int(parts[2])
                if not (1 <= k <= 100_000):
                    raise ParameterError(name, s, "LO:HI:K with 1 <= K <= 100000")
                vals = np.linspace(lo, hi, k)
            elif len(parts) == 1 and allow_count and s.isdigit():
                k = int(s)
                if not (1 <= k <= 100_000):
                    raise ParameterError(name, s, "a count K in [1, 100000] or LO:HI:K")
                return k
            elif len(parts) == 1:
                vals = np.array([float(s)])
            else:
                raise ValueError
        except ValueError:
            raise ParameterError(
                name, s, "LO:HI:K, a number" + (" or a count K" if allow_count else "")
            ) from None
    if vals.size == 0 or not np.all(np.isfinite(vals)):
        raise ParameterError(name, spec, "finite values")
    return vals


def velocity_span(law: HardeningSofteningLaw, kind: str, rows: Any) -> tuple[float, float]:
    """Union of the existence intervals of V over the rows (see module doc)."""
    lo, hi = math.inf, -math.inf
    if kind == "superkink":  # the branches share eq. V_bounds_cubic; a general law's may differ
        for branch in rows:
            a, b = qc.superkink_velocity_bounds(law, branch)
            lo, hi = min(lo, a), max(hi, b)
        return lo, hi
    for w in rows:
        try:
            cp, _, cm = qc.sound_speeds(law, float(w))
        except ParameterError:
            continue  # w₊ outside (α, β): a row of "no wave"
        lo, hi = min(lo, cp), max(hi, cm)
    if not lo < hi:
        valid = f"values in (alpha, beta) = ({law.alpha:.10g}, {law.beta:.10g})"
        raise ParameterError("w_plus", list(rows), valid, "no row has waves")
    return lo, hi


def make_grid(
    law: HardeningSofteningLaw,
    kind: str,
    rows: Any,
    V: str | Sequence[float] | np.ndarray | int,
    chunk: int | None = None,
) -> Grid:
    """rows : w₊ values (``"LO:HI:K"``, a number or a list; solitary) or branch names
    (superkink).  V : ``"LO:HI:K"``, a list, or a count K (see module doc).  chunk : points per
    chunk (default: a whole grid line for solitary grids, 4 for superkinks, whose only line
    would otherwise run on one worker)."""
    if kind not in KINDS:
        raise ParameterError("kind", kind, " | ".join(KINDS))
    if kind == "solitary":
        row_dim, row_vals = "w_plus", tuple(float(x) for x in parse_values("w_plus", rows))  # type: ignore[union-attr]
    else:
        names = [rows] if isinstance(rows, str) else list(rows or ["lower"])
        if not names or any(b not in BRANCHES for b in names) or len(set(names)) != len(names):
            raise ParameterError("branch", rows, "lower | upper | both")
        row_dim, row_vals = "branch", tuple(names)  # type: ignore[arg-type]
    v = parse_values("V", V, allow_count=True)
    if isinstance(v, int):
        lo, hi = velocity_span(law, kind, row_vals)
        v = np.linspace(lo, hi, v + 2)[1:-1]
    if np.any(v <= 0):
        raise ParameterError(
            "V", list(v), "velocities V > 0", "waves with -V are mirror images of those with V"
        )
    if len(row_vals) * v.size > MAX_POINTS:
        raise ParameterError("grid", f"{len(row_vals)} x {v.size}", f"<= {MAX_POINTS} points")
    if chunk is None:
        chunk = v.size if kind == "solitary" else 4
    if not (isinstance(chunk, (int, np.integer)) and chunk >= 1):
        raise ParameterError("chunk", chunk, "an integer >= 1")
    return Grid(kind, row_dim, row_vals, v, int(min(chunk, v.size)))
