"""Untrusted text in the dashboard: shown literally (md_literal) and a typed law built within
its budgets in a worker process, never waited for during a page build."""

from __future__ import annotations

import html
import re
import time

import pytest

pn = pytest.importorskip("panel")

import nbformat  # noqa: E402
from bokeh.models import Axis, Label, LegendItem, Markup, Title  # noqa: E402
from slow_law import slow_law_job  # noqa: E402 - tests/support: a stand-in law job

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.state import MAX_URL_VALUE, URL_PARAMS, ExplorerState  # noqa: E402
from app.url_state import parse_url, resolve_atlas_store, state_from_url  # noqa: E402
from app.views.atlas import AtlasScene  # noqa: E402
from app.views.untrusted import (  # noqa: E402
    LITERAL_MD,
    LiteralAlert,
    LiteralMarkdown,
    md_literal,
    md_plain,
)
from fpucore import atlas  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402

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


#: TeX that MathJax (Bokeh's Markup models) or KaTeX would typeset: links (\href, \url),
#: HTML attributes (\htmlClass, \class, \style), raw code points (\unicode), in every
#: delimiter pair (MathJax: $$…$$, \(…\), \[…\]; KaTeX/TeX: $…$, environments).  Each
#: ≤ 40 characters, so a URL message repeats it whole (tests/browser/test_untrusted_text.py).
MATH_PAYLOADS = [
    r"$$\href{javascript:alert(1)}{pwn}$$",
    r"\(\href{javascript:alert(1)}{pwn}\)",
    r"\[\url{javascript:alert(1)}\]",
    r"$\href{javascript:alert(1)}{p}$",
    r"$$\htmlClass{x}{\href{javascript:1}{}}$$",
    r"\(\class{x}{y}\unicode{x3C}\)",
    r"\[\style{color:red}{\url{javascript:}}\]",
    r"\begin{x}\href{javascript:1}{e}\end{x}",
    r"\\(\href{javascript:alert(1)}{b}\\)",
]
#: the issue's link: a store named with TeX (the message repeats the store's name)
ISSUE_ATLAS = r"\(\href{javascript:alert(document.domain)}{\text{Open the atlas store}}\)"
TEX_DELIMITERS = ("$", "\\(", "\\[", "\\begin")


@pytest.mark.parametrize("text", PAYLOADS + MATH_PAYLOADS)
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
        compute.laws.expression_law("w + 11*w**2 - w**3")
    assert time.monotonic() - t0 < 30  # stopped at its budget, not after the job's 60 s
    monkeypatch.undo()
    assert compute.laws.expression_law("w + 9*w**2 - w**3").coeffs == (1.0, 9.0, -1.0)


def test_a_page_build_never_waits_for_a_law(monkeypatch):
    """On the event loop (a page build) a law whose build has not finished is not waited for:
    "being checked" at once; elsewhere the same call waits for the worker's answer."""
    monkeypatch.setattr(compute.laws, "build_law_job", slow_law_job)
    monkeypatch.setattr(compute.laws, "LAW_TIME_S", 1.0)
    text = "w + 12*w**2 - w**3"
    t0 = time.monotonic()
    with compute.laws.building_page(), pytest.raises(compute.ParameterError, match="being checked"):
        compute.laws.expression_law(text)
    assert time.monotonic() - t0 < 0.5
    outcome = compute.laws.request_law(text).result(timeout=60)  # the watcher's answer, later
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


# ----------------------------------------------------------------------------- math
def test_the_math_payloads_fit_a_url_message_whole():
    assert all(len(p) <= MAX_URL_VALUE for p in MATH_PAYLOADS)


def _page_models(ex):
    """Every Bokeh model of the explorer's page (sidebar and all tabs)."""
    return list(pn.Row(*ex.sidebar(), ex.tabs).get_root().references())


