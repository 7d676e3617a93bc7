"""Figures as HoloViews objects, and their export (HTML with inline resources, SVG, PNG).

The one place fpucore draws.  HoloViews / Bokeh / Matplotlib are imported lazily, inside
:func:`ui` only, so ``import fpucore`` stays headless (tests/project/test_architecture.py names
this file as the single exception).  Why here and not in ``app/``: ``fpu paper --out`` and a
Jupyter user (``fpucore.paper.plot.plot(compute("pplane"))``) need the plots without the
dashboard; the explorer can reuse the same functions.

Backends: ``"bokeh"`` (interactive; HTML) and ``"matplotlib"`` (SVG and PNG written without a
browser — Bokeh's own SVG/PNG export needs a webdriver).
"""

from __future__ import annotations

import html
import io
from pathlib import Path

import numpy as np

from fpucore.errors import ParameterError, import_extra
from fpucore.paper.figure import FigureResult, Panel, Series

BACKENDS = ("bokeh", "matplotlib")
FORMATS = {".html": "bokeh", ".svg": "matplotlib", ".png": "matplotlib"}
CONTOUR_LEVELS = 16  # level curves of a "contours" series
PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf")


def ui():
    """(holoviews, bokeh.resources.INLINE, bokeh.embed.file_html, bokeh.models) — imported now
    (MissingExtra naming the ``paper`` extra when they are not installed)."""
    for module in ("holoviews", "bokeh", "matplotlib"):
        import_extra(module, "paper", "a figure as a file")
    import holoviews as hv
    from bokeh import models
    from bokeh.embed import file_html
    from bokeh.resources import Resources

    class SelfContained(Resources):
        """Bokeh's inline resources without the files that models *declare* (``__javascript__``,
        ``__css__`` of every registered model class, used or not): importing HoloViews registers
        Panel's ESM model, whose shim is a server path ("static/extensions/panel/...") — a page
        opened from disk fails to fetch it (net::ERR_FILE_NOT_FOUND).  These plots use none."""

        def _collect_external_resources(self, resource_attr):
            return []

        def clone(self, *, components=None):
            copy = super().clone(components=components)  # Bokeh's bundle clones: keep the class
            copy.__class__ = type(self)
            return copy

    return hv, SelfContained(mode="inline"), file_html, models


def _load(hv, backend: str) -> None:
    if backend not in BACKENDS:
        raise ParameterError("backend", backend, " | ".join(BACKENDS))
    if backend not in hv.Store.loaded_backends():
        hv.extension(backend, logo=False)
    hv.Store.set_current_backend(backend)


def _element(hv, s: Series, color: str, backend: str, panel: Panel):
    label = s.label
    if backend == "matplotlib" and label in (panel.xlabel, panel.ylabel):
        # HoloViews' Matplotlib backend maps a style value that names a dimension to that
        # dimension's values: a legend label equal to an axis label ("f(w)") became an array
        label += "\u200a"  # hair space: the same text, no longer the dimension's name
    kw = {"label": label} if label else {}
    dims = {"kdims": [panel.xlabel], "vdims": [panel.ylabel]}
    if s.style in ("line", "dashed"):
        el = hv.Curve((s.x, s.y), **dims, **kw).opts(color=color)
        if s.style == "dashed":
            el = el.opts(**({"line_dash": "dashed"} if backend == "bokeh" else {"linestyle": "--"}))
        return el
    if s.style == "points":
        size = {"size": 5} if backend == "bokeh" else {"s": 25}
        return hv.Scatter((s.x, s.y), **dims, **kw).opts(color=color, **size)
    if s.style == "vline":
        return hv.VLine(float(s.x[0])).opts(
            color="gray", **({"line_dash": "dashed"} if backend == "bokeh" else {"linestyle": "--"})
        )
    if s.style == "hline":
        return hv.HLine(float(s.y[0])).opts(color="gray")
    if s.style == "contours":
        img = hv.Image((s.x, s.y, s.z), kdims=[panel.xlabel, panel.ylabel], vdims=["H"])
        lines = hv.operation.contours(img, levels=CONTOUR_LEVELS, filled=False)
        return lines.opts(color="lightgray", **({"line_width": 1} if backend == "bokeh" else {}))
    if s.style == "image":
        el = hv.Image((s.x, s.y, s.z), kdims=[panel.xlabel, panel.ylabel], vdims=["w"])
        # Matplotlib draws an image with equal data aspect by default: a 300-site × 10-time
        # map became a strip; the panels' own 5 : 3.6 shape instead
        shape = {"aspect": 1.4} if backend == "matplotlib" else {}
        return el.opts(cmap="viridis", colorbar=True, **shape)
    raise ParameterError("series.style", s.style, "one of the fpucore.paper.figure.STYLES")


def panel_plot(p: Panel, backend: str = "bokeh"):
    """One panel as an hv.Overlay (title, axis labels, legend)."""
    hv = ui()[0]
    _load(hv, backend)
    els = [_element(hv, s, PALETTE[i % len(PALETTE)], backend, p) for i, s in enumerate(p.series)]
    ov = hv.Overlay(els) if len(els) != 1 else els[0]
    size = {"width": 460, "height": 330} if backend == "bokeh" else {"fig_inches": (5, 3.6)}
    ov = ov.opts(title=p.title, **size)
    if isinstance(ov, hv.Overlay):
        ov = ov.opts(
            legend_position="right" if backend == "bokeh" else "best",
            **({"show_legend": True} if backend == "bokeh" else {}),
        )
    return ov


