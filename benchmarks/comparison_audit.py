"""Audit of the paper comparisons against the numbers printed beside them (the rule of
:mod:`fpucore.paper`): "agrees" must mean |ours − paper| ≤ error + half a unit of the paper's last
printed digit for a value, or ours ± error on the stated side for a bound.  Like
:mod:`benchmarks.verdict_audit`, the rules read the printed text and never trust the record that
wrote it (tests: tests/paper/test_comparison_audit.py)."""

from __future__ import annotations

import re

from benchmarks.verdict_audit import NEGATIVE_ABS, NUM


def audit_comparison(verdict: str, why: str, ours: float | None = None,
                     error: float | None = None, paper: float | None = None,
                     rounding: float | None = None) -> list[str]:  # fmt: skip
    """Problems of one paper comparison (fpucore.paper.Comparison or a row of
    docs/paper_comparison.md): "agrees" must mean |ours − paper| ≤ error + half a unit of the
    paper's last printed digit (a value) or ours ± error on the stated side (a bound), checked
    on the numbers printed in ``why`` and, when given, on the raw numbers."""
    bad = []
    agrees = verdict.strip("* ").startswith("agrees")
    m = re.search(r"= (" + NUM + r") (≤|>) error (" + NUM + r") \+ printed rounding (" + NUM
                  + r")", why)  # fmt: skip
    b = re.search(r"ours ([+−-]) error = (" + NUM + r") (<|≥|>|≤) (" + NUM + r")", why)
    if m:
        d, rel, e, r = float(m[1]), m[2], float(m[3]), float(m[4])
        holds = d <= (e + r) * 1.05 + 1e-300  # printed to 2-3 digits
        if agrees and (rel != "≤" or not holds):
            bad.append(f"'agrees' but {m[0]}")
        if not agrees and rel == "≤":
            bad.append(f"'disagrees' but {m[0]}")
    elif b:
        x, rel, p = float(b[2]), b[3], float(b[4])
        ok = (x < p) if rel in ("<", "≥") else (x > p)
        if agrees != ok:
            bad.append(f"{verdict!r} but {b[0]}")
    else:
        bad.append(f"comparison without its numbers: {why!r}")
    if None not in (ours, error, paper, rounding) and m:
        true = abs(ours - paper) <= abs(error) + rounding
        if true != agrees:
            bad.append(f"{verdict!r} but |{ours!r} − {paper!r}| vs {error!r} + {rounding!r}")
    if NEGATIVE_ABS.search(why):
        bad.append(f"a negative absolute value: {why!r}")
    return bad


def audit_comparison_table(text: str) -> list[str]:
    """Problems of the generated table docs/paper_comparison.md, row by row."""
    bad = []
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
        if len(cells) == 8 and cells[5].strip("* ") in ("agrees", "disagrees"):
            bad += [f"{cells[0]} {cells[1]}: {x}" for x in audit_comparison(cells[5],
                    cells[6].replace("\\|", "|"))]  # fmt: skip
    return bad
