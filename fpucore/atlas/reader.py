"""Reading an atlas back: :func:`open_atlas` (a Zarr store written by ``fpu atlas`` /
:func:`fpucore.atlas.run`) and :func:`atlas_data` (the Dataset of a run) give an
:class:`AtlasData` with typed fields, so a reader never spells the store's layout.

    data = atlas.open_atlas("atlas.zarr")
    data.w_plus, data.V          # the grid (solitary atlases; data.rows for any kind)
    data.max_modulus[data.ok]    # (rows, V) arrays of the store's fields

The layout (dims, one variable per field of :data:`fpucore.atlas.point.FIELDS`, ``done``, the
attributes) is :mod:`fpucore.atlas.store`'s; this module is its one reader.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from fpucore.atlas.point import FIELDS
from fpucore.atlas.store import IDENTITY, xarray_module
from fpucore.errors import ParameterError

if TYPE_CHECKING:
    import xarray as xr

#: point statuses (fpucore.atlas.point), in the order summaries list them
STATUSES = ("ok", "not_converged", "no_wave", "failed")
ROW_DIMS = {"w_plus": "solitary", "branch": "superkink"}
STORE = "an atlas store (a Zarr directory written by fpu atlas … --out)"


@dataclass(frozen=True)
class AtlasData:
    """An atlas as arrays of shape (rows, V).

    kind : "solitary" (rows are w₊ values) | "superkink" (rows are branch names).  rows, V :
    the grid.  status : each point's status (:data:`STATUSES`, "" = not computed); done : its
    final record is stored.  amplitude, energy, residual : the wave's; max_modulus and
    max_modulus_error : its Floquet spectrum's largest |μ| and that value's error bar (NaN
    without Floquet).  N : the chain size the waves were computed at (None: chosen per point).
    tol : the solves' tolerance; floquet : whether spectra were computed.  parameters : the
    store's attributes that determine its records (:data:`fpucore.atlas.store.IDENTITY`) and
    the cubic's a, b, in that order, plus the version and creation time.  path : the store
    (None for a run kept in memory).  dataset : the whole table (every field of
    :data:`~fpucore.atlas.point.FIELDS`), for anything not named here."""

    kind: str
    rows: np.ndarray
    V: np.ndarray
    status: np.ndarray
    done: np.ndarray
    amplitude: np.ndarray
    energy: np.ndarray
    residual: np.ndarray
    max_modulus: np.ndarray
    max_modulus_error: np.ndarray
    N: int | None
    tol: float
    floquet: bool
    parameters: dict
    path: str | None
    dataset: xr.Dataset

    @property
    def w_plus(self) -> np.ndarray:
        """The rows' w₊ (a solitary atlas; a superkink atlas has branches instead)."""
        if self.kind != "solitary":
            raise ParameterError(
                "kind",
                self.kind,
                "'solitary' (an atlas over (w₊, V))",
                "a superkink atlas is over V only",
            )
        return self.rows

    @property
    def ok(self) -> np.ndarray:
        """(rows, V) bool: the points with a converged wave (and spectrum, with Floquet)."""
        return self.status == "ok"

    @property
    def shape(self) -> tuple[int, int]:
        return self.status.shape

    def counts(self) -> dict[str, int]:
        """Points by status (:data:`STATUSES`; those not computed are not counted)."""
        return {s: int(np.sum(self.status == s)) for s in STATUSES}


def atlas_data(ds: xr.Dataset, path: str | os.PathLike | None = None) -> AtlasData:
    """The :class:`AtlasData` of an atlas Dataset (``AtlasResult.dataset``, or a store's).
    Raises ParameterError if it is not an atlas (a dimension or a field missing)."""
    name, where = ("dataset", "the Dataset") if path is None else ("path", str(path))
    row_dim = next((d for d in ROW_DIMS if d in ds.dims), None)
    if row_dim is None or "V" not in ds.dims:
        raise ParameterError(
            name, where, STORE, f"{where} has dimensions {tuple(ds.dims)}, not (w_plus | branch, V)"
        )
    missing = [k for k in [*FIELDS, "done"] if k not in ds.data_vars]
    if missing:
        raise ParameterError(name, where, STORE, f"{where} has no {', '.join(missing)}")
    order = (row_dim, "V")

    def values(name: str) -> np.ndarray:
        return np.asarray(ds[name].transpose(*order).values)

    rows = np.asarray(ds[row_dim].values)
    attrs = dict(ds.attrs)
    N = int(attrs.get("N", -1))
    keys = [*IDENTITY, "a", "b", "fpucore_version", "created", "updated"]
    return AtlasData(
        kind=ROW_DIMS[row_dim],
        rows=rows.astype(float) if row_dim == "w_plus" else rows.astype(str),
        V=np.asarray(ds["V"].values, float),
        status=values("status").astype(str),
        done=values("done") == 1,
        amplitude=values("amplitude").astype(float),
        energy=values("energy").astype(float),
        residual=values("residual").astype(float),
        max_modulus=values("max_modulus").astype(float),
        max_modulus_error=values("max_modulus_error").astype(float),
        N=N if N > 0 else None,
        tol=float(attrs.get("tol", np.nan)),
        floquet=bool(attrs.get("floquet", 0)),
        parameters={k: attrs[k] for k in keys if k in attrs},
        path=None if path is None else str(path),
        dataset=ds,
    )


def open_atlas(path: str | os.PathLike) -> AtlasData:
    """Read the atlas store at ``path`` whole (it is written chunk by chunk; points not yet
    computed have status "" and ``done`` False).  Raises ParameterError naming ``path`` if
    there is no store there or it cannot be read."""
    p = Path(path)
    if not p.is_dir():
        raise ParameterError("path", str(path), STORE, f"no atlas store at {p}")
    try:
        ds = xarray_module().open_zarr(p, consolidated=False).load()
    except Exception as exc:  # noqa: BLE001  (whatever xarray or zarr raise: unreadable)
        raise ParameterError(
            "path", str(path), STORE, f"cannot read {p}: {type(exc).__name__}: {exc}"
        ) from None
    return atlas_data(ds, p)