def plot(result: FigureResult, backend: str = "bokeh"):
    """The figure as an hv.Layout of its panels (two columns); displays in Jupyter."""
    hv = ui()[0]
    _load(hv, backend)
    layout = hv.Layout([panel_plot(p, backend) for p in result.panels])
    return layout.cols(2).opts(title=f"Fig. {result.label}")


def save(result: FigureResult, path: str | Path) -> Path:
    """Write the figure to ``path``: .html (Bokeh, resources inline: opens offline), .svg / .png
    (Matplotlib).  Returns the path."""
    path = Path(path)
    backend = FORMATS.get(path.suffix.lower())
    if backend is None:
        raise ParameterError("out", str(path), "a file ending in " + ", ".join(FORMATS))
    hv, INLINE, file_html, _ = ui()
    obj = plot(result, backend)
    if backend == "bokeh":
        # Bokeh's file_html, not hv.save: hv.save's page (Panel's template) links its favicons
        # from cdn.holoviz.org — the page would not be self-contained
        page = file_html(
            hv.render(obj, backend="bokeh"), resources=INLINE, title=f"Fig. {result.label}"
        )
        path.write_text(page, encoding="utf-8")
    else:
        hv.save(obj, str(path), backend="matplotlib", fmt=path.suffix[1:].lower())
    return path


#: width of a thumbnail (px): the explorer's Paper tab shows them at this size beside the captions
THUMB_WIDTH = 400


def thumbnail(result: FigureResult, path: str | Path, width: int = THUMB_WIDTH) -> Path:
    """Write a small PNG of the whole figure, exactly ``width`` px wide (Matplotlib, resampled
    with Lanczos by Pillow and reduced to a 256-colour palette: a few tens of kB), for the
    explorer's list of figures (docs/figures/<label>.png).  Returns the path."""
    from PIL import Image

    if not (isinstance(width, int) and 64 <= width <= 2000):
        raise ParameterError("width", width, "an integer in [64, 2000] px")
    hv = ui()[0]
    buf = io.BytesIO()
    # HoloViews' renderer draws with bbox "tight" (the title kept) and closes its figure
    hv.save(plot(result, "matplotlib"), buf, backend="matplotlib", fmt="png", dpi=100)
    buf.seek(0)
    with Image.open(buf) as im:
        im = im.convert("RGB")  # type: ignore[assignment]
        height = max(1, round(im.height * width / im.width))
        small = im.resize((width, height), Image.LANCZOS).quantize(colors=256)  # type: ignore[attr-defined]
    path = Path(path)
    small.save(path, format="PNG", optimize=True)
    return path


def _table_html(results) -> str:
    rows = []
    for r in results:
        for c in r.comparisons:
            cls = "ok" if c.agrees else "bad"
            rows.append(
                f"<tr class='{cls}'><td>{html.escape(r.label)}</td>"
                f"<td>{html.escape(c.quantity)}</td>"
                f"<td>{html.escape(c.printed)}</td><td>{c.ours:.10g}</td><td>{c.error:.2g}</td>"
                f"<td>{c.verdict}</td><td>{html.escape(c.why)}</td><td>{c.elapsed_s:.2f}</td></tr>"
            )
    head = (
        "<tr><th>figure</th><th>quantity</th><th>paper</th><th>fpu-explorer</th>"
        "<th>error</th><th>verdict</th><th>why</th><th>time (s)</th></tr>"
    )
    return (
        "<style>table.cmp{border-collapse:collapse;font:13px sans-serif}"
        "table.cmp td,table.cmp th{border:1px solid #ccc;padding:2px 6px}"
        "tr.ok td:nth-child(6){color:#060}tr.bad td:nth-child(6){color:#b00;font-weight:bold}"
        "</style><table class='cmp'>" + head + "".join(rows) + "</table>"
    )


def report_html(results, figures, path: str | Path, title: str, summary: str = "") -> Path:
    """One self-contained HTML page: the comparison table, then every figure with its number,
    caption, notes and interactive plot (Bokeh, all resources inline)."""
    hv, INLINE, file_html, models = ui()
    _load(hv, "bokeh")
    items = [
        models.Div(
            text=f"<h1>{html.escape(title)}</h1><p>{html.escape(summary)}</p>"
            + _table_html(results),
            width=1100,
        )
    ]
    for r in results:
        fig = figures[r.label]
        text = (
            f"<h2>Fig. {fig.number} ({html.escape(r.label)}, {fig.section})</h2>"
            f"<p>{html.escape(fig.caption)}</p><p><i>parameters:</i> "
            f"{html.escape(str(r.params))}; computed in {r.elapsed_s:.2f} s"
            f"{' (reduced)' if r.reduced else ''}. {html.escape(r.notes)}</p>"
        )
        items.append(models.Div(text=text, width=1000))
        if r.panels:
            items.append(hv.render(plot(r, "bokeh"), backend="bokeh"))
    doc = models.Column(children=items)
    page = file_html(doc, resources=INLINE, title=title)
    Path(path).write_text(page, encoding="utf-8")
    return Path(path)


def finite(x) -> np.ndarray:
    """x with non-finite entries dropped (plots of sweeps with unconverged rows)."""
    x = np.asarray(x, float)
    return x[np.isfinite(x)]
