"""Ctrl-C while `fpu warm` compiles (issue 14 item 7): one line on stderr and exit 130 — no
traceback from the parent or from the compiling worker processes."""

import os
import signal
import subprocess
import sys
import time


def test_ctrl_c_during_jit_compilation_exits_130_with_one_line(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))  # an empty cache: warm must compile
    p = subprocess.Popen(
        [sys.executable, "-m", "fpucore", "warm"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    time.sleep(8.0)  # past the imports, inside the compilation of the parallel groups
    assert p.poll() is None, "warm finished before it could be interrupted"
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, err)
    assert "Traceback" not in err, err
    assert err.strip().splitlines() == ["fpu: interrupted"], err
