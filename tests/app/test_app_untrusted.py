"""Untrusted text in the dashboard: shown literally (md_literal) and a typed law built within
its budgets in a worker process, never waited for during a page build."""

from __future__ import annotations

import html
import re
import time

import pytest

pn = pytest.importorskip("panel")

from slow_law import slow_law_job  # noqa: E402 - tests/support: a stand-in law job

from app import compute  # noqa: E402
from app.url_state import parse_url, resolve_atlas_store  # noqa: E402
from app.views.untrusted import LITERAL_MD, md_literal  # noqa: E402

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
    "<svg onload=alert(1)>",
    "<iframe srcdoc='<script>alert(1)</script>'>",
    "<javascript:alert(1)>",
    "&lt;img src=x onerror=alert(1)&gt;",
    "&#60;script&#62;alert(1)&#60;/script&#62;",
    "</textarea><script>alert(1)</script>",
    '" onmouseover="alert(1)',
    "`${alert(1)}` {{7*7}}",
    "\u200b<scr\u200bipt>alert(1)</script> \u202e<b>x</b>",
    "%3Cscript%3E %253Cscript%253E",
    "<math><mtext><table><mglyph><style><img src=x onerror=alert(1)>",
    # no link either (Panel's Markdown linkifies these by default)
    "http://evil.example/x //evil.example evil.com a@b.co store.py",
    "<img src=x onerror=alert(1)>" * 180,
]


@pytest.mark.parametrize("text", PAYLOADS)
def test_markdown_pane_shows_the_text_as_typed(text):
    """Rendered by Panel's own Markdown renderer: one paragraph, no other tag, whose text is the
    input (line breaks aside) — no link, no image, no emphasis, no raw HTML."""
    out = html.unescape(
        pn.pane.Markdown(**LITERAL_MD)._transform_object(md_literal(text))["object"]
    )
    tags = set(re.findall(r"</?([a-zA-Z0-9]+)", out))
    assert tags <= {"p"}, (text, out)
    inner = re.sub(r"</?p>", "", out).strip()
    assert html.unescape(inner).split() == text.split(), (text, out)


def test_a_law_past_its_time_budget_is_stopped_and_a_good_one_still_builds(monkeypatch):
    """fpucore's parser answers every text in milliseconds now; the server's budget is the net
    for a construction that is slow anyway: a job past LAW_TIME_S is stopped (its worker killed
    and replaced) and the law refused, and the next law builds on the new worker.  The slow job
    is a stand-in (tests/support/slow_law.py): no real text is slow enough to trip it."""
    monkeypatch.setattr(compute.laws, "build_law_job", slow_law_job)
    monkeypatch.setattr(compute.laws, "LAW_TIME_S", 0.5)
    t0 = time.monotonic()
    with pytest.raises(compute.ParameterError, match="took longer than 0.5 s"):
        compute.expression_law("w + 11*w**2 - w**3")
    assert time.monotonic() - t0 < 30  # stopped at its budget, not after the job's 60 s
    monkeypatch.undo()
    assert compute.expression_law("w + 9*w**2 - w**3").coeffs == (1.0, 9.0, -1.0)


def test_a_page_build_never_waits_for_a_law(monkeypatch):
    """On the event loop (a page build) a law whose build has not finished is not waited for:
    "being checked" at once; elsewhere the same call waits for the worker's answer."""
    monkeypatch.setattr(compute.laws, "build_law_job", slow_law_job)
    monkeypatch.setattr(compute.laws, "LAW_TIME_S", 1.0)
    text = "w + 12*w**2 - w**3"
    t0 = time.monotonic()
    with compute.building_page(), pytest.raises(compute.ParameterError, match="being checked"):
        compute.expression_law(text)
    assert time.monotonic() - t0 < 0.5
    outcome = compute.request_law(text).result(timeout=60)  # the watcher's answer, later
    assert isinstance(outcome, compute.ParameterError) and "took longer than 1 s" in str(outcome)


@pytest.mark.parametrize("raw", ["x\x00y", "~nosuchuser/x", "x" * 201, "a/" * 2500])
def test_an_unreadable_store_path_is_refused_by_name(raw):
    """A NUL byte, an unknown user's home, a path past the limits: a ParameterError naming the
    store (a URL message), never a ValueError / RuntimeError / OSError out of the page build."""
    values, errors = parse_url({"atlas": raw, "V": "5.1"})
    assert values == {"V": 5.1} and len(errors) == 1 and "atlas=" in errors[0], errors
    with pytest.raises(compute.ParameterError, match="atlas store="):
        resolve_atlas_store("atlas store", raw)


def test_a_message_in_the_python_code_is_all_comment():
    """A scene's message repeats user text, which may hold line breaks (a store path from a
    link): in "Copy as Python" every line of it stays a comment, never a statement."""
    from app.state import ExplorerState
    from app.views.force_law import ForceLawScene

    sc = ForceLawScene(ExplorerState())
    sc._show_message("no atlas store at /x\nimport os; os.system('id')\r\nprint(1)", "warning")
    said = sc.code.value.split("law = ")[1].splitlines()[1:]
    assert said and all(line.startswith("# ") for line in said), said
