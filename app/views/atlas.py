"""Scene "Atlas" — heat maps over the existence diagram (w₊, V) from an atlas store
(:mod:`fpucore.atlas`), or from a small atlas run in the background through the execution layer
(:class:`fpucore.parallel.Executor`, one process per core, one BLAS thread each).

Quantities: max |μ| − 1 (log scale of the excess; needs Floquet), amplitude, E_ren^D.  Cells
without a wave (outside the existence region, or not converged) are blank; the counts by status
and the largest error bars are shown next to the plot.  A click on a cell sets (w₊, V) to that
cell's point and the atlas's N (``ExplorerState.pick``), marks the cell, and the Profiles /
Floquet tabs then show that wave.  A store is read only below ``app.state.atlas_root()``; its
path is part of the state, so the URL carries it.
"""

from __future__ import annotations

import numpy as np
import panel as pn
import xarray as xr
from bokeh.events import Tap
from bokeh.models import ColorBar, ColumnDataSource, LinearColorMapper

import fpucore
from fpucore import atlas
from fpucore.errors import ParameterError

from ..compute import Computed
from ..state import N_RANGE, resolve_atlas_store
from .bokeh_scene import BokehScene, Updates, new_figure
from .formatting import as_csv
from .python_code import python_preamble
from .report import Info, SceneMessage
from .untrusted import md_literal

QUANTITIES = {
    "max |μ| − 1": "max_modulus",
    "amplitude": "amplitude",
    "E_ren": "energy",
}


