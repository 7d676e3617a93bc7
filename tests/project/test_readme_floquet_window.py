"""The README's snippet names the rings of the finite-size window its verdict reads (N = 500:
fpucore.floquet.finite_size.chain_lengths, from N/2 to N)."""

from __future__ import annotations

import re
from pathlib import Path

from fpucore.floquet.finite_size import chain_lengths

README = Path(__file__).resolve().parents[2] / "README.md"


def test_the_snippets_window_is_the_one_computed():
    text = README.read_text(encoding="utf-8")
    pattern = r"print\(fr\.verdict\)  # the evidence: max\|mu\|-1 on the rings N = (\d+) … (\d+)"
    m = re.search(pattern, text)
    assert m, "the README's fr.verdict comment does not name the window"
    assert (int(m.group(1)), int(m.group(2))) == (chain_lengths(500)[0], 500)
