"""Each scene's caption cites the paper's figures by their labels (and, where it gives numbers,
the numbers of those labels): the Atlas caption once cited "Figs. 8, 9, 14" (a profile figure
and the Riemann run) for its amplitude, energy and stability maps."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("panel")

from app.views import SCENES  # noqa: E402

#: the paper's figure labels in the order of its figures (\label{fig:…} in the LaTeX source)
PAPER_FIGURES = (
    "superkink pplane cubic SWvelocities_cubic SWs_cubic SWamp_energy_QCcubic TWcubic "
    "SWs_cubic_DvsQC SWamp_cubic_DvsQC SWenergy_cubic_DvsQC floquet_SK Floquet_example stabSK "
    "Riemann1 floquet_cubicSW stabSW SWdyn"
).split()
#: "Fig. 1 (superkink)", "Figs. 5, 7 and 8 (SWs_cubic, TWcubic, …)" or "Figs. A, B and C"
CITATION = re.compile(r"Figs?\.\s+([^()]*?)\s*(?:\(([^)]*)\))?\.?_?$", re.S)
WORD = re.compile(r"[A-Za-z][A-Za-z0-9_]*")


def citations(caption: str) -> list[tuple[list[int], list[str]]]:
    """(figure numbers, labels) of each "Fig./Figs." citation, read to the caption's end or its
    parenthesis; labels given without numbers come back with an empty number list."""
    out = []
    for part in caption.split("Fig")[1:]:
        m = CITATION.match("Fig" + part.strip())
        assert m, part
        head, paren = m.group(1), m.group(2) or ""
        nums = [int(n) for n in re.findall(r"\d+", head)]
        words = [w for w in WORD.findall(head) if w != "and"]
        labels = words if words else [w for w in WORD.findall(paren) if w != "and"]
        out.append((nums, labels))
    return out


@pytest.mark.parametrize("cls", [c for c in SCENES if "Fig" in c.caption], ids=lambda c: c.key)
def test_captions_cite_the_papers_figures_by_label(cls):
    cited = citations(cls.caption)
    assert cited, cls.caption
    for nums, labels in cited:
        assert labels and set(labels) <= set(PAPER_FIGURES), (cls.key, labels)
        if nums:  # numbers given: they are those labels' figure numbers, in order
            assert nums == [PAPER_FIGURES.index(lab) + 1 for lab in labels], (cls.key, nums)


def test_the_atlas_cites_its_maps_figures():
    (nums, labels), *_ = citations(next(c for c in SCENES if c.key == "atlas").caption)
    assert set(labels) == {"SWamp_cubic_DvsQC", "SWenergy_cubic_DvsQC", "floquet_cubicSW"}
