"""The docs build's guards, without a build: a figure that raises fails it, a page that would
load from another host fails it, a cross-reference to a name fpucore does not have stays broken
(and so fails the nitpicky build) while a real unexported name resolves."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
from browser_harness import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))

import fpu_docs_refs  # noqa: E402
import paper_gallery  # noqa: E402
from sphinx.errors import ExtensionError  # noqa: E402


def test_a_figure_that_raises_fails_the_build(monkeypatch, tmp_path):
    from fpucore.paper import report

    def failing(labels, **kw):
        return [], ["pplane: ZeroDivisionError: float division by zero"], 0.0

    monkeypatch.setattr(report, "compute_many", failing)
    app = SimpleNamespace(
        config=SimpleNamespace(paper_gallery_reduced=True, paper_gallery_workers=1),
        srcdir=str(tmp_path),
    )
    with pytest.raises(ExtensionError, match="pplane: ZeroDivisionError"):
        paper_gallery.build_gallery(app)


@pytest.mark.parametrize(
    "html",
    [
        '<script src="https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-mml-chtml.js"></script>',
        "<link rel='stylesheet' href='//fonts.googleapis.com/css?family=Georgia'>",
        '<img alt="x" src="http://example.org/a.png">',
        "<style>body{background:url( 'https://example.org/b.png')}</style>",
        '<script async="async" src="_static/mathjax/tex-chtml.js"></script><p>MathJax</p>',
    ],
)
def test_a_page_that_loads_from_another_host_fails_the_build(tmp_path, html):
    (tmp_path / "page.html").write_text(f"<html><head>{html}</head></html>")
    app = SimpleNamespace(outdir=str(tmp_path), builder=SimpleNamespace(format="html"))
    with pytest.raises(ExtensionError, match="another host"):
        paper_gallery.check_no_remote(app, None)


def test_local_pages_pass_the_host_check(tmp_path):
    (tmp_path / "page.html").write_text(
        '<link rel="stylesheet" href="_static/alabaster.css"><a href="https://example.org">a'
        ' link is not a load</a><img src="_images/pplane.png">'
    )
    app = SimpleNamespace(outdir=str(tmp_path), builder=SimpleNamespace(format="html"))
    paper_gallery.check_no_remote(app, None)


class Node(dict):
    source = ""


def ref(target, module=None, cls=None, source=""):
    n = Node(refdomain="py", reftarget=target)
    n["py:module"], n["py:class"] = module, cls
    n.source = source
    return n


def test_unexported_names_resolve_and_missing_ones_stay_broken():
    contnode = object()
    # a module constant documented nowhere, named from a re-exported class's docstring
    src = "fpucore/qc/closed_forms.py:docstring of fpucore.qc.QCSuperkink.converged"
    assert fpu_docs_refs.resolve_fpucore(None, None, ref("QC_CHECK", "fpucore.qc", "QCSuperkink",
                                                         src), contnode) is contnode  # fmt: skip
    assert fpu_docs_refs.resolve_fpucore(
        None, None, ref("fpucore.floquet.reversible"), contnode) is contnode  # fmt: skip
    # names that do not exist: left to Sphinx, which warns (an error under -W)
    for target in ("QC_CHEK", "fpucore.floquet.no_such_module", "fpucore.wave.solve_superkinq"):
        n = ref(target, "fpucore.qc")
        assert fpu_docs_refs.resolve_fpucore(None, None, n, contnode) is None


def test_absolute_value_bars_are_escaped_outside_literals():
    lines = ["max |μ| − 1 over ``a|b`` and :data:`X|Y`, |a|"]
    fpu_docs_refs.escape_bars(None, "function", "f", None, None, lines)
    assert lines == ["max \\|μ\\| − 1 over ``a|b`` and :data:`X|Y`, \\|a\\|"]


def test_markdown_cells_escape_punctuation():
    assert paper_gallery.md_text("w* | b_1 [x]") == "w\\* \\| b\\_1 \\[x\\]"
    assert Path(paper_gallery.__file__).parent == ROOT / "docs" / "_ext"


def test_a_law_page_whose_route_raises_fails_the_build(monkeypatch, tmp_path):
    import law_gallery

    def failing(name):
        raise FloatingPointError("overflow in the Riemann run")

    monkeypatch.setattr(law_gallery, "compute", failing)
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))
    app = SimpleNamespace(srcdir=str(tmp_path))
    with pytest.raises(ExtensionError, match="law pages: exponential: FloatingPointError"):
        law_gallery.build_law_pages(app)
