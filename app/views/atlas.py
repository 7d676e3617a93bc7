"""Scene "Atlas" — heat maps over the existence diagram (w₊, V) from an atlas store (read by
:func:`fpucore.atlas.open_atlas`), or from a small atlas computed as a job of :mod:`app.compute`
(``compute.run(law, AtlasRequest(...))``: in a worker process of the server's pool, cached on
its exact request, with progress and Cancel, as every heavy computation of the app).

Quantities: max |μ| − 1 (log scale of the excess; needs Floquet), amplitude, E_ren^D.  Cells
without a wave (outside the existence region, or not converged) are blank; the counts by status
and the largest error bars are shown next to the plot.  A click on a cell sets (w₊, V) to that
cell's point and the atlas's N (``ExplorerState.pick``), marks the cell, and the Profiles /
Floquet tabs then show that wave.  A superkink atlas (rows: the branches, over V only) is
drawn as the quantity against V, one series per branch; a click on a point opens that
superkink (superkink mode, w₊ from V on its branch).  A store is read only below
``app.url_state.atlas_root()``; its path is part of the state, so the URL carries it.
"""

from __future__ import annotations

import numpy as np
import panel as pn
from bokeh.events import Tap
from bokeh.layouts import column
from bokeh.models import ColorBar, ColumnDataSource, LinearColorMapper

import fpucore
from fpucore import atlas, qc
from fpucore.atlas import AtlasData
from fpucore.errors import ParameterError

from .. import compute
from ..compute import Computed
from ..data_dir import hide_server_paths
from ..state import N_RANGE
from ..url_state import resolve_atlas_store
from .bokeh_scene import (
    BokehScene,
    Updates,
    add_legend,
    add_points,
    finite_extent,
    new_figure,
)
from .formatting import as_csv
from .python_code import python_preamble
from .report import Info, SceneMessage
from .untrusted import md_literal

#: the heat map's quantities: name → its (rows, V) values in an atlas
QUANTITIES = {
    "max |μ| − 1": lambda d: d.max_modulus - 1.0,
    "amplitude": lambda d: d.amplitude,
    "E_ren": lambda d: d.energy,
}
#: the AtlasData field each quantity is computed from (what "Copy as Python" prints)
FIELDS = {"max |μ| − 1": "max_modulus", "amplitude": "amplitude", "E_ren": "energy"}
FLOQUET_QUANTITY = "max |μ| − 1"
#: the excess drawn on the log scale is floored here (a stable wave's is ~0 or below)
EXCESS_FLOOR = 1e-16
RUN = "background run"  # the source of the atlas on screen when it is the button's run
#: a superkink atlas's branches, drawn in these colours
BRANCH_COLOURS = {"lower": "#1f77b4", "upper": "#d62728"}


