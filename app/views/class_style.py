"""The Floquet classes' colours and legend words (fpucore.floquet.CLASSES: stable, finite-size
artefact, unstable, not determined), shared by the scenes that colour waves by their decision —
the Floquet scene's sweep and the diagram scene's branch views — so neither imports the other."""

from __future__ import annotations

from fpucore.floquet import CLASSES

from .bokeh_scene import add_legend, add_points

#: a wave's point by its decision: legend words and colour
CLASS_STYLE = {
    "stable": ("stable (drawn at its error bar)", "#2ca02c"),
    "finite_size": ("finite-size artefact", "#1f77b4"),
    "unstable": ("unstable", "#d62728"),
    "undetermined": ("not determined at this N", "#7f7f7f"),
}


def class_points(fig, name: str) -> tuple[dict, list]:
    """One point renderer per Floquet class on ``fig`` (its source named ``name-<class>``, read
    by the tests) and their legend at the right: ({class: (renderer, source)}, legend items)."""
    rs = {}
    for c in CLASSES:
        r = add_points(fig, "circle", 9, color=CLASS_STYLE[c][1], line_color="black")
        r[1].name = f"{name}-{c}"
        rs[c] = r
    return rs, add_legend(fig, "right", [(CLASS_STYLE[c][0], [rs[c][0]]) for c in CLASSES])
