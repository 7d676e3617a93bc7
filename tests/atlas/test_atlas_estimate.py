"""``fpu atlas`` says what it will cost before it starts (point count, measured cost per point,
estimated wall time on stderr), refuses a ``--time-budget`` below the estimate before the store
exists, keeps every finished chunk on Ctrl-C, and leaves no ``<store>.lock`` behind."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time

import numpy as np

from fpucore.atlas.estimate import duration
from fpucore.atlas.store import StoreLock

BASE = [sys.executable, "-m", "fpucore", "atlas", "superkink", "--N", "64", "--chunk", "1"]
ESTIMATE = re.compile(r"^fpu: (\d+) points.*; estimate ([0-9.e+-]+) s per point .* = about ",
                      re.MULTILINE)  # fmt: skip


def _run(args, **kw):
    return subprocess.run([*BASE, *args], capture_output=True, text=True, timeout=300, **kw)


def test_estimate_before_the_work_and_no_lock_left(tmp_path):
    out = tmp_path / "a.zarr"
    p = _run(["--V", "5.0:5.3:6", "--workers", "1", "--out", str(out)])
    assert p.returncode == 0, p.stderr
    m = ESTIMATE.search(p.stderr)
    assert m, p.stderr
    assert int(m.group(1)) == 6 and float(m.group(2)) > 0
    # the estimate comes before the progress bar (before any chunk is computed)
    assert p.stderr.index("estimate") < p.stderr.find("atlas superkink") or "atlas superkink" \
        not in p.stderr  # fmt: skip
    assert out.is_dir()
    assert not (tmp_path / "a.zarr.lock").exists()  # released and removed after success
    assert sorted(os.listdir(tmp_path)) == ["a.zarr"]


def test_a_budget_below_the_estimate_is_refused_before_the_store(tmp_path):
    out = tmp_path / "big.zarr"
    p = _run(["--V", "5.0:5.3:100000", "--out", str(out), "--time-budget", "60"])
    assert p.returncode == 2, p.stderr
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("fpu: error: time_budget_s=60 ") and "estimated" in last
    assert "100000 points" in last and "--resume" in last
    assert "Traceback" not in p.stderr
    assert os.listdir(tmp_path) == []  # no store, no lock, no probe left


def test_ctrl_c_keeps_the_finished_chunks_and_resume_completes(tmp_path):
    out = tmp_path / "c.zarr"
    args = ["--V", "5.0:5.3:60", "--backend", "inline", "--no-progress", "--out", str(out)]
    p = subprocess.Popen([*BASE, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)  # fmt: skip
    import zarr

    def n_saved() -> int:  # chunks saved so far (the store may be between two writes)
        try:
            return int((np.asarray(zarr.open_array(out / "done", mode="r", zarr_format=2)[:])
                        == 1).sum())  # fmt: skip
        except Exception:
            return 0

    # interrupted as soon as two chunks are saved (not after a fixed sleep: on a quiet machine
    # with a warm JIT cache the 60 points take ~3 s, and a signal at the very end races the exit)
    t0 = time.monotonic()
    while n_saved() < 2 and time.monotonic() - t0 < 120 and p.poll() is None:
        time.sleep(0.05)
    assert p.poll() is None, "the atlas finished before it could be interrupted"
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "Traceback" not in err and "--resume" in err

    done = np.asarray(zarr.open_array(out / "done", mode="r", zarr_format=2)[:]) == 1
    n_kept = int(done.sum())
    assert 0 < n_kept < 60, n_kept
    assert not (tmp_path / "c.zarr.lock").exists()
    r = _run([*args, "--resume", "--json"])
    assert r.returncode == 0, r.stderr
    assert f'"n_loaded": {n_kept}' in r.stdout and '"n_pending": 0' in r.stdout
    assert re.search(rf"60 points, {60 - n_kept} to do", r.stderr), r.stderr


def test_the_lock_file_goes_with_its_release_and_a_new_lock_is_fresh(tmp_path):
    store = tmp_path / "s.zarr"
    lock = StoreLock(store)
    assert (tmp_path / "s.zarr.lock").exists()
    lock.release()
    assert not (tmp_path / "s.zarr.lock").exists()
    with StoreLock(store):
        assert (tmp_path / "s.zarr.lock").read_text().startswith(f"pid {os.getpid()}")
    assert not (tmp_path / "s.zarr.lock").exists()


def test_duration_words():
    assert [duration(s) for s in (42, 210, 3 * 3600, 5 * 86400)] == [
        "42 s", "3.5 min", "3.0 h", "5.0 days"]  # fmt: skip
