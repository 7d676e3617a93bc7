"""Untrusted text in the dashboard: shown literally (md_literal) and a typed law built within
its budgets in a worker process, never waited for during a page build."""

from __future__ import annotations

import html
import re
import time

import pytest

pn = pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.views.base import md_literal  # noqa: E402

PAYLOADS = [
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(7)>",
    '"><svg onload=alert(1)>',
    "[x](javascript:alert(1))",
    "![i](x) ~~s~~ `c` $x$ $$y$$",
    "__import__('os')",
    "w + 10*w**2 - w**3",
    "# h\n- item\n1. one\n2) two\n===\n> q\n    code",
    "a | b\n--|--\n1 | 2",
    "&amp; &lt; \\*",
]


@pytest.mark.parametrize("text", PAYLOADS)
def test_markdown_pane_shows_the_text_as_typed(text):
    """Rendered by Panel's own Markdown renderer: one paragraph, no other tag, whose text is the
    input (line breaks aside) — no link, no image, no emphasis, no raw HTML."""
    out = html.unescape(pn.pane.Markdown()._transform_object(md_literal(text))["object"])
    tags = set(re.findall(r"</?([a-zA-Z0-9]+)", out))
    assert tags <= {"p"}, (text, out)
    inner = re.sub(r"</?p>", "", out).strip()
    assert html.unescape(inner).split() == text.split(), (text, out)


def test_a_pathological_law_is_refused_within_its_budget_and_a_good_one_still_builds():
    t0 = time.monotonic()
    with pytest.raises(compute.ParameterError, match="took longer than"):
        compute.expression_law("(w+1)**100000")
    # the budget (3 s) counts from the job's start; the worker's start comes first
    assert time.monotonic() - t0 < compute.LAW_TIME_S + 30
    assert compute.expression_law("w + 9*w**2 - w**3").coeffs == (1.0, 9.0, -1.0)


def test_a_page_build_never_waits_for_a_law():
    text = "w*9**9**9"
    t0 = time.monotonic()
    with compute.building_page(), pytest.raises(compute.ParameterError, match="being checked"):
        compute.expression_law(text)
    assert time.monotonic() - t0 < 0.5
    outcome = compute.request_law(text).result(timeout=60)  # the worker's answer, later
    assert isinstance(outcome, compute.ParameterError) and "took longer" in str(outcome)
