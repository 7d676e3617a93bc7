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


def test_a_law_past_its_time_budget_is_stopped_and_a_good_one_still_builds(monkeypatch):
    """fpucore's parser refuses the known DoS strings itself now; the server's budget is the net
    for any construction that is slow anyway: with a zero budget the job is stopped (its worker
    killed and replaced) and the law refused, and the next law builds on the new worker."""
    monkeypatch.setattr(compute.laws, "LAW_TIME_S", 0.0)
    with pytest.raises(compute.ParameterError, match="took longer than 0 s"):
        compute.expression_law("(w+1)**16 - (w+1)**15")
    monkeypatch.undo()
    assert compute.expression_law("w + 9*w**2 - w**3").coeffs == (1.0, 9.0, -1.0)


def test_a_page_build_never_waits_for_a_law():
    text = "w*9**9**9"
    t0 = time.monotonic()
    with compute.building_page(), pytest.raises(compute.ParameterError, match="being checked"):
        compute.expression_law(text)
    assert time.monotonic() - t0 < 0.5
    outcome = compute.request_law(text).result(timeout=60)  # the worker's answer, later
    assert isinstance(outcome, compute.ParameterError) and "9**9**9" in str(outcome)
