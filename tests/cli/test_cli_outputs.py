"""Outputs of the ``fpu`` commands: a target that cannot be written is refused before the work
(one line, exit 2), a write that fails after the work is one line with exit 1 that says what was
kept, and no partial file is left behind (fpucore/cli/common.py: check_out_path, check_out_dir,
output_file)."""

from __future__ import annotations

import errno
import os
import subprocess
import sys

import pytest

from fpucore.cli.common import OutputError, check_out_dir, check_out_path, output_file
from fpucore.errors import ParameterError

UNWRITABLE = [  # each once gave a traceback (OSError ENOSPC, FileNotFoundError under /proc)
    ["floquet", "sweep", "superkink", "--V", "5.2", "--N", "64", "--no-cache", "--out",
     "/dev/full"],
    ["floquet", "sweep", "superkink", "--V", "5.2", "--N", "64", "--no-cache", "--out",
     "/proc/x.csv"],
    ["paper", "--figure", "pplane", "--out", "/proc/x.html"],
    ["paper", "--figure", "pplane", "--table", "/proc/x.md"],
    ["paper", "--figure", "pplane", "--thumbnails", "/proc"],
]  # fmt: skip


@pytest.mark.parametrize("argv", UNWRITABLE, ids=lambda a: " ".join(a[-2:]))
def test_unwritable_target_is_refused_before_the_work_in_one_line(argv, tmp_path):
    env = dict(os.environ, FPU_CACHE_DIR=str(tmp_path))
    p = subprocess.run([sys.executable, "-m", "fpucore", *argv], capture_output=True, text=True,
                       timeout=120, env=env)  # fmt: skip
    assert p.returncode == 2, (p.returncode, p.stderr)
    assert "Traceback" not in p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("fpu: error: "), p.stderr
    assert argv[-1] in lines[0]  # names the path as typed
    assert "fpu paper" not in p.stderr  # refused before the progress bar: no figure computed


def test_check_out_path_refuses_devices_kernel_fs_and_missing_dirs(tmp_path):
    for bad in ("/dev/full", "/dev/null", "/proc/x.csv", "/sys/x.json",
                str(tmp_path / "no" / "x.csv"), str(tmp_path)):  # fmt: skip
        with pytest.raises(ParameterError) as ei:
            check_out_path(bad)
        assert ei.value.name == "--out"
    check_out_path(str(tmp_path / "ok.csv"))  # a new file in a writable directory
    assert os.listdir(tmp_path) == []  # the probe leaves nothing


def test_check_out_dir_refuses_proc_and_files(tmp_path):
    (tmp_path / "f").write_text("x")
    for bad in ("/proc", str(tmp_path / "f"), str(tmp_path / "missing")):
        with pytest.raises(ParameterError):
            check_out_dir(bad, "--thumbnails")
    check_out_dir(str(tmp_path), "--thumbnails")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_check_out_path_refuses_a_read_only_directory(tmp_path):
    d = tmp_path / "ro"
    d.mkdir()
    d.chmod(0o500)
    try:
        with pytest.raises(ParameterError):
            check_out_path(str(d / "x.csv"))
    finally:
        d.chmod(0o700)


def test_output_file_replaces_atomically_and_keeps_the_mode(tmp_path):
    target = tmp_path / "t.csv"
    target.write_text("old")
    target.chmod(0o640)
    with output_file(target) as tmp:
        assert tmp.endswith(".csv") and os.path.dirname(tmp) == str(tmp_path)
        assert target.read_text() == "old"  # the old file stays until the new one is complete
        with open(tmp, "w") as fh:
            fh.write("new")
    assert target.read_text() == "new"
    assert oct(target.stat().st_mode & 0o777) == oct(0o640)
    assert sorted(os.listdir(tmp_path)) == ["t.csv"]


def test_disk_full_during_a_write_leaves_no_partial_file(tmp_path):
    target = tmp_path / "t.json"
    with pytest.raises(OutputError) as ei:
        with output_file(target, "--out", "the table was cached") as tmp:
            with open(tmp, "w") as fh:
                fh.write("{partial")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    msg = str(ei.value)
    assert "No space left on device" in msg and "the table was cached" in msg
    assert "\n" not in msg
    assert os.listdir(tmp_path) == []  # neither the target nor the temporary file


def test_paper_write_failure_after_the_work_is_one_line_exit_1(tmp_path, monkeypatch, capsys):
    """The figure is computed, then the disk fills while it is written: exit 1, one line that
    says the figures are cached, and no file (partial or not) in the directory."""
    from fpucore.cli import main
    from fpucore.paper import plot

    def full_disk(result, path):
        with open(path, "w") as fh:
            fh.write("<html>")  # a partial page, then the disk is full
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(plot, "save", full_disk)  # .svg / .png
    monkeypatch.setattr(
        plot, "report_html", lambda results, figures, path, *a, **k: full_disk(results, path)
    )  # .html: the figure with its comparison rows
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))
    out = tmp_path / "out"
    out.mkdir()
    rc = main(["paper", "--figure", "pplane", "--reduced", "--out", str(out / "p.html")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1
    assert err[-1].startswith("fpu: error: could not write --out") and "cached" in err[-1]
    assert os.listdir(out) == []
