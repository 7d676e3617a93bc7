"""Scene "Atlas" — heat maps over the existence diagram (w₊, V) from an atlas store
(:mod:`fpucore.atlas`), or from a small atlas run in the background through the execution layer
(:class:`fpucore.parallel.Executor`, one process per core, one BLAS thread each).

Quantities: max |μ| − 1 (log scale of the excess; needs Floquet), amplitude, E_ren^D.  Cells
without a wave (outside the existence region, or not converged) are blank; the counts by status
and the largest error bars are shown next to the plot.  A click on a cell sets (w₊, V) to that
cell's point (``ExplorerState.pick``); the Profiles / Floquet tabs then show that wave.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import panel as pn
import xarray as xr
from bokeh.events import Tap
from bokeh.models import ColorBar, ColumnDataSource, LinearColorMapper

from fpucore import atlas
from fpucore.errors import ParameterError

from .base import Info, SceneMessage, as_csv, md_literal, provenance, python_preamble
from .bokeh_scene import BokehScene, Updates, new_figure

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
        "cell to open that wave. Paper: Figs. 8, 9 and 14 (one line of this map each)._"
    )
    depends = ("a", "b", "expression")
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
        fig.on_event(Tap, lambda ev: self.pick(ev.x, ev.y))
        return fig

    def controls(self):
        self.store = pn.widgets.TextInput(name="atlas store (Zarr)", placeholder="atlas.zarr",
                                          width=280)  # fmt: skip
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
        self.last_z: np.ndarray | None = None

        def go(_):
            self._want_run = True
            self.request()

        self.run_btn.on_click(go)
        self.store.param.watch(lambda _: self.request(), "value")
        self.quantity.param.watch(lambda _: self.request(), "value")

    # ------------------------------------------------------------------ data
    def load(self, path: str) -> xr.Dataset:
        p = Path(path).expanduser()
        if not p.is_dir():
            raise SceneMessage(f"no atlas store at {path}")
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
        res = atlas.run(law, "solitary", rows=rows, V=int(self.n_V.value),
                        N=int(self.N_run.value), floquet=True, finite_size=False,
                        progress=lambda d, n, f: self.set_progress(d, n))  # fmt: skip
        info.time(f"atlas run ({res.n_computed} points, {res.workers} {res.backend} workers)",
                  res.elapsed_s)  # fmt: skip
        return res.dataset

    # ------------------------------------------------------------------ render
    def render(self, info: Info):
        if self._want_run:
            self._want_run = False
            self._ds, self._source = self.run_small(info), "background run"
        elif self.store.value:
            self._ds, self._source = self.load(self.store.value), self.store.value
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
        return up

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
        try:
            self.state.pick(float(w[i]), float(V[j]))
        except ParameterError:
            return False
        return True

    def download_data(self):
        if self._ds is None:
            raise SceneMessage("nothing to download yet")
        ds = self._ds
        W, Vg = np.meshgrid(ds["w_plus"].values, ds["V"].values, indexing="ij")
        cols = {"w_plus": W.ravel(), "V": Vg.ravel()}
        for k in ("amplitude", "energy", "residual", "max_modulus", "max_modulus_error"):
            cols[k] = ds[k].values.ravel()
        hdr = provenance(self.state, f"atlas from {self._source}")
        return "atlas.csv", as_csv(cols, hdr + "\n" + self.python_code())

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
