"""A scene as the user sees it, taken out of the browser: its figure (SVG, PNG) and a notebook.

**Figure.**  Bokeh's own SVG/PNG export needs a browser (a webdriver); here the scene's Bokeh
figures — exactly the models on screen, with the data of the last render, nothing recomputed —
are drawn again with Matplotlib, server side: every visible line, scatter, band, image, quad,
segment, span, label and whisker with its colour, dash, marker, title, axis labels, ranges, log
axis and legend, the figures laid out in the scene's rows.  A renderer whose source carries a
name (the names the browser tests read) becomes an SVG group with that id.

**Notebook.**  nbformat: a Markdown cell with the state (URL query, parameters, what the status
shows), then the scene's "Copy as Python" code cut into one cell per computation (joined, the
cells are that code exactly), then a Matplotlib cell drawing what was computed.

Matplotlib (~0.4 s) and nbformat (~0.1 s) are imported when a file is built, not by the server
at start (tests/project/test_architecture.py allow-lists exactly these imports).
"""

from __future__ import annotations

import io
import re

import numpy as np
from bokeh.models import (
    Column,
    GridBox,
    Image,
    Label,
    Line,
    LogScale,
    Quad,
    Row,
    Scatter,
    Segment,
    Span,
    VArea,
    Whisker,
)
from bokeh.plotting import figure as BokehFigure

import fpucore

FORMATS = ("svg", "png")
#: Bokeh marker → Matplotlib marker
MARKERS = {
    "circle": "o",
    "x": "x",
    "diamond": "D",
    "square": "s",
    "triangle": "^",
    "cross": "+",
    "inverted_triangle": "v",
    "asterisk": "*",
    "dot": ".",
}
WIDTH_IN = 10.0  # the exported figure's width (inches); each row's height follows its figures
DPI = 110


# ---------------------------------------------------------------------------- the scene's layout
def figure_rows(models) -> list[list]:
    """The visible Bokeh figures under ``models`` (figures, rows, columns), as rows."""
    rows: list[list] = []
    for m in models:
        rows += _rows(m)
    return [r for r in rows if r]


def _rows(m) -> list[list]:
    if m is None or not getattr(m, "visible", True):
        return []
    if isinstance(m, BokehFigure):
        return [[m]]
    if isinstance(m, Column):
        out = []
        for c in m.children:
            out += _rows(c)
        return out
    if isinstance(m, Row):
        return [[f for c in m.children for r in _rows(c) for f in r]]
    if isinstance(m, GridBox):
        return [[f for c in m.children for r in _rows(c[0]) for f in r]]
    return []


# ---------------------------------------------------------------------------- Bokeh → Matplotlib
def _col(src, data: dict, spec, n: int | None = None):
    """A glyph property: the source's column it names, or its fixed value (repeated n times)."""
    if isinstance(spec, str) and spec in data:
        return np.asarray(data[spec])
    field = getattr(spec, "field", None) or (spec.get("field") if isinstance(spec, dict) else None)
    if field is not None:
        return np.asarray(data.get(field, []))
    value = getattr(spec, "value", None) if not isinstance(spec, (int, float)) else spec
    if isinstance(spec, dict):
        value = spec.get("value")
    return np.full(n or 0, np.nan if value is None else value, dtype=float)


def _dash(d) -> object:
    if not d or d == "solid":
        return "-"
    if isinstance(d, str):
        return {"dashed": "--", "dotted": ":", "dotdash": "-.", "dashdot": "-."}.get(d, "--")
    return (0, tuple(float(x) * 0.6 for x in d))  # Bokeh's px on/off pattern


def _color(c, default="none"):
    return default if c is None else c


def _alpha(a) -> float:
    return 1.0 if a is None or not isinstance(a, (int, float)) else float(a)