class AtlasScene(BokehScene):
    title = "Atlas"
    caption = (
        "_Heat map of an atlas of discrete solitary waves over the existence region (w₊, V): "
        "max |μ| − 1 of their Floquet spectra, their amplitude or renormalized energy. Click a "
        "cell to open that wave. Paper: Figs. SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC and "
        "floquet_cubicSW (one line of this map each)._"
    )
    depends = ("a", "b", "expression", "atlas")
    plot_height = 480

    def build(self):
        fig = new_figure("Atlas over (w₊, V) (click a cell: that wave)", "w₊", "V",
                         sizing_mode="stretch_width", height=self.plot_height)  # fmt: skip
        self.fig = fig
        self.mapper = LinearColorMapper(palette="Viridis256", nan_color=(0, 0, 0, 0))
        # a 1 x 1 transparent image until an atlas is shown: BokehJS's image glyph needs a 2-D
        # array in every row of its source ("expected a 2D array" otherwise)
        self.src = ColumnDataSource(
            {"image": [np.full((1, 1), np.nan)], "x": [0.0], "y": [0.0], "dw": [1.0], "dh": [1.0]},
            name="atlas-image",
        )
        fig.image("image", x="x", y="y", dw="dw", dh="dh", source=self.src,
                  color_mapper=self.mapper)  # fmt: skip
        self.colorbar = ColorBar(color_mapper=self.mapper, width=12)
        fig.add_layout(self.colorbar, "right")
        # the picked cell's outline (empty until a click)
        self.pick_src = ColumnDataSource({"l": [], "r": [], "b": [], "t": []}, name="atlas-pick")
        fig.quad(left="l", right="r", bottom="b", top="t", source=self.pick_src,
                 fill_alpha=0.0, line_color="#d62728", line_width=3)  # fmt: skip
        fig.on_event(Tap, lambda ev: self.pick(ev.x, ev.y))
        # a superkink atlas: the quantity against V per branch (hidden until one is shown)
        self.fig_sk = new_figure("Superkink atlas (click a point: that superkink)", "V", "",
                                 sizing_mode="stretch_width", height=self.plot_height)  # fmt: skip
        self.sk_points = {}
        for branch, colour in BRANCH_COLOURS.items():
            r, src = add_points(self.fig_sk, "circle", 8, color=colour)
            src.name = f"atlas-superkink-{branch}"
            self.sk_points[branch] = (r, src)
        add_legend(
            self.fig_sk, "below", [(f"{b} branch", [r]) for b, (r, _) in self.sk_points.items()]
        )
        self.fig_sk.visible = False
        self.fig_sk.on_event(Tap, lambda ev: self.pick_superkink(ev.x, ev.y))
        return column(fig, self.fig_sk, sizing_mode="stretch_width")

    def controls(self):
        self.store = pn.widgets.TextInput(
            name="atlas store (Zarr, below the server's directory)", placeholder="atlas.zarr",
            value=self.state.atlas, width=280,
        )  # fmt: skip
        self.quantity = pn.widgets.Select(name="quantity", options=list(QUANTITIES), width=200)
        lo, hi = compute.requests.SMALL_ATLAS_POINTS
        self.n_w = pn.widgets.IntInput(name="w₊ rows", value=8, start=lo, end=hi, width=130)
        self.n_V = pn.widgets.IntInput(name="velocities", value=8, start=lo, end=hi, width=130)
        N_lo, N_hi = compute.requests.SMALL_ATLAS_N
        self.N_run = pn.widgets.IntInput(name="N", value=200, start=N_lo, end=N_hi, step=20,
                                         width=130)  # fmt: skip
        self.run_btn = pn.widgets.Button(
            label="Run a small atlas (with Floquet)", color="primary", css_classes=["atlas-run"]
        )
        return [self.store, self.quantity, pn.Row(self.n_w, self.n_V), self.N_run, self.run_btn]

    def __init__(self, state):
        super().__init__(state)
        self._want_run = False
        self._refused = ""  # a click on a blank cell, named above the plot
        self._data: AtlasData | None = None
        self._source = ""
        # the run on screen: its request, timing label and cost
        self._run: tuple[compute.AtlasRequest, str, float] | None = None
        self._cell: tuple[int, int] | None = None  # the picked (w₊ row, V column)
        self.last_z: np.ndarray | None = None

        def go(_):
            self._want_run = True
            if self.state.atlas:  # the run replaces the store on screen (and in the URL)
                self.state.atlas = ""
            self.request()

        self.run_btn.on_click(go)

        def typed(event):  # the box writes the state (and so the URL); the state renders
            if self.state.atlas != event.new:
                self.state.atlas = event.new
            else:
                self.request()

        def linked(event):  # the state (the box, a URL) names a store: show it
            if self.store.value != event.new:
                self.store.value = event.new
            self.request()

        self.store.param.watch(typed, "value")
        self.state.param.watch(linked, "atlas")
        self.quantity.param.watch(lambda _: self.request(), "value")

    # ------------------------------------------------------------------ data
    def load(self, path: str) -> AtlasData:
        p = resolve_atlas_store("atlas store", path)  # ParameterError: shown as the message
        try:
            data = atlas.open_atlas(p)
        except ParameterError as exc:  # no store there, or unreadable: the reason names it
            # relative to the server's data directory, never its absolute path
            raise SceneMessage(hide_server_paths(exc.reason or str(exc))) from None
        return data

    def atlas_request(self) -> compute.AtlasRequest:
        """The button's atlas: the widgets' grid over the law's w₊ range (ParameterError for a
        count outside the widgets' range)."""
        lo, _, hi = self.state.w_plus_range()  # (alpha, beta) for the cubic; finite for any law
        pad = 0.02 * (hi - lo)
        return compute.AtlasRequest(lo + pad, hi - pad, self.n_w.value, self.n_V.value,
                                    self.N_run.value)  # fmt: skip

    def run_small(self, info: Info) -> AtlasData:
        req = self.atlas_request()
        self.set_stage("atlas points")
        c = compute.run(self.state.law(), req, **self.job_hooks("atlas points"))
        res = c.value
        label = f"atlas run ({res.n_computed} points)"
        self._run = (req, label, c.elapsed_s)
        info.time(label, c)
        return atlas.atlas_data(res.dataset)

    # ------------------------------------------------------------------ render
    def render(self, info: Info):
        if self._want_run:
            self._want_run = False
            self._data, self._source = self.run_small(info), RUN
            self._cell = None
        elif self.state.atlas:
            if self._source != self.state.atlas:
                self._data, self._source = self.load(self.state.atlas), self.state.atlas
                self._cell, self._run = None, None
        elif self._source != RUN:
            self._data, self._source, self._cell = None, "", None
        if self._source == RUN and self._run and not info.timings:
            # a re-render of the run already on screen keeps what the run cost
            info.time(self._run[1], Computed(None, self._run[2], True))
        if self._data is None:
            raise SceneMessage("Give an atlas store (fpu atlas solitary … --out atlas.zarr) or "
                               "run a small atlas with the button.", "info")  # fmt: skip
        data = self._data
        name = self.quantity.value
        z = QUANTITIES[name](data)
        ok = data.ok
        z = np.where(ok & np.isfinite(z), z, np.nan)
        if not np.isfinite(z).any():
            raise SceneMessage(f"no {name} in this atlas (computed without Floquet?)")
        info.error("max residual", np.nanmax(np.where(ok, data.residual, np.nan)))
        if name == FLOQUET_QUANTITY:
            info.error("max |μ| error bar", np.nanmax(np.where(ok, data.max_modulus_error, np.nan)))
        info.notes.append(", ".join(f"{v} {k}" for k, v in data.counts().items() if v))
        if data.kind == "superkink":
            return self._render_superkink(info, data, name, z)
        info.shown = f"{name} over (w₊, V), {md_literal(self._source)}"
        w, V = data.w_plus, data.V
        self.last_z = z  # (n_w, n_V): what the image shows
        # cell edges half way between grid points (the grid may be non-uniform in V)
        dw = (w[-1] - w[0]) / max(len(w) - 1, 1) if len(w) > 1 else 1.0
        dv = (V[-1] - V[0]) / max(len(V) - 1, 1) if len(V) > 1 else 1.0
        up = Updates()
        up.set(self.fig, visible=True)
        up.set(self.fig_sk, visible=False)
        drawn, bar = z, name
        if name == FLOQUET_QUANTITY:  # the excess spans decades: drawn on a log scale
            drawn = np.log10(np.maximum(z, EXCESS_FLOOR))
            bar = f"log₁₀(max |μ| − 1), ≤ {EXCESS_FLOOR:.0e} drawn at {np.log10(EXCESS_FLOOR):.0f}"
        up.set(self.colorbar, title=bar)
        if self._refused:
            info.warning = self._refused
        # set, not Updates.data: the image column is a *list* of 2-D arrays (np.asarray would
        # stack it into one 3-D array, which BokehJS's image glyph rejects)
        up.set(self.src, data={"image": [np.ascontiguousarray(drawn.T)], "x": [w[0] - dw / 2],
                               "y": [V[0] - dv / 2], "dw": [dw * len(w)],
                               "dh": [dv * len(V)]})  # fmt: skip
        finite = drawn[np.isfinite(drawn)]
        up.set(self.mapper, low=float(finite.min()), high=float(finite.max()))
        up.set(self.fig.title, text=f"{name} over (w₊, V) (click a cell: that wave)")
        up.range(self.fig.x_range, w[0] - dw / 2, w[-1] + dw / 2)
        up.range(self.fig.y_range, V[0] - dv / 2, V[-1] + dv / 2)
        self._cell_edges = (w, V, dw, dv)
        up.set(self.pick_src, data=self._cell_outline())
        if self._cell is not None:
            i, j = self._cell
            info.notes.append(f"picked cell w₊ = {w[i]:.6g}, V = {V[j]:.6g} (N = {self.atlas_N})")
        return up

    def _render_superkink(self, info: Info, data: AtlasData, name: str, z: np.ndarray):
        """A superkink atlas: ``name`` against V, one series per branch (its rows); the excess
        max |μ| − 1 on log₁₀ (floored as on the map)."""
        info.shown = f"{name} of superkinks against V, {md_literal(self._source)}"
        self.last_z = z
        drawn, label = z, name
        if name == FLOQUET_QUANTITY:
            drawn = np.log10(np.maximum(z, EXCESS_FLOOR))
            label = f"log₁₀(max |μ| − 1) (≤ {EXCESS_FLOOR:.0e} drawn at the floor)"
        up = Updates()
        up.set(self.fig, visible=False)
        up.set(self.fig_sk, visible=True)
        up.set(self.fig_sk.yaxis[0], axis_label=label)
        up.set(self.fig_sk.title, text=f"{name} of superkinks against V (click a point: that "
                                       "superkink)")  # fmt: skip
        rows = [str(r) for r in data.rows]
        for branch, (_, src) in self.sk_points.items():
            if branch in rows:
                y = drawn[rows.index(branch)]
                keep = np.isfinite(y)
                up.data(src, x=data.V[keep], y=y[keep])
            else:
                up.data(src, x=np.empty(0), y=np.empty(0))
        up.range(self.fig_sk.x_range, float(data.V.min()), float(data.V.max()), pad=0.04)
        up.range(self.fig_sk.y_range, *finite_extent(drawn), pad=0.08)
        return up

    def pick_superkink(self, x, y) -> bool:
        """A click on the superkink atlas: the nearest computed point (in V, then the branch
        nearest in the drawn value) becomes the current superkink; False if none."""
        d = self._data
        if x is None or y is None or d is None or d.kind != "superkink":
            return False
        j = int(np.argmin(np.abs(d.V - x)))
        z = QUANTITIES[self.quantity.value](d)[:, j]
        if self.quantity.value == FLOQUET_QUANTITY:
            z = np.log10(np.maximum(z, EXCESS_FLOOR))
        rows = [i for i in range(len(d.rows)) if d.ok[i, j] and np.isfinite(z[i])]
        if not rows:
            return False
        i = min(rows, key=lambda k: abs(z[k] - y))
        V, branch = float(d.V[j]), str(d.rows[i])
        try:
            w_plus = qc.superkink_from_V(self.state.law(), V, branch).w_plus
            self.state.mode = "superkink"
            N = self.atlas_N
            N = N if N is not None and N_RANGE[0] <= N <= N_RANGE[1] else None
            self.state.pick(w_plus, V, N=N)
        except ParameterError:
            return False
        return True

    def _cell_outline(self) -> dict:
        if self._cell is None or self._data is None:
            return {"l": [], "r": [], "b": [], "t": []}
        w, V, dw, dv = self._cell_edges
        i, j = self._cell
        return {"l": [w[i] - dw / 2], "r": [w[i] + dw / 2], "b": [V[j] - dv / 2],
                "t": [V[j] + dv / 2]}  # fmt: skip

    @property
    def atlas_N(self) -> int | None:
        """The chain size the atlas's waves were computed at (None: not recorded)."""
        return None if self._data is None else self._data.N

    @property
    def atlas_data(self) -> AtlasData | None:
        """The atlas on screen (None before one is loaded or run)."""
        return self._data

    def pick(self, x, y) -> bool:
        """Set the state to the grid point nearest to (x, y) = (w₊, V); False if none."""
        if x is None or y is None or self._data is None:
            return False
        w, V = self._data.w_plus, self._data.V
        i, j = int(np.argmin(np.abs(w - x))), int(np.argmin(np.abs(V - y)))
        if not self._data.ok[i, j]:  # a blank cell: no wave there, the state stays valid
            self._refused = (
                f"No wave at the cell w₊ = {w[i]:.6g}, V = {V[j]:.6g} (blank: outside the "
                "existence region or not converged); the parameters are unchanged."
            )
            self.request()
            return False
        self._refused = ""
        N = self.atlas_N
        try:
            # the atlas's N too: the Profiles / Floquet tabs then show this cell's very wave
            self.state.pick(
                float(w[i]),
                float(V[j]),
                N=N if N is not None and N_RANGE[0] <= N <= N_RANGE[1] else None,
            )
        except ParameterError:
            return False
        self._cell = (i, j)
        self.request()  # redraw with the cell marked
        return True

    def download_data(self):
        if self._data is None:
            raise SceneMessage("nothing to download yet")
        d = self._data
        W, Vg = np.meshgrid(d.w_plus, d.V, indexing="ij")
        cols = {"w_plus": W, "V": Vg, "amplitude": d.amplitude, "energy": d.energy,
                "residual": d.residual, "max_modulus": d.max_modulus,
                "max_modulus_error": d.max_modulus_error}  # fmt: skip
        cols = {k: v.ravel() for k, v in cols.items()}
        return "atlas.csv", as_csv(cols, self.header() + "\n" + self.python_code())

    def header(self) -> str:
        """The download's header: the atlas's own parameters (its store attributes), not the
        sidebar's N and tol, which may differ."""
        lines = [f"atlas from {self._source}", f"fpu-explorer / fpucore {fpucore.__version__}"]
        lines += [f"{k}={v!r}" for k, v in self._data.parameters.items()]
        return "\n".join(lines)

    def notebook_plot(self) -> str:
        var = FIELDS[self.quantity.value]
        return f"data.dataset[{var!r}].plot(x='w_plus', y='V')\n"

    def python_code(self) -> str:
        var = FIELDS[self.quantity.value]  # the numbers on screen, (w₊, V) rows
        code = python_preamble(self.state) + "from fpucore import atlas\n"
        if self._source and self._source != RUN:
            return code + (
                f"data = atlas.open_atlas({self._source!r})\nprint(data.{var}.tolist())\n"
            )
        try:  # the run on screen, else the one the button would start
            req = self._run[0] if self._run else self.atlas_request()
        except ParameterError as exc:
            return code + f"# no atlas: {exc}\n"
        return code + (
            f"res = {req.call().code()}\n"
            "data = atlas.atlas_data(res.dataset)\n"
            "print(res.message)\n"
            f"print(data.{var}.tolist())\n"
        )
