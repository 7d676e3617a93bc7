"""The atlas on disk: an xarray Dataset in a Zarr store, written chunk by chunk.

Layout: dims (row_dim, "V") with row_dim "w_plus" (solitary) or "branch" (superkink); one
variable per field of :data:`fpucore.atlas.point.FIELDS` plus ``done`` (int8: 1 = the point's
final record is stored); Zarr chunks = the atlas chunks (1 × chunk), so every write of a chunk
touches its own files only.  Attributes: kind, law and params (a, b for the cubic), N, tol,
floquet, finite_size, m, chunk, continuation, the fpucore version and source hash,
created/updated times.

Crash safety.  Zarr's local store writes each file atomically (temporary file + rename).  A chunk
is written data first, ``done`` last: a client killed in between leaves ``done = 0`` and the
chunk is recomputed on resume — a half-written point is never read as valid.  A chunk any of
whose files cannot be read back (a damaged or truncated file: a decompression error) counts as
not done, is recomputed on resume and its files rewritten (:func:`load_records`).  A damaged
skeleton — a variable's metadata (``.zarray``), the attributes or a coordinate — cannot be
repaired from the chunks: resuming it is refused with one line saying what to do
(:func:`open_existing`).

Exclusive writer.  :class:`StoreLock` takes an ``fcntl`` lock on ``<store>.lock`` (pid and host
written inside): a second sweep on the same store is refused; the kernel releases the lock when
the holder dies (a killed client leaves a lock file that no longer locks anything; a finished
run removes it).  Local file systems only.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import socket
import tempfile
import time
import warnings
from importlib import metadata
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from fpucore.atlas.grid import Grid
from fpucore.atlas.point import FIELDS, ChunkTask
from fpucore.errors import ParameterError, import_extra
from fpucore.jit_cache import source_hash
from fpucore.law import CubicLaw
from fpucore.result import jsonable

if TYPE_CHECKING:
    import xarray as xr


def xarray_module():
    """xarray, imported on first use: with zarr and pandas it is ~0.4 s that every
    ``import fpucore`` (each CLI call, the server, each worker pool) would pay for stores only
    atlases and sweeps write."""
    return import_extra("xarray", "atlas", "an atlas store (Zarr)")


def zarr_module():
    """zarr, imported on first use (see :func:`xarray_module`)."""
    return import_extra("zarr", "atlas", "an atlas store (Zarr)")


# attributes that must match for a store to be resumed
IDENTITY = (
    "kind",
    "law",
    "params",
    "N",
    "tol",
    "floquet",
    "finite_size",
    "floquet_method",
    "m",
    "chunk",
    "continuation",
    "fpucore_source",
)


def fpucore_version() -> str:
    try:
        return metadata.version("fpu-explorer")
    except metadata.PackageNotFoundError:
        return "unknown"


def check_out(path: str | os.PathLike) -> Path:
    """Refuse a store path that cannot be written, before anything is computed: its directory
    must exist and take a new entry (tried: ``os.access`` says yes for root on ``/proc``)."""
    p = Path(path)
    if not p.parent.is_dir():
        raise ParameterError(
            "out", str(path), "a path in an existing directory", f"{p.parent} does not exist"
        )
    if p.exists() and not p.is_dir():
        raise ParameterError(
            "out", str(path), "a Zarr store (a directory) or a new path", "it is a file"
        )
    if not os.access(p.parent, os.W_OK):
        raise ParameterError("out", str(path), "a writable location")
    try:  # the store, its ".creating" twin and its ".lock" are all made in the parent
        os.rmdir(tempfile.mkdtemp(prefix=f".{p.name}.", suffix=".probe", dir=p.parent))
    except OSError as exc:
        raise ParameterError(
            "out",
            str(path),
            "a writable location",
            f"cannot create anything in {p.parent}: {exc.strerror or exc}",
        ) from None
    return p


class StoreLock:
    """Exclusive lock of one store for the lifetime of this object (see module doc).  The lock
    file is removed on release (no ``<store>.lock`` is left beside a finished store); a process
    that opened it just before is told by the inode check below and takes a fresh one."""

    def __init__(self, path: Path):
        self.path = path.with_name(path.name + ".lock")  # beside the store: not a Zarr node
        self._fd = -1
        for _ in range(100):  # each retry follows a release that removed the file under us
            if self._acquire(path):
                break
        else:  # pragma: no cover (100 releases in a row between our open and our lock)
            raise ParameterError(
                "out",
                str(path),
                "a store no other sweep is writing",
                "its lock file keeps being replaced",
            )
        os.ftruncate(self._fd, 0)
        os.pwrite(self._fd, f"pid {os.getpid()} on {socket.gethostname()}".encode(), 0)

    def _acquire(self, path: Path) -> bool:
        """Lock the file at self.path; False if it was removed (released) in between."""
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise ParameterError(
                "out",
                str(path),
                "a writable location",
                f"cannot create {self.path.name}: {exc.strerror or exc}",
            ) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 200, 0).decode(errors="replace").strip()
            os.close(fd)
            raise ParameterError(
                "out",
                str(path),
                "a store no other sweep is writing",
                f"locked by {holder or 'another process'}",
            ) from None
        try:
            same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if not same:  # the holder released (and removed) it between our open and our lock
            os.close(fd)
            return False
        self._fd = fd
        return True

    def release(self) -> None:
        if self._fd >= 0:
            try:  # removed while still locked: whoever opens it next sees a new inode
                os.unlink(self.path)
            except OSError:
                pass
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
    xr = xarray_module()
    return xr.Dataset(data, coords={grid.row_dim: skeleton_rows(grid), "V": grid.V}, attrs=attrs)


def identity_attrs(grid: Grid, task: ChunkTask) -> dict:
    """The store's attributes: everything that determines its records (see IDENTITY: the
    grid's and the run's task's), plus a and b for the cubic law."""
    law: Any = task.law  # every concrete law describes itself (describe())
    fl = task.floquet
    attrs = {
        "kind": grid.kind,
        "law": law.describe(),
        "params": [float(x) for x in law.params],
        "N": -1 if task.N is None else int(task.N),
        "tol": float(task.tol),
        "floquet": int(bool(fl.enabled)),
        "finite_size": int(bool(fl.finite_size)),
        "floquet_method": str(fl.method),
        "m": -1 if fl.m is None else int(fl.m),
        "chunk": int(grid.chunk),
        "continuation": int(bool(task.continuation)),
        "fpucore_source": source_hash(),
        "fpucore_version": fpucore_version(),
    }
    if isinstance(law, CubicLaw):
        attrs["a"], attrs["b"] = float(law.a), float(law.b)
    return attrs


