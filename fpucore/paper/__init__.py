"""The paper, figure by figure: every figure of Vainchtein & Truskinovsky by its LaTeX label,
computed by fpucore's routes and compared with the numbers the paper prints.

compare (Comparison: paper vs ours, error bar, verdict)  →  figure (Panel, Series,
FigureResult)  →  common (the paper's law and printed closed forms)  →  figures_qc /
figures_wave / figures_stability / figures_dynamics (one function per figure)  →  registry
(FIGURES by label)  →  report (cached, parallel computation; HTML report, Markdown table)
→  plot (HoloViews, imported lazily: the one place fpucore draws)
"""

from fpucore.paper.compare import Comparison, compare
from fpucore.paper.figure import FigureResult, Panel, Series
from fpucore.paper.registry import FIGURES, LABELS, Figure, compute, figure

__all__ = [
    "Comparison",
    "compare",
    "FigureResult",
    "Panel",
    "Series",
    "FIGURES",
    "LABELS",
    "Figure",
    "compute",
    "figure",
]
