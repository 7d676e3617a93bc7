"""Sphinx extension: the gallery of the paper's 17 figures, executed when the docs are built.

At ``builder-inited`` every figure of :data:`fpucore.paper.FIGURES` is computed through
:func:`fpucore.paper.report.compute_many` — the same cached route as ``fpu paper`` (one pickle
per figure in ``$FPU_CACHE_DIR/paper``, keyed by the sha256 of fpucore's source) — and drawn to
a PNG (Matplotlib, cached beside it under ``docs/<version>``).  One MyST page per figure is
written into ``docs/gallery/`` (generated, not committed): caption, the figure, the code that
makes it (the call, and the figure function's source by ``literalinclude``) and its comparison
rows.  A page or PNG is rewritten only when its bytes change, so Sphinx's incremental build
re-reads nothing on a rebuild with the same fpucore.

A figure whose computation raises fails the build (ExtensionError naming it), as does a page
that would load anything from another host (``build-finished`` scans every HTML file).
"""

from __future__ import annotations

import re
import shutil
import time
from pathlib import Path

from sphinx.application import Sphinx
from sphinx.errors import ExtensionError
from sphinx.util import logging

logger = logging.getLogger(__name__)

GALLERY = "gallery"
#: an attribute or tag that makes the browser fetch: src=, href= of <link>, url(...) in CSS
REMOTE = re.compile(
    r"""(?:<(?:script|img|iframe|source|embed|video|audio)\b[^>]*\bsrc|<link\b[^>]*\bhref)"""
    r"""\s*=\s*["']?\s*(?:https?:)?//|url\(\s*["']?\s*(?:https?:)?//""",
    re.I,
)
_ESCAPE = re.compile(r"([\\`*_{}\[\]<>()#+!|$~])")


def md_text(s: object) -> str:
    """Plain text for a MyST table cell: Markdown punctuation escaped, no line breaks."""
    return _ESCAPE.sub(r"\\\1", str(s)).replace("\n", " ")


def write_if_changed(path: Path, data: bytes) -> bool:
    """Write ``data`` to ``path`` unless it holds exactly that already (keeps mtimes: Sphinx
    re-reads only changed sources)."""
    if path.exists() and path.read_bytes() == data:
        return False
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return True


def render_png(result, path: Path) -> None:
    """The whole figure as a PNG (Matplotlib through fpucore.paper.plot, 100 dpi)."""
    from fpucore.paper import plot

    hv = plot.ui()[0]
    tmp = path.with_suffix(".tmp.png")
    hv.save(plot.plot(result, "matplotlib"), str(tmp), backend="matplotlib", fmt="png", dpi=80)
    tmp.replace(path)


