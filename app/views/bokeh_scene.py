"""Scenes drawn with raw Bokeh figures that are built once and then updated in place.

The QC scenes must follow a slider within tens of milliseconds.  Building HoloViews elements and
letting HoloViews diff them against the plot on every move costs hundreds; here a scene builds
its Bokeh figure(s) once (:meth:`BokehScene.build`) and :meth:`render` returns an
:class:`Updates` list — new ``ColumnDataSource.data`` dicts, axis ranges, span locations, label
texts — computed from fpucore's results.  :meth:`BokehScene.publish` applies them on the
session's event loop (Bokeh models that belong to a served document may only be changed there).
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import Any

import numpy as np
import panel as pn
import param
from bokeh.models import (
    ColumnDataSource,
    GlyphRenderer,
    Label,
    Legend,
    LegendItem,
    Range1d,
    Span,
)
from bokeh.plotting import figure
from panel.viewable import Layoutable

from .scene import Scene

TOOLS = "pan,wheel_zoom,box_zoom,save,reset"


class Updates:
    """Property changes of one render: ``(model, key, props)``.  A ``key`` (any hashable that
    identifies the content, e.g. the cache key of the fpucore result) lets :meth:`publish` skip
    a change identical to the one already on screen, so unchanged data are not re-sent."""

    def __init__(self) -> None:
        self.items: list[tuple[Any, Hashable | None, dict]] = []

    def set(self, model, key: Hashable | None = None, **props) -> None:
        self.items.append((model, key, props))

    def data(self, source: ColumnDataSource, key: Hashable | None = None, **columns) -> None:
        self.set(source, key, data={k: np.asarray(v) for k, v in columns.items()})

    def range(self, rng: Range1d, lo: float, hi: float, pad: float = 0.0) -> None:
        """Axis range [lo, hi] widened by ``pad`` × its span (the reset tool returns here)."""
        lo, hi = float(lo), float(hi)
        if not (np.isfinite(lo) and np.isfinite(hi)):
            return
        if hi <= lo:
            lo, hi = lo - 0.5 * max(abs(lo), 1.0), hi + 0.5 * max(abs(hi), 1.0)
        d = pad * (hi - lo)
        lo, hi = lo - d, hi + d
        self.set(rng, start=lo, end=hi, reset_start=lo, reset_end=hi)

    def show(self, renderer: GlyphRenderer, item: LegendItem | None, visible: bool) -> None:
        """Show/hide a renderer together with its legend entry."""
        self.set(renderer, visible=bool(visible))
        if item is not None:
            self.set(item, visible=bool(visible))


def new_figure(title: str, x: str, y: str, **kw) -> figure:
    """A figure with explicit ranges (set by every update, like HoloViews' framewise axes)."""
    kw.setdefault("tools", TOOLS)
    return figure(
        title=title,
        x_axis_label=x,
        y_axis_label=y,
        x_range=Range1d(0.0, 1.0),
        y_range=Range1d(0.0, 1.0),
        toolbar_location="right",
        **kw,
    )


def add_line(fig: figure, color: str, width: float = 1.0, dash: str = "solid", **kw):
    """An (initially empty) line renderer; returns (renderer, source)."""
    src = ColumnDataSource({"x": np.empty(0), "y": np.empty(0)})
    r = fig.line("x", "y", source=src, line_color=color, line_width=width, line_dash=dash, **kw)
    return r, src


def add_band(fig: figure, color: str, alpha: float = 0.6):
    """A filled band between y1 and y2 over x (HoloViews' Area); returns (renderer, source)."""
    src = ColumnDataSource({"x": np.empty(0), "y1": np.empty(0), "y2": np.empty(0)})
    r = fig.varea("x", "y1", "y2", source=src, fill_color=color, fill_alpha=alpha)
    return r, src


def add_points(fig: figure, marker: str = "circle", size: float = 8, **kw):
    """An (initially empty) scatter renderer; returns (renderer, source)."""
    src = ColumnDataSource({"x": np.empty(0), "y": np.empty(0)})
    r = fig.scatter("x", "y", source=src, marker=marker, size=size, **kw)
    return r, src


def add_vline(fig: figure, color: str, dash: str = "solid", width: float = 1.0) -> Span:
    span = Span(location=0.0, dimension="height", line_color=color, line_dash=dash)
    span.line_width = width
    fig.add_layout(span)
    return span


def add_label(fig: figure, color: str = "gray", size: str = "10pt", align: str = "center") -> Label:
    lab = Label(x=0.0, y=0.0, text="", text_color=color, text_font_size=size, text_align=align)
    fig.add_layout(lab)
    return lab


def add_legend(
    fig: figure, place: str, entries: Iterable[tuple[str, list[GlyphRenderer]]]
) -> list[LegendItem]:
    """A legend *outside* the data: ``place`` is a side of the figure ("right", "below",
    "above"), so no entry ever covers a curve."""
    items = [LegendItem(label=label, renderers=rs) for label, rs in entries]
    orientation = "vertical" if place in ("left", "right") else "horizontal"
    legend = Legend(
        items=items,
        location="top_left" if orientation == "vertical" else "center",
        orientation=orientation,
        border_line_alpha=0.0,
        label_text_font_size="9pt",
        spacing=2,
        click_policy="hide",
    )
    fig.add_layout(legend, place)
    return items


def finite_extent(*arrays) -> tuple[float, float]:
    """(min, max) over the finite values of the arrays (NaN, NaN if there are none)."""
    parts = [np.asarray(a, float).ravel() for a in arrays]
    v = np.concatenate(parts) if parts else np.empty(0)
    v = v[np.isfinite(v)]
    return (float(v.min()), float(v.max())) if v.size else (float("nan"), float("nan"))


class FigurePane(pn.pane.Bokeh):
    """``pn.pane.Bokeh`` whose sync of the figure's layout properties into the pane skips
    ``stylesheets``: the Panel design puts ImportedStyleSheet models there, which the pane's
    list-of-str parameter rejects (TypeError) when it re-syncs, e.g. on a visibility change.
    It also reads only the layout properties instead of all of the figure's (cheaper), and
    keeps the figure's ``visible`` equal to the pane's."""

    @param.depends("object", watch=True)
    def _sync_properties(self):
        if self.object is None:
            return
        skip = {"css_classes", "name", "stylesheets", "visible", *self._overrides}
        names = [p for p in Layoutable.param if p not in skip and p in self.object.properties()]
        self._syncing_props = True
        try:
            self.param.update({p: getattr(self.object, p) for p in names})
            # the pane owns visibility (Panel's version leaves a figure hidden when `visible`
            # returns to its default while the pane is not displayed)
            props = {o: getattr(self, o) for o in {*self._overrides, "visible"}}
            fig = self.object
            doc = fig.document
            if doc is not None and doc.session_context is not None:
                # a served figure may only change on the session's loop (this runs from scene
                # worker threads too, e.g. when a message hides the plot): now if on it, else
                # scheduled — a direct write from a thread kills that thread in Bokeh
                pn.state.execute(lambda: fig.update(**props), schedule="auto")
            else:
                fig.update(**props)
        finally:
            self._syncing_props = False


class BokehScene(Scene):
    """A scene whose plot is a Bokeh model built once, empty, at construction (:meth:`build`;
    nothing is computed then) and updated in place by the :class:`Updates` that :meth:`render`
    returns."""

    #: keyword arguments of the main plot pane (the figure itself carries its size)
    pane_kw: dict = {"sizing_mode": "stretch_width"}

    def __init__(self, state):
        super().__init__(state)
        # Build the figures and put them in their pane while the page is being built: every
        # render then only changes models the browser already has.  Building them lazily inside
        # the first render raced with a tab switch coming from the URL (the browser kept the
        # pre-render ranges).
        self._keys: dict[str, Hashable] = {}
        self._root = self.build()
        self.attach()

    def make_plot(self):
        return FigurePane(None, **self.pane_kw)

    def build(self):  # pragma: no cover - abstract
        """Create figures, sources and annotations (store references on self); return the root
        model of the main plot pane."""
        raise NotImplementedError

    def attach(self) -> None:
        """Put the built models into the panes (once, at construction)."""
        self.plot.object = self._root

    def figure_models(self) -> list:
        """The main pane's model and every further figure pane's (e.g. a clickable diagram)."""
        extra = [p.object for p in self._extra if isinstance(p, pn.pane.Bokeh)]
        return [self._root, *extra]

    def publish(self, upd: Updates) -> None:
        self.plot.visible = True
        for pane in self._extra:
            pane.visible = True
        todo = []
        for model, key, props in upd.items:
            if key is not None:
                if self._keys.get(model.id) == key:
                    continue
                self._keys[model.id] = key
            todo.append((model, props))

        def apply():
            for model, props in todo:
                model.update(**props)

        doc = self._doc
        if doc is not None and doc.session_context is not None:
            # served models change only on the session's loop, in order: Bokeh's thread-safe
            # next-tick queue (the same queue Panel uses for the status text written after
            # this), never a direct write from the worker thread
            doc.add_next_tick_callback(apply)
        else:
            apply()