class AtlasScene(BokehScene):
    key = "atlas"
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
        fig.add_layout(ColorBar(color_mapper=self.mapper, width=12), "right")
        # the picked cell's outline (empty until a click)
        self.pick_src = ColumnDataSource({"l": [], "r": [], "b": [], "t": []}, name="atlas-pick")
        fig.quad(left="l", right="r", bottom="b", top="t", source=self.pick_src,
                 fill_alpha=0.0, line_color="#d62728", line_width=3)  # fmt: skip
        fig.on_event(Tap, lambda ev: self.pick(ev.x, ev.y))
        return fig

    def controls(self):
        self.store = pn.widgets.TextInput(
            name="atlas store (Zarr, below the server's directory)", placeholder="atlas.zarr",
            value=self.state.atlas, width=280,
        )  # fmt: skip
        self.quantity = pn.widgets.Select(name="quantity", options=list(QUANTITIES), width=200)
        self.n_w = pn.widgets.IntInput(name="w₊ rows", value=8, start=2, end=60, width=130)
        self.n_V = pn.widgets.IntInput(name="velocities", value=8, start=2, end=60, width=130)
        self.N_run = pn.widgets.IntInput(name="N", value=200, start=40, end=1000, step=20,
                                         width=130)  # fmt: skip
        self.run_btn = pn.widgets.Button(
            label="Run a small atlas (with Floquet)", color="primary", css_classes=["atlas-run"]
        )
        return [self.store, self.quantity, pn.Row(self.n_w, self.n_V), self.N_run, self.run_btn]

    def _extra_watch(self) -> None:
        self._want_run = False
        self._ds: xr.Dataset | None = None
        self._source = ""
        self._rows = ""
        self._run_time: tuple[str, float] | None = None  # the background run's label and cost
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
    def load(self, path: str) -> xr.Dataset:
        p = resolve_atlas_store("atlas store", path)  # ParameterError: shown as the message
        if not p.is_dir():
            raise SceneMessage(f"no atlas store at {p}")
        try:
            ds = xr.open_zarr(p, consolidated=False).load()
        except Exception as exc:  # noqa: BLE001  (shown, not raised)
            raise SceneMessage(f"cannot read {path}: {type(exc).__name__}: {exc}") from None
        if "w_plus" not in ds.dims:
            raise SceneMessage("this store is a superkink atlas (over V only): no (w₊, V) map")
        return ds

    def run_small(self, info: Info) -> xr.Dataset:
        s = self.state
        law = s.law()
        lo, _, hi = s.w_plus_range()  # (alpha, beta) for the cubic; finite for any law
        pad = 0.02 * (hi - lo)
        rows = self._rows = f"{lo + pad}:{hi - pad}:{int(self.n_w.value)}"
        res = atlas.run(
            law, "solitary", rows=rows, V=int(self.n_V.value), N=int(self.N_run.value),
            floquet=True, finite_size=False,
            progress=lambda d, n, f: self.set_progress(d, n, "atlas points"),
        )  # fmt: skip
        label = f"atlas run ({res.n_computed} points, {res.workers} {res.backend} workers)"
        self._run_time = (label, res.elapsed_s)
        info.time(label, res.elapsed_s)
        return res.dataset

    # ------------------------------------------------------------------ render
    def render(self, info: Info):
        if self._want_run:
            self._want_run = False
            self._ds, self._source = self.run_small(info), "background run"
            self._cell = None
        elif self.state.atlas:
            if self._source != self.state.atlas:
                self._ds, self._source = self.load(self.state.atlas), self.state.atlas
                self._cell, self._run_time = None, None
        elif self._source != "background run":
            self._ds, self._source, self._cell = None, "", None
        if self._source == "background run" and self._run_time and not info.timings:
            # a re-render of the run already on screen keeps what the run cost
            info.time(self._run_time[0], Computed(None, self._run_time[1], True))
        if self._ds is None:
            raise SceneMessage("Give an atlas store (fpu atlas solitary … --out atlas.zarr) or "
                               "run a small atlas with the button.", "info")  # fmt: skip
        ds = self._ds
        name = self.quantity.value
        var = QUANTITIES[name]
        z = ds[var].values.astype(float)
        if var == "max_modulus":
            z = z - 1.0
        ok = ds["status"].values == "ok"
        z = np.where(ok & np.isfinite(z), z, np.nan)
        if not np.isfinite(z).any():
            raise SceneMessage(f"no {name} in this atlas (computed without Floquet?)")
        counts = {k: int(np.sum(ds["status"].values == k))
                  for k in ("ok", "not_converged", "no_wave", "failed")}  # fmt: skip
        info.shown = f"{name} over (w₊, V), {md_literal(self._source)}"
        info.error("max residual", np.nanmax(np.where(ok, ds["residual"].values, np.nan)))
        if var == "max_modulus":
            info.error("max |μ| error bar", np.nanmax(np.where(ok, ds[
                "max_modulus_error"].values, np.nan)))  # fmt: skip
        info.notes.append(", ".join(f"{v} {k}" for k, v in counts.items() if v))
        w, V = ds["w_plus"].values.astype(float), ds["V"].values.astype(float)
        self.last_z = z  # (n_w, n_V): what the image shows
        # cell edges half way between grid points (the grid may be non-uniform in V)
        dw = (w[-1] - w[0]) / max(len(w) - 1, 1) if len(w) > 1 else 1.0
        dv = (V[-1] - V[0]) / max(len(V) - 1, 1) if len(V) > 1 else 1.0
        up = Updates()
        # set, not Updates.data: the image column is a *list* of 2-D arrays (np.asarray would
        # stack it into one 3-D array, which BokehJS's image glyph rejects)
        up.set(self.src, data={"image": [np.ascontiguousarray(z.T)], "x": [w[0] - dw / 2],
                               "y": [V[0] - dv / 2], "dw": [dw * len(w)],
                               "dh": [dv * len(V)]})  # fmt: skip
        finite = z[np.isfinite(z)]
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

    def _cell_outline(self) -> dict:
        if self._cell is None or self._ds is None:
            return {"l": [], "r": [], "b": [], "t": []}
        w, V, dw, dv = self._cell_edges
        i, j = self._cell
        return {"l": [w[i] - dw / 2], "r": [w[i] + dw / 2], "b": [V[j] - dv / 2],
                "t": [V[j] + dv / 2]}  # fmt: skip

    @property
    def atlas_N(self) -> int | None:
        """The chain size the atlas's waves were computed at (None: not recorded)."""
        N = int(self._ds.attrs.get("N", -1)) if self._ds is not None else -1
        return N if N > 0 else None

    @property
    def dataset(self) -> xr.Dataset | None:
        """The atlas on screen (None before one is loaded or run)."""
        return self._ds

    def pick(self, x, y) -> bool:
        """Set the state to the grid point nearest to (x, y) = (w₊, V); False if none."""
        if x is None or y is None or self._ds is None:
            return False
        w, V = self._ds["w_plus"].values, self._ds["V"].values
        i, j = int(np.argmin(np.abs(w - x))), int(np.argmin(np.abs(V - y)))
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
        if self._ds is None:
            raise SceneMessage("nothing to download yet")
        ds = self._ds
        W, Vg = np.meshgrid(ds["w_plus"].values, ds["V"].values, indexing="ij")
        cols = {"w_plus": W.ravel(), "V": Vg.ravel()}
        for k in ("amplitude", "energy", "residual", "max_modulus", "max_modulus_error"):
            cols[k] = ds[k].values.ravel()
        return "atlas.csv", as_csv(cols, self.header() + "\n" + self.python_code())

    def header(self) -> str:
        """The download's header: the atlas's own parameters (its store attributes), not the
        sidebar's N and tol, which may differ."""
        a = self._ds.attrs
        keys = ("kind", "law", "params", "N", "tol", "floquet", "finite_size", "floquet_method",
                "m", "continuation", "fpucore_version", "created")  # fmt: skip
        lines = [f"atlas from {self._source}", f"fpu-explorer / fpucore {fpucore.__version__}"]
        lines += [f"{k}={a[k]!r}" for k in keys if k in a]
        return "\n".join(lines)

    def notebook_plot(self) -> str:
        name = "ds" if self._source and self._source != "background run" else "res.dataset"
        return f"{name}['amplitude'].plot(x='w_plus', y='V')\n"

    def python_code(self) -> str:
        if self._source and self._source != "background run":
            return python_preamble(self.state) + (
                f"import xarray as xr\nds = xr.open_zarr({self._source!r}, consolidated=False)\n"
            )
        return python_preamble(self.state) + (
            "from fpucore import atlas\n"
            f"res = atlas.run(law, 'solitary', rows='{self._rows}', V={int(self.n_V.value)}, "
            f"N={int(self.N_run.value)}, floquet=True, finite_size=False)\n"
            "print(res.dataset)\n"
        )