def figure_page(fig, result, version: str) -> str:
    """The MyST source of one gallery page."""
    fn = fig.run
    module = fn.__module__
    src = "../../" + module.replace(".", "/") + ".py"
    size = "reduced grids (FPU_DOCS_REDUCED=1)" if result.reduced else "full size"
    rows = [
        "| quantity | paper | fpu-explorer | error bar | verdict | why | time (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for c in result.comparisons:
        verdict = "agrees" if c.agrees else "**disagrees**"
        rows.append(
            f"| {md_text(c.quantity)} | {md_text(c.printed)} | {c.ours:.10g} | {c.error:.2g} "
            f"| {verdict} | {md_text(c.why)} | {c.elapsed_s:.2f} |"
        )
    params = ", ".join(f"{k} = {v}" for k, v in result.params.items())
    notes = f"\n\n{md_text(result.notes)}" if result.notes else ""
    n, ok = len(result.comparisons), result.n_agree
    return f"""(gallery-{fig.label})=
# Fig. {fig.number}: `{fig.label}` ({md_text(fig.section)})

{md_text(fig.caption)}

![Fig. {fig.label}]({fig.label}.png)

Computed when these pages were built, {size}, in {result.elapsed_s:.2f} s (fpucore source
`{version}`); parameters: {md_text(params) or "none"}.{notes}

## The code that makes it

```python
from fpucore import paper
from fpucore.paper import plot

r = paper.compute("{fig.label}")        # FigureResult: panels, comparisons, elapsed_s
plot.save(r, "{fig.label}.png")         # this picture (Matplotlib; .html for Bokeh)
```

`paper.compute` runs `{module}.{fn.__name__}`:

```{{literalinclude}} {src}
:language: python
:pyobject: {fn.__name__}
```

## Comparison with the paper

{ok} of {n} printed numbers agree (a value agrees when |ours − paper| ≤ error + half a unit of
the paper's last printed digit; a bound holds when ours ± error is on its side).

{chr(10).join(rows)}
"""


def index_page(figures, results) -> str:
    lines = [
        "(gallery)=",
        "# Gallery: the paper, figure by figure",
        "",
        "Each of the 17 figures of Vainchtein & Truskinovsky, computed by fpucore when this site "
        "was built, with its caption, the code that makes it and the numbers the paper prints "
        "beside ours (the same as `fpu paper`, see {doc}`../guide/paper`).",
        "",
        "```{toctree}",
        ":hidden:",
        "",
        *[r.label for r in results],
        "```",
        "",
        "| Fig. | label | section | printed numbers that agree |",
        "|---|---|---|---|",
    ]
    for r in results:
        f = figures[r.label]
        lines.append(
            f"| {f.number} | {{doc}}`{r.label} <{r.label}>` | {md_text(f.section)} "
            f"| {r.n_agree} of {len(r.comparisons)} |"
        )
    return "\n".join(lines) + "\n"


def build_gallery(app: Sphinx) -> None:
    from fpucore.paper.registry import FIGURES, LABELS
    from fpucore.paper.report import cache_dir, code_version, compute_many

    t0 = time.perf_counter()
    reduced = bool(app.config.paper_gallery_reduced)
    version = code_version()
    results, missing, wall = compute_many(
        list(LABELS), reduced=reduced, use_cache=True, workers=app.config.paper_gallery_workers
    )
    if missing:
        raise ExtensionError("paper gallery: figures failed: " + "; ".join(missing))
    out = Path(app.srcdir) / GALLERY
    png_cache = cache_dir().parent / "docs" / f"{version}{'-reduced' if reduced else ''}"
    png_cache.mkdir(parents=True, exist_ok=True)
    keep = {"index.md"}
    for r in results:
        png = png_cache / f"{r.label}.png"
        if not png.exists():
            render_png(r, png)
        write_if_changed(out / png.name, png.read_bytes())
        page = figure_page(FIGURES[r.label], r, version)
        write_if_changed(out / f"{r.label}.md", page.encode())
        keep |= {png.name, f"{r.label}.md"}
    write_if_changed(out / "index.md", index_page(FIGURES, results).encode())
    for stale in out.iterdir():  # a figure renamed or removed: its old page goes
        if stale.name not in keep:
            shutil.rmtree(stale) if stale.is_dir() else stale.unlink()
    logger.info(
        f"paper gallery: {len(results)} figures ({wall:.1f} s computing or reading the cache, "
        f"{time.perf_counter() - t0:.1f} s in all)"
    )


#: a script that loads or configures MathJax (the word in prose, e.g. the untrusted-input guide's
#: account of the explorer's math fix, is not one)
MATHJAX_SCRIPT = re.compile(r"<script[^>]*mathjax|<script[^>]*>[^<]*mathjax", re.IGNORECASE)


def check_no_remote(app: Sphinx, exc: Exception | None) -> None:
    """Fail the build if any page would fetch from another host (script/img/link or CSS url)
    or load MathJax."""
    if exc is not None or app.builder.format != "html":
        return
    bad = []
    outdir = Path(app.outdir)
    for p in sorted(outdir.rglob("*")):
        if p.suffix not in (".html", ".css", ".js") or not p.is_file():
            continue
        text = p.read_text(encoding="utf-8", errors="replace")
        m = REMOTE.search(text)
        if m or (p.suffix == ".html" and MATHJAX_SCRIPT.search(text)):
            bad.append(f"{p.relative_to(outdir)}: {m.group(0) if m else 'MathJax'}")
    if bad:
        raise ExtensionError("pages that load from another host: " + "; ".join(bad[:10]))


def setup(app: Sphinx) -> dict:
    app.add_config_value("paper_gallery_reduced", False, "env")
    app.add_config_value("paper_gallery_workers", None, "env")
    app.connect("builder-inited", build_gallery)
    app.connect("build-finished", check_no_remote)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