def create(path: Path, ds: xr.Dataset, chunk: int) -> None:
    """Write the empty store ``ds`` (the run's own table: no second copy of the grid in memory)
    beside ``path`` and rename it into place (a client killed while creating leaves no
    half-made store behind).  chunk : points per Zarr chunk along V."""
    tmp = path.with_name(path.name + ".creating")
    shutil.rmtree(tmp, ignore_errors=True)
    ds = ds.copy(deep=False)
    ds.attrs = {**ds.attrs, "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    enc = {k: {"chunks": (1, chunk)} for k in ds.data_vars}
    # Zarr format 2: fixed-width unicode (status, message) is part of its spec (not yet of v3's)
    ds.to_zarr(tmp, mode="w", encoding=enc, consolidated=False, zarr_format=2)
    os.rename(tmp, path)


RESUME_ADVICE = (
    "move it aside (or delete it) and run again without --resume (resume=False), "
    "or choose a new --out"
)


def damaged(path: Path, what: str) -> ParameterError:
    """The refusal of a store whose skeleton (metadata, attributes, coordinates) is broken."""
    return ParameterError(
        "out",
        str(path),
        "an intact atlas store to resume",
        f"the store is damaged: {what}; {RESUME_ADVICE}",
    )


def open_existing(path: Path, grid: Grid, attrs: dict):
    """The stored Zarr group, after checking its skeleton is intact (every variable's metadata,
    the attributes, the coordinates) and that it is this grid with these parameters.  Damaged
    data chunks are not looked at here: :func:`load_records` recomputes them."""
    try:
        group = zarr_module().open_group(path, mode="r", zarr_format=2)
        stored = dict(group.attrs)
    except Exception as exc:  # noqa: BLE001  (whatever zarr raises: the store is unusable)
        raise damaged(path, f"not a readable Zarr group ({type(exc).__name__}: {exc})") from None
    if not stored:
        raise damaged(path, "its attributes (.zattrs) are missing")
    diff = [k for k in IDENTITY if jsonable(stored.get(k)) != jsonable(attrs[k])]
    if diff:
        what = ", ".join(f"{k}: stored {stored.get(k)!r} vs {attrs[k]!r}" for k in diff)
        raise ParameterError(
            "out", str(path), "a store of the same grid and parameters to resume", what
        )
    names = [*FIELDS, "done", grid.row_dim, "V"]
    with warnings.catch_warnings():  # zarr warns of each directory without metadata: said below
        warnings.simplefilter("ignore")
        present = set(group.array_keys())
    missing = [k for k in names if k not in present]
    if missing:
        raise damaged(path, f"variable(s) {', '.join(missing)} missing (no .zarray)")
    wrong = [k for k in [*FIELDS, "done"] if tuple(group[k].shape) != grid.shape]
    if wrong:
        raise damaged(path, f"variable(s) {', '.join(wrong)} not of the grid's shape")
    try:
        V, rows = group["V"][:], group[grid.row_dim][:]
    except Exception as exc:  # noqa: BLE001
        raise damaged(path, f"a coordinate is unreadable ({type(exc).__name__}: {exc})") from None
    same_grid = (
        len(rows) == len(grid.rows)
        and np.array_equal(np.asarray(V), grid.V)
        and [str(x) for x in rows] == [str(x) for x in skeleton_rows(grid)]
    )
    if not same_grid:
        raise ParameterError(
            "out",
            str(path),
            "a store of the same grid and parameters to resume",
            "the grid differs",
        )
    return group


def skeleton_rows(grid: Grid) -> np.ndarray:
    return np.array(grid.rows, dtype=float if grid.row_dim == "w_plus" else "<U8")


def done_of(arr, grid: Grid) -> np.ndarray:
    """(n_rows, n_V) bool from the ``done`` array: 1 = final record stored; a chunk that cannot
    be read counts as not done (it is recomputed)."""
    done = np.zeros(grid.shape, bool)
    for i, j0, j1 in grid.chunks():
        try:
            done[i, j0:j1] = np.asarray(arr[i, j0:j1]) == 1
        except Exception:  # noqa: BLE001  (a damaged chunk is recomputed)
            pass
    return done


def read_done(path: Path, grid: Grid) -> np.ndarray:
    """(n_rows, n_V) bool: points whose final record is stored (unreadable chunks: False)."""
    return done_of(zarr_module().open_array(path / "done", mode="r", zarr_format=2), grid)


READ_BLOCK = 16 * 2**20  # bytes of one field read at once while loading a store


def load_records(group, grid: Grid, cols: dict[str, np.ndarray]) -> np.ndarray:
    """Copy the stored records of the done points into ``cols`` (one array per field, the
    grid's shape, filled with the fields' fill values) and return the done mask.

    A point counts as done only if its ``done`` flag and every field of its chunk read back and
    its status is not empty (every record has one: an empty status is a lost data chunk).  A
    chunk failing any of these is left at its fill values and recomputed by the run; its files
    are rewritten whole, so the damage is repaired.  Fields are read in blocks of rows of at
    most :data:`READ_BLOCK` bytes (the transient memory of loading, whatever the grid)."""
    done = done_of(group["done"], grid)
    bad = np.zeros(grid.shape, bool)
    chunks = grid.chunks()
    for k in FIELDS:
        arr, col = group[k], cols[k]
        step = max(1, READ_BLOCK // max(1, col.itemsize * grid.shape[1]))
        for r0 in range(0, grid.shape[0], step):
            r1 = min(r0 + step, grid.shape[0])
            sel = done[r0:r1]
            if not sel.any():
                continue
            try:
                col[r0:r1][sel] = np.asarray(arr[r0:r1])[sel]
                continue
            except Exception:  # noqa: BLE001  (a damaged chunk in the block: chunk by chunk)
                pass
            for i, j0, j1 in chunks:
                if r0 <= i < r1 and done[i, j0:j1].any():
                    try:
                        pick = done[i, j0:j1]
                        col[i, j0:j1][pick] = np.asarray(arr[i, j0:j1])[pick]
                    except Exception:  # noqa: BLE001
                        bad[i, j0:j1] = True
    lost = done & (cols["status"] == "")  # a point's status is never empty once written
    if lost.any():
        for i, j0, j1 in chunks:
            if lost[i, j0:j1].any():
                bad[i, j0:j1] = True
    done &= ~bad
    for k, (_, fill) in FIELDS.items():  # chunks read only in part go back to "not computed"
        cols[k][bad] = fill
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
