"""The atlas on disk: an xarray Dataset in a Zarr store, written chunk by chunk.

Layout: dims (row_dim, "V") with row_dim "w_plus" (solitary) or "branch" (superkink); one
variable per field of :data:`fpucore.atlas.point.FIELDS` plus ``done`` (int8: 1 = the point's
final record is stored); Zarr chunks = the atlas chunks (1 × chunk), so every write of a chunk
touches its own files only.  Attributes: kind, law and params (a, b for the cubic), N, tol,
floquet, finite_size, m, chunk, continuation, the fpucore version and source hash,
created/updated times.

Crash safety.  Zarr's local store writes each file atomically (temporary file + rename).  A chunk
is written data first, ``done`` last: a client killed in between leaves ``done = 0`` and the
chunk is recomputed on resume — a half-written point is never read as valid.  Unreadable
``done`` files count as not done.

Exclusive writer.  :class:`StoreLock` takes an ``fcntl`` lock on ``<store>.lock`` (pid and host
written inside): a second sweep on the same store is refused; the kernel releases the lock when
the holder dies (a killed client leaves no stale lock).  Local file systems only.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import socket
import time
from importlib import metadata
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from fpucore.atlas.grid import Grid
from fpucore.atlas.point import FIELDS
from fpucore.errors import ParameterError
from fpucore.jit_cache import source_hash
from fpucore.law import CubicLaw

if TYPE_CHECKING:
    import xarray as xr


def xarray_module():
    """xarray, imported on first use: with zarr and pandas it is ~0.4 s that every
    ``import fpucore`` (each CLI call, the server, each worker pool) would pay for stores only
    atlases and sweeps write."""
    import xarray

    return xarray


def zarr_module():
    """zarr, imported on first use (see :func:`xarray_module`)."""
    import zarr

    return zarr


# attributes that must match for a store to be resumed
IDENTITY = ("kind", "law", "params", "N", "tol", "floquet", "finite_size", "floquet_method", "m",
            "chunk", "continuation", "fpucore_source")  # fmt: skip


def fpucore_version() -> str:
    try:
        return metadata.version("fpu-explorer")
    except metadata.PackageNotFoundError:
        return "unknown"


def check_out(path: str | os.PathLike) -> Path:
    """Refuse a store path that cannot be written, before anything is computed."""
    p = Path(path)
    if not p.parent.is_dir():
        raise ParameterError("out", str(path), "a path in an existing directory",
                             f"{p.parent} does not exist")  # fmt: skip
    if p.exists() and not p.is_dir():
        raise ParameterError("out", str(path), "a Zarr store (a directory) or a new path",
                             "it is a file")  # fmt: skip
    if not os.access(p.parent, os.W_OK):
        raise ParameterError("out", str(path), "a writable location")
    return p


class StoreLock:
    """Exclusive lock of one store for the lifetime of this object (see module doc)."""

    def __init__(self, path: Path):
        self.path = path.with_name(path.name + ".lock")  # beside the store: not a Zarr node
        self._fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(self._fd, 200, 0).decode(errors="replace").strip()
            os.close(self._fd)
            self._fd = -1
            raise ParameterError("out", str(path), "a store no other sweep is writing",
                                 f"locked by {holder or 'another process'}") from None  # fmt: skip
        os.ftruncate(self._fd, 0)
        os.pwrite(self._fd, f"pid {os.getpid()} on {socket.gethostname()}".encode(), 0)

    def release(self) -> None:
        if self._fd >= 0:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
            os.close(self._fd)
            self._fd = -1

    def __enter__(self) -> StoreLock:
        return self

    def __exit__(self, *exc) -> None:
        self.release()


def skeleton(grid: Grid, attrs: dict) -> xr.Dataset:
    """The Dataset of a grid with every point not computed."""
    dims = (grid.row_dim, "V")
    data = {k: (dims, np.full(grid.shape, fill, dtype=dt)) for k, (dt, fill) in FIELDS.items()}
    data["done"] = (dims, np.zeros(grid.shape, np.int8))
    rows = np.array(grid.rows, dtype=float if grid.row_dim == "w_plus" else "<U8")
    xr = xarray_module()
    return xr.Dataset(data, coords={grid.row_dim: rows, "V": grid.V}, attrs=attrs)


def identity_attrs(grid: Grid, law, N, tol: float, floquet: bool, finite_size: bool, m,
                   continuation: bool, floquet_method: str = "dense") -> dict:  # fmt: skip
    """The store's attributes: everything that determines its records (see IDENTITY), plus a
    and b for the cubic law."""
    attrs = {
        "kind": grid.kind, "law": law.describe(), "params": [float(x) for x in law.params],
        "N": -1 if N is None else int(N), "tol": float(tol), "floquet": int(bool(floquet)),
        "finite_size": int(bool(finite_size)), "floquet_method": str(floquet_method),
        "m": -1 if m is None else int(m),
        "chunk": int(grid.chunk), "continuation": int(bool(continuation)),
        "fpucore_source": source_hash(), "fpucore_version": fpucore_version(),
    }  # fmt: skip
    if isinstance(law, CubicLaw):
        attrs["a"], attrs["b"] = float(law.a), float(law.b)
    return attrs


def create(path: Path, grid: Grid, attrs: dict) -> None:
    """Write the empty store beside ``path`` and rename it into place (a client killed while
    creating leaves no half-made store behind)."""
    tmp = path.with_name(path.name + ".creating")
    shutil.rmtree(tmp, ignore_errors=True)
    ds = skeleton(grid, {**attrs, "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())})
    enc = {k: {"chunks": (1, grid.chunk)} for k in ds.data_vars}
    # Zarr format 2: fixed-width unicode (status, message) is part of its spec (not yet of v3's)
    ds.to_zarr(tmp, mode="w", encoding=enc, consolidated=False, zarr_format=2)
    os.rename(tmp, path)


def open_existing(path: Path, grid: Grid, attrs: dict) -> xr.Dataset:
    """The stored Dataset, after checking it is this grid with these parameters."""
    try:
        ds = xarray_module().open_zarr(path, consolidated=False)
    except Exception as exc:  # noqa: BLE001
        raise ParameterError("out", str(path), "an atlas store", f"cannot open: {exc}") from None
    diff = [k for k in IDENTITY if _plain(ds.attrs.get(k)) != _plain(attrs[k])]
    same_grid = (
        grid.row_dim in ds.dims and ds.sizes.get(grid.row_dim) == len(grid.rows)
        and ds.sizes.get("V") == grid.V.size and np.array_equal(ds["V"].values, grid.V)
        and [str(x) for x in ds[grid.row_dim].values] == [str(x) for x in skeleton_rows(grid)]
    )  # fmt: skip
    if diff or not same_grid:
        what = ", ".join(f"{k}: stored {ds.attrs.get(k)!r} vs {attrs[k]!r}" for k in diff)
        raise ParameterError("out", str(path), "a store of the same grid and parameters to "
                             "resume", what or "the grid differs")  # fmt: skip
    return ds


def _plain(v):
    return list(v) if isinstance(v, (list, tuple)) else v


def skeleton_rows(grid: Grid) -> np.ndarray:
    return np.array(grid.rows, dtype=float if grid.row_dim == "w_plus" else "<U8")


def read_done(path: Path, grid: Grid) -> np.ndarray:
    """(n_rows, n_V) bool: points whose final record is stored (unreadable chunks: False)."""
    arr = zarr_module().open_array(path / "done", mode="r", zarr_format=2)
    done = np.zeros(grid.shape, bool)
    for i, j0, j1 in grid.chunks():
        try:
            done[i, j0:j1] = np.asarray(arr[i, j0:j1]) == 1
        except Exception:  # noqa: BLE001  (a damaged chunk is recomputed)
            pass
    return done


class Writer:
    """Writes chunks of records into an open store (data first, then ``done``)."""

    def __init__(self, path: Path):
        self.path = path
        self.group = zarr_module().open_group(path, mode="r+", zarr_format=2)
        self.arrays = {k: self.group[k] for k in [*FIELDS, "done"]}

    def write(self, i: int, j0: int, j1: int, records: list[dict], final: bool = True) -> None:
        for k, (dt, _) in FIELDS.items():
            self.arrays[k][i, j0:j1] = np.array([r[k] for r in records], dtype=dt)
        self.arrays["done"][i, j0:j1] = np.full(j1 - j0, 1 if final else 0, np.int8)

    def touch(self) -> None:
        self.group.attrs["updated"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