@pytest.mark.parametrize("payload", MATH_PAYLOADS + [ISSUE_ATLAS])
def test_no_user_text_reaches_the_browser_as_math(payload, tmp_path, monkeypatch):
    """The payload in every URL parameter, then typed as the law and as the atlas store: every
    Markup model of the page (what BokehJS renders as HTML, typesetting TeX unless
    ``disable_math``) that holds TeX delimiters has math off, and no plot title, axis label,
    legend entry or label (Bokeh renders TeX in those too) repeats it.  Panel 1.9's Markdown
    and Alert panes never sent ``disable_math``: the URL message and the scene's message
    (the store's name) were typeset, and MathJax's \\href made a javascript: link."""
    monkeypatch.setenv("FPU_ATLAS_ROOT", str(tmp_path))
    state, errors = state_from_url({name: payload for name in URL_PARAMS})
    assert len(errors) >= len(URL_PARAMS) - 2, errors  # the store's name is a valid path
    ex = Explorer(state, url_errors=errors)
    force, atlas_scene = ex.by_key["force"], ex.by_key["atlas"]
    ex.state.param.update(expression=payload, atlas=payload)  # the law box, the store box
    force.refresh()
    atlas_scene.refresh()
    assert f"law={payload}" in md_plain(force.status.object)  # the parameters line, as typed
    assert "no atlas store" in atlas_scene.last_message, atlas_scene.last_message
    shown = []
    for m in _page_models(ex):
        if isinstance(m, Markup):
            text = html.unescape(m.text or "")
            if any(d in text for d in TEX_DELIMITERS):
                shown.append(text)
                assert m.disable_math, (type(m).__name__, text[:300])
        for attr in ("text", "axis_label"):
            if isinstance(m, (Title, Axis, Label)) and isinstance(getattr(m, attr, None), str):
                assert not any(d in getattr(m, attr) for d in TEX_DELIMITERS), getattr(m, attr)
        if isinstance(m, LegendItem):
            assert not any(d in str(m.label) for d in TEX_DELIMITERS), m.label
    assert shown  # the payload is on the page (as text)


def test_literal_panes_send_math_off_to_the_browser():
    for pane in (LiteralMarkdown("$$x$$"), LiteralAlert("\\(x\\)", alert_type="warning")):
        model = pane.get_root()
        assert model.disable_math is True
    assert pn.pane.Markdown("$$x$$", disable_math=True).get_root().disable_math is False  # Panel


# ----------------------------------------------------------------------------- exports
@pytest.fixture(scope="module")
def payload_store(tmp_path_factory):
    """A small solitary atlas store whose name is TeX with a javascript: link."""
    root = tmp_path_factory.mktemp("srv")
    name = "$$\\href{javascript:alert(1)}{pwn}$$.zarr"
    atlas.run(CubicLaw(-1.0, 10.0), "solitary", rows=[1.0, 6.0], V=[4.6, 5.0], N=64,
              floquet=False, finite_size=False, out=root / name, backend="inline")  # fmt: skip
    return root, name


def _outside_code(markdown: str) -> str:
    """The HTML CommonMark renders for ``markdown`` minus its code spans and blocks (which
    Jupyter's and MathJax's math finders skip)."""
    from markdown_it import MarkdownIt

    out = MarkdownIt("commonmark").render(markdown)
    return re.sub(r"<pre>.*?</pre>|<code>.*?</code>", "", out, flags=re.S)


def test_exports_repeat_a_store_name_literally(payload_store, monkeypatch):
    """The scene on screen shows a store named with TeX; its notebook's Markdown has that
    name only inside code (Jupyter would typeset it: a javascript: link in the notebook),
    the link's query percent-encoded, and the figure files carry no link or script."""
    root, name = payload_store
    monkeypatch.setenv("FPU_ATLAS_ROOT", str(root))
    sc = AtlasScene(ExplorerState(atlas=name))
    sc.quantity.value = "amplitude"
    assert sc.refresh() is not None, sc.last_message
    nb = nbformat.reads(sc.export_notebook(), as_version=4)
    md = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    assert name in md  # shown as typed ...
    rest = html.unescape(_outside_code(md))
    assert not any(d in rest for d in TEX_DELIMITERS) and "href" not in rest, rest  # ... as code
    for fmt in ("svg", "png"):
        data = sc.export_figure(fmt)
        drawn = re.sub(rb"<!--.*?-->", b"", data, flags=re.S)  # SVG: texts as comments, inert
        assert b"javascript:" not in drawn and b"<script" not in data and b"<a " not in data


def test_a_figure_title_with_tex_is_drawn_as_typed():
    """Matplotlib parses $…$ as mathtext: a stamp repeating a typed law with "$" drew math or
    failed the export ("Unknown symbol: \\href"); it is drawn as typed."""
    from app.views import export
    from app.views.force_law import ForceLawScene

    fs = ForceLawScene(ExplorerState())
    assert fs.refresh() is not None
    for payload in MATH_PAYLOADS:
        svg = export.figure_bytes(fs.figure_models(), "svg", f"law={payload}")
        assert svg.startswith(b"<?xml") and b"<a " not in svg and b"<script" not in svg
        drawn = re.sub(rb"<!--.*?-->", b"", svg, flags=re.S)  # the texts as comments: inert
        assert b"javascript:" not in drawn