def _draw_renderer(ax, r, gid: str | None):
    """Draw one glyph renderer; returns the artist (for the legend) or None."""
    g, src = r.glyph, r.data_source
    data = dict(src.data)
    if isinstance(g, Line):
        x, y = _col(src, data, g.x), _col(src, data, g.y)
        if len(x) == 0:
            return None
        (art,) = ax.plot(
            x,
            y,
            color=_color(g.line_color),
            lw=g.line_width,
            ls=_dash(g.line_dash),
            alpha=_alpha(g.line_alpha),
        )
    elif isinstance(g, Scatter):
        x, y = _col(src, data, g.x), _col(src, data, g.y)
        if len(x) == 0:
            return None
        size = g.size if isinstance(g.size, (int, float)) else 8
        marker = MARKERS.get(g.marker if isinstance(g.marker, str) else "circle", "o")
        filled = marker not in ("x", "+")
        face = _color(g.fill_color) if filled and _alpha(g.fill_alpha) > 0 else "none"
        edge = _color(g.line_color, "black")
        kw = {"edgecolors": edge} if filled else {"color": edge}
        art = ax.scatter(
            x,
            y,
            s=(0.75 * size) ** 2,
            marker=marker,
            linewidths=g.line_width,
            **({"facecolors": face} if filled else {}),
            **kw,
            zorder=3,
        )
    elif isinstance(g, VArea):
        x = _col(src, data, g.x)
        if len(x) == 0:
            return None
        art = ax.fill_between(
            x,
            _col(src, data, g.y1),
            _col(src, data, g.y2),
            color=_color(g.fill_color),
            alpha=_alpha(g.fill_alpha),
            lw=0,
        )
    elif isinstance(g, Quad):
        lft = _col(src, data, g.left)
        if len(lft) == 0:
            return None
        n = len(lft)
        rgt, bot, top = (_col(src, data, s, n) for s in (g.right, g.bottom, g.top))
        art = None
        for a, b, c, d in zip(lft, rgt, bot, top):
            art = ax.fill_between(
                [a, b],
                [c, c],
                [d, d],
                color=_color(g.fill_color),
                alpha=_alpha(g.fill_alpha),
                edgecolor=_color(g.line_color),
                lw=g.line_width * _alpha(g.line_alpha),
            )
    elif isinstance(g, Segment):
        x0 = _col(src, data, g.x0)
        if len(x0) == 0:
            return None
        n = len(x0)
        y0, x1, y1 = (_col(src, data, s, n) for s in (g.y0, g.x1, g.y1))
        art = None
        for a, b, c, d in zip(x0, y0, x1, y1):
            (art,) = ax.plot(
                [a, c], [b, d], color=_color(g.line_color), lw=g.line_width, ls=_dash(g.line_dash)
            )
    elif isinstance(g, Image):
        imgs = data.get(g.image if isinstance(g.image, str) else "image", [])
        if len(imgs) == 0:
            return None
        z = np.asarray(imgs[0], float)
        x, y, dw, dh = (float(_col(src, data, s, 1)[0]) for s in (g.x, g.y, g.dw, g.dh))
        cm = g.color_mapper
        cmap = _listed(cm.palette)
        art = ax.imshow(
            z,
            origin="lower",
            extent=(x, x + dw, y, y + dh),
            aspect="auto",
            cmap=cmap,
            vmin=cm.low,
            vmax=cm.high,
            interpolation="nearest",
        )
        ax.figure.colorbar(art, ax=ax, fraction=0.04)
    else:
        return None
    if gid and art is not None:
        art.set_gid(gid)
    return art


def _listed(palette):
    from matplotlib.colors import ListedColormap

    return ListedColormap(list(palette))


def plain(text) -> str:
    """``text`` for Matplotlib, drawn as typed: a ``$`` is escaped, so no ``$…$`` of a typed
    law or a store's name is parsed as mathtext (it drew math, or failed the export)."""
    return str(text).replace("$", r"\$")


def _label_text(label) -> str:
    if isinstance(label, str):
        return label
    if isinstance(label, dict):
        return str(label.get("value", ""))
    return str(getattr(label, "value", "") or "")


