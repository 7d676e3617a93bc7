"""A missing optional dependency is one line naming the extra that installs it (exit 2), before
any work: the atlas extra (xarray, Zarr, Dask), the paper extra (figure files), the app extra
(fpu serve)."""

from __future__ import annotations

import sys

import pytest

from fpucore.cli import main
from fpucore.errors import MissingExtra, import_extra


def test_import_extra_names_the_extra_and_lets_other_import_errors_through(monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # as if not installed
    with pytest.raises(MissingExtra, match=r"pip install 'fpu-explorer\[atlas\]'"):
        import_extra("xarray", "atlas", "an atlas store (Zarr)")
    assert import_extra("json", "atlas", "x").dumps(1) == "1"


def test_atlas_store_without_the_atlas_extra(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "xarray", None)
    monkeypatch.setitem(sys.modules, "zarr", None)
    out = tmp_path / "a.zarr"
    rc = main(["atlas", "superkink", "--V", "5.2:5.3:2", "--N", "64", "--backend", "inline",
               "--out", str(out), "--no-progress"])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "fpu-explorer[atlas]" in err, err


def test_figure_file_without_the_paper_extra(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "holoviews", None)
    rc = main(["paper", "--figure", "pplane", "--reduced", "--out", str(tmp_path / "p.svg")])
    err = capsys.readouterr().err
    assert rc == 2 and "fpu-explorer[paper]" in err and "Traceback" not in err, err


def test_serve_without_the_app_extra(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "panel", None)
    assert main(["serve", "--port", "5999"]) == 2
    err = capsys.readouterr().err
    assert (
        err == "fpu: error: fpu serve needs panel, which is not installed: "
        "pip install 'fpu-explorer[app]'\n"
    )
