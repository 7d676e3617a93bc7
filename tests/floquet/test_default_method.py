"""One default Floquet method for every entry point: ``floquet.spectrum``, ``atlas.run``, the
sweep (and its cache key and checks), the atlas store's identity and every ``fpu`` command that
computes spectra take :data:`fpucore.floquet.DEFAULT_METHOD`; ``fpu atlas --method`` chooses
another and a bad one is refused in one line."""

from __future__ import annotations

import inspect
import subprocess
import sys

import pytest
import xarray as xr

from fpucore import atlas, floquet
from fpucore.atlas import sweeps
from fpucore.cli import build_parser, choices

D = floquet.DEFAULT_METHOD


def _default(fn, name: str):
    return inspect.signature(fn).parameters[name].default


def test_the_api_entry_points_share_the_default():
    assert D in floquet.METHODS
    assert _default(floquet.spectrum, "method") == D
    assert _default(atlas.run, "floquet_method") == D
    assert _default(atlas.sweep, "method") == D
    assert _default(sweeps.cache_key, "method") == D
    assert _default(sweeps.check_sweep_args, "method") == D
    assert atlas.FloquetOptions().method == D  # the atlas's task, and so its store's identity


@pytest.mark.parametrize("argv", [
    ["floquet", "superkink", "--V", "5.2"],
    ["floquet", "solitary", "--w-plus", "1", "--V", "5.0"],
    ["floquet", "sweep", "superkink", "--V", "5.2"],
    ["atlas", "superkink", "--out", "x.zarr"],
    ["atlas", "solitary", "--w-plus", "1", "--out", "x.zarr"],
])  # fmt: skip
def test_every_command_defaults_to_it(argv):
    assert choices.DEFAULT_FLOQUET_METHOD == D  # the parser's copy (no NumPy at --help)
    assert build_parser().parse_args(argv).method == D


CLI = [sys.executable, "-m", "fpucore", "atlas", "superkink", "--V", "5.5:5.6:2", "--N", "64",
       "--floquet", "--no-finite-size", "--chunk", "2", "--workers", "1",
       "--no-progress"]  # fmt: skip


def test_fpu_atlas_method_is_used_and_stored(tmp_path):
    other = next(m for m in floquet.METHODS if m != D)
    out = tmp_path / "a.zarr"
    r = subprocess.run([*CLI, "--method", other, "--out", str(out)], capture_output=True,
                       text=True, timeout=300)  # fmt: skip
    assert r.returncode == 0, r.stderr
    ds = xr.open_zarr(out, consolidated=False)
    assert ds.attrs["floquet_method"] == other and bool((ds["status"].values == "ok").all())


def test_fpu_atlas_refuses_a_bad_method_in_one_line(tmp_path):
    out = tmp_path / "b.zarr"
    r = subprocess.run([*CLI, "--method", "eig", "--out", str(out)], capture_output=True,
                       text=True, timeout=60)  # fmt: skip
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert lines[0].startswith("fpu: error:") and "--method" in lines[0] and "'eig'" in lines[0]
    assert all(repr(m) in lines[0] for m in floquet.METHODS)
    assert not out.exists()
