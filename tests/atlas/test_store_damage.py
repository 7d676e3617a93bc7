"""A damaged atlas store: a data or ``done`` chunk that cannot be read back (garbled, truncated,
lost) is recomputed on resume and its files rewritten, the other points loaded; a damaged
skeleton (a variable's ``.zarray``, the attributes, a coordinate) is refused in one line that
names the store and says what to do — never a traceback, never a half-loaded table.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from fpucore import atlas
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
# four points of one row, one chunk each: every chunk is solved cold, so a recomputed point is
# bit-identical to the first computation (same process, same thread count)
KW = dict(rows=[1.0], V="4.4:5.3:4", N=64, chunk=1, backend="inline")
CLI = [sys.executable, "-m", "fpucore", "atlas", "solitary", "--w-plus", "1", "--V", "4.4:5.3:4",
       "--N", "64", "--chunk", "1", "--backend", "inline", "--no-progress"]  # fmt: skip
T = 300  # s: generous for a cold Numba cache; a hang fails here instead of never


@pytest.fixture(scope="module")
def pristine(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("store") / "a.zarr"
    res = atlas.run(LAW, "solitary", out=out, **KW)
    assert res.n_ok == 4
    return out


def copy_of(pristine: Path, tmp_path: Path) -> Path:
    out = tmp_path / "a.zarr"
    shutil.copytree(pristine, out)
    return out


def records(path: Path) -> xr.Dataset:
    return xr.open_zarr(path, consolidated=False).load()


def same(a: xr.Dataset, b: xr.Dataset) -> None:
    for k in ("status", "message", "N", "iterations", "done"):
        assert np.array_equal(a[k].values, b[k].values), k
    for k in ("amplitude", "energy", "residual"):
        assert np.array_equal(a[k].values, b[k].values, equal_nan=True), k


def test_damaged_chunks_are_recomputed_and_rewritten(pristine, tmp_path):
    out = copy_of(pristine, tmp_path)
    (out / "amplitude" / "0.1").write_bytes(b"garbage, not blosc")  # decompression error
    blob = (out / "message" / "0.2").read_bytes()
    (out / "message" / "0.2").write_bytes(blob[: len(blob) // 2])  # truncated
    (out / "done" / "0.3").write_bytes(b"\x00" * 7)  # the done flag itself
    res = atlas.run(LAW, "solitary", out=out, resume=True, **KW)
    assert (res.n_loaded, res.n_computed, res.n_ok, res.n_pending) == (1, 3, 4, 0)
    same(records(out), records(pristine))  # repaired: every file reads back, equal records
    again = atlas.run(LAW, "solitary", out=out, resume=True, **KW)
    assert (again.n_loaded, again.n_computed) == (4, 0)


def test_a_lost_status_chunk_is_recomputed(pristine, tmp_path):
    out = copy_of(pristine, tmp_path)
    (out / "status" / "0.2").unlink()  # reads back as the fill value "": not a stored record
    res = atlas.run(LAW, "solitary", out=out, resume=True, **KW)
    assert (res.n_loaded, res.n_computed, res.n_ok) == (3, 1, 4)
    same(records(out), records(pristine))


def test_cli_resume_recomputes_a_damaged_chunk(pristine, tmp_path):
    out = copy_of(pristine, tmp_path)
    (out / "energy" / "0.0").write_bytes(b"\x01\x02\x03")
    r = subprocess.run([*CLI, "--out", str(out), "--resume", "--json"], capture_output=True,
                       text=True, timeout=T)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert '"n_loaded": 3' in r.stdout and '"n_computed": 1' in r.stdout
    same(records(out), records(pristine))


SKELETON = {
    "a variable's metadata": lambda p: (p / "amplitude" / ".zarray").unlink(),
    "the done flags' metadata": lambda p: (p / "done" / ".zarray").unlink(),
    "the attributes": lambda p: (p / ".zattrs").unlink(),
    "the group": lambda p: (p / ".zgroup").unlink(),
    "a coordinate's chunk": lambda p: (p / "V" / "0").write_bytes(b"garbage"),
    "a variable's shape": lambda p: (p / "energy" / ".zarray").write_text(
        (p / "energy" / ".zarray").read_text().replace("4\n", "5\n", 1)
    ),
}


@pytest.mark.parametrize("what", list(SKELETON))
def test_damaged_skeleton_is_refused_in_one_line(pristine, tmp_path, what):
    out = copy_of(pristine, tmp_path)
    SKELETON[what](out)
    with pytest.raises(ParameterError, match="damaged") as info:
        atlas.run(LAW, "solitary", out=out, resume=True, **KW)
    assert info.value.name == "out" and "without --resume" in str(info.value)
    r = subprocess.run([*CLI, "--out", str(out), "--resume"], capture_output=True, text=True,
                       timeout=T)  # fmt: skip
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"fpu: error: out='{out}'"), r.stderr
    assert "damaged" in lines[0] and "without --resume" in lines[0]