def draw_figure(ax, fig) -> None:
    arts = {}
    for r in fig.renderers:
        if getattr(r, "visible", True) and hasattr(r, "glyph"):
            name = getattr(r.data_source, "name", None)
            art = _draw_renderer(ax, r, name)
            if art is not None:
                arts[r.id] = art
    for obj in fig.center + fig.above + fig.below + fig.left + fig.right:
        if not getattr(obj, "visible", True):
            continue
        if isinstance(obj, Span) and obj.location is not None:
            line = ax.axvline if obj.dimension == "height" else ax.axhline
            line(
                obj.location,
                color=_color(obj.line_color),
                ls=_dash(obj.line_dash),
                lw=obj.line_width,
            )
        elif isinstance(obj, Label) and obj.text:
            ax.text(
                obj.x,
                obj.y,
                plain(obj.text),
                color=_color(obj.text_color, "black"),
                fontsize=8,
                ha={"center": "center", "right": "right"}.get(obj.text_align, "left"),
            )
        elif isinstance(obj, Whisker):
            d = dict(obj.source.data)
            if len(d.get(obj.base, [])):
                ax.vlines(d[obj.base], d[obj.lower], d[obj.upper], color=obj.line_color)
    for rng, setter in ((fig.x_range, ax.set_xlim), (fig.y_range, ax.set_ylim)):
        start, end = getattr(rng, "start", None), getattr(rng, "end", None)
        if isinstance(start, (int, float)) and isinstance(end, (int, float)) and end > start:
            setter(start, end)
    fw, fh = getattr(fig, "frame_width", None), getattr(fig, "frame_height", None)
    if fw and fh:  # a fixed frame (the complex plane's square): the same box, so the same
        ax.set_box_aspect(fh / fw)  # ranges draw the unit circle round, as on screen
    if isinstance(fig.y_scale, LogScale):
        ax.set_yscale("log")
    if isinstance(fig.x_scale, LogScale):
        ax.set_xscale("log")
    ax.set_title(plain(fig.title.text if fig.title is not None else ""), fontsize=9)
    ax.set_xlabel(plain(fig.xaxis[0].axis_label or "" if fig.xaxis else ""))
    ax.set_ylabel(plain(fig.yaxis[0].axis_label or "" if fig.yaxis else ""))
    handles, labels = [], []
    for legend in fig.legend:
        for item in legend.items:
            text = _label_text(item.label)
            art = next((arts[r.id] for r in item.renderers if r.id in arts), None)
            if item.visible and text and art is not None:
                handles.append(art)
                labels.append(plain(text))
    if handles:
        ax.legend(
            handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False
        )


def figure_bytes(models, fmt: str, title: str = "") -> bytes:
    """The visible figures under ``models`` drawn with Matplotlib, as SVG or PNG bytes."""
    from matplotlib import rc_context
    from matplotlib.figure import Figure

    if fmt not in FORMATS:
        raise ValueError(f"fmt must be one of {FORMATS}, not {fmt!r}")
    rows = figure_rows(models)
    if not rows:
        raise LookupError("nothing is drawn")
    heights = [max(2.6, min(4.5, max((f.height or 300) for f in row) / 90.0)) for row in rows]
    mfig = Figure(figsize=(WIDTH_IN, sum(heights) + 0.4), dpi=DPI, layout="constrained")
    if title:
        mfig.suptitle(plain(title), fontsize=8)  # the stamp: it may repeat a typed law
    subs = mfig.subfigures(len(rows), 1, height_ratios=heights) if len(rows) > 1 else [mfig]
    for sub, row in zip(np.atleast_1d(subs), rows):
        axes = np.atleast_1d(sub.subplots(1, len(row)))
        for ax, f in zip(axes, row):
            draw_figure(ax, f)
    buf = io.BytesIO()
    # every sample drawn, as on screen (Matplotlib's path simplification would drop vertices)
    with rc_context({"path.simplify": False}):
        mfig.savefig(buf, format=fmt, metadata=_metadata(fmt))
    return buf.getvalue()


def _metadata(fmt: str) -> dict:
    who = f"fpu-explorer / fpucore {fpucore.__version__}"
    return {"Creator": who} if fmt == "svg" else {"Software": who}


# ---------------------------------------------------------------------------- notebook
_STATEMENT = re.compile(r"^[A-Za-z_][\w, ]*\s*=(?!=)")


def code_cells(code: str) -> list[str]:
    """``code`` cut into cells: the preamble (imports, the law), then one cell per computation —
    an assignment at column 0 (with the comment just above it) and the lines after it (prints,
    imports, continuation lines) up to the next one.  ``"\\n".join(cells)`` is ``code`` without
    its trailing newline."""
    lines = code.rstrip("\n").split("\n")
    cells: list[list[str]] = [[]]
    law_done = False  # the preamble ends with the line that makes ``law``
    introduced = False  # a comment has just opened the cell of the next computation
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if law_done and line.startswith("#") and _STATEMENT.match(nxt):
            cells.append([])
            introduced = True
        elif law_done and _STATEMENT.match(line):
            if not introduced:
                cells.append([])
            introduced = False
        cells[-1].append(line)
        law_done = law_done or line.startswith("law = ")
    return ["\n".join(c) for c in cells if c]


def notebook_json(title: str, intro: str, code: str, plot_code: str) -> str:
    """The notebook (JSON text): a Markdown cell, the code cells, a plot cell."""
    import nbformat

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell(f"# {title}\n\n{intro}")]
    nb.cells += [nbformat.v4.new_code_cell(c) for c in code_cells(code)]
    if plot_code:
        nb.cells.append(nbformat.v4.new_code_cell(plot_code.rstrip("\n")))
    nb.metadata["kernelspec"] = {
        "name": "python3",
        "display_name": "Python 3",
        "language": "python",
    }
    nbformat.validate(nb)
    return nbformat.writes(nb)
