"""The energy criterion on a plot against V: where E_ren(V) is stationary (dE_ren/dV = 0), a
change of stability of the solitary family may occur (Friesecke–Pego type; paper eqs. Eren_D,
Eren_QC; fpucore.floquet.energy).  Used by the Diagrams scene (panel (b), E_ren against V) and
the Floquet scene (panel (c), max |μ| against V).

:class:`ExtremumMarks` draws each extremum as a vertical line at V* over a band V* ± δV (its
error bar; a hover shows both), built once like every figure model; :func:`criterion_words`
says what was found in words a student understands.  Nothing here computes: the extrema come
from :mod:`app.compute` (``EnergyRequest``, ``SampledEnergyRequest``).
"""

from __future__ import annotations

import numpy as np
from bokeh.models import ColumnDataSource, HoverTool

from .bokeh_scene import Updates

#: x = V*, y = mid-height (the tests read x, y like every named source), band [left, right],
#: vertical extent [lo, hi], label = the hover text
EMPTY = {"x": [], "y": [], "left": [], "right": [], "lo": [], "hi": [], "label": []}


def fmt_extremum(kind: str, v: float, dv: float) -> str:
    """'minimum at V = 5.03 ± 2e-06' (the value to the digits its error bar allows, ≥ 4)."""
    digits = 4 if not np.isfinite(dv) or dv <= 0 else max(4, int(np.ceil(-np.log10(dv))) + 2)
    word = "minimum" if kind == "min" else "maximum"
    return f"{word} at V = {v:.{min(digits, 12)}g} ± {dv:.1g}"


class ExtremumMarks:
    """Vertical marks at the extrema of E_ren on a figure with V on its x-axis.

    ``renderers`` (line, band) go into a legend entry; :meth:`update` fills them."""

    def __init__(self, fig, color: str, dash: str = "solid", name: str = "energy-extremum"):
        self.src = ColumnDataSource(dict(EMPTY))
        self.src.name = name  # read by the tests
        self.band = fig.quad(
            left="left",
            right="right",
            bottom="lo",
            top="hi",
            source=self.src,
            fill_color=color,
            fill_alpha=0.2,
            line_alpha=0.0,
        )
        self.line = fig.segment(
            x0="x",
            y0="lo",
            x1="x",
            y1="hi",
            source=self.src,
            line_color=color,
            line_dash=dash,
            line_width=2,
        )
        fig.add_tools(HoverTool(renderers=[self.line, self.band], tooltips=[("E_ren", "@label")]))
        self.renderers = [self.line, self.band]

    def update(self, up: Updates, V, dV, kinds, y_lo: float, y_hi: float, item=None) -> None:
        """Marks at V (k,) ± dV (k,) from y_lo to y_hi; hidden (with ``item``) when k = 0."""
        V, dV = np.asarray(V, float), np.asarray(dV, float)
        n = V.size
        labels = [fmt_extremum(k, v, d) for k, v, d in zip(kinds, V, dV)]
        up.set(
            self.src,
            data={
                "x": V,
                "y": np.full(n, 0.5 * (y_lo + y_hi)),
                "left": V - dV,
                "right": V + dV,
                "lo": np.full(n, float(y_lo)),
                "hi": np.full(n, float(y_hi)),
                "label": labels,
            },
        )
        for r in self.renderers:
            up.set(r, visible=n > 0)
        if item is not None:
            up.set(item, visible=n > 0)


def criterion_words(V, dV, kinds, what: str, where: str) -> str:
    """One sentence: where E_ren(V) of ``what`` (e.g. "the QC family") has its extrema V ± dV
    (kinds "min" | "max") — there, by the energy criterion, stability can change — or that it
    has none ``where`` (e.g. "between c₊ and c₋")."""
    if len(V) == 0:
        return (
            f"Energy criterion: E_ren(V) of {what} has no minimum or maximum {where}, so there "
            "the stability of the family cannot change through its translation mode."
        )
    found = "; ".join(fmt_extremum(k, v, d) for k, v, d in zip(kinds, V, dV))
    return (
        f"Energy criterion: E_ren(V) of {what} has a {found}: by the energy criterion, "
        "stability can change only there."
    )
