"""Ctrl-C while `fpu warm` compiles: one line on stderr and exit 130 — no
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


def _grandchildren(pid: int) -> list[int]:
    """Pids of the children of ``pid``'s children (the pool's workers under its forkserver)."""
    out = []
    for child in _children(pid):
        out += _children(child)
    return out


def _children(pid: int) -> list[int]:
    out = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            if ppid == pid:
                out.append(int(d))
    return out


def test_ctrl_c_during_a_sweep_exits_130_with_one_line():
    """`fpu floquet sweep` computes in this process and a worker (Executor caller_runs): Ctrl-C
    once the worker runs gives one line and exit 130 — no "leaked semaphore" warning from the
    resource tracker (Numba's threading-layer lock in a terminated worker, fixed in
    fpucore/parallel/worker.py)."""
    p = subprocess.Popen(
        [sys.executable, "-m", "fpucore", "floquet", "sweep", "superkink", "--V-min", "4.9",
         "--V-max", "5.8", "--n", "12", "--N", "500", "--no-cache", "--no-progress",
         "--method", "dense"],  # the dense route: ~6 s, so the interrupt lands mid-sweep
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    t0 = time.monotonic()
    while not _grandchildren(p.pid) and time.monotonic() - t0 < 60 and p.poll() is None:
        time.sleep(0.05)
    time.sleep(2.0)  # the worker has started its threading layer and is computing
    assert p.poll() is None, "the sweep finished before it could be interrupted"
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, err)
    assert err.strip().splitlines() == ["fpu: interrupted"], err


def _maps(pid: int) -> str:
    try:
        with open(f"/proc/{pid}/maps") as f:
            return f.read()
    except OSError:
        return ""


def test_ctrl_c_while_the_package_imports_exits_130_with_one_line():
    """Ctrl-C in the first second of `fpu …`, while `import fpucore` runs (before main() can
    catch it): the same one line and exit 130, no KeyboardInterrupt traceback.  The signal is
    sent as soon as the child has mapped NumPy's extension (early in the import); should the
    import already be over, main() answers the same way."""
    interrupted = 0
    for _ in range(3):
        p = subprocess.Popen(
            [sys.executable, "-m", "fpucore", "qc", "--w-plus", "1"],  # imports NumPy as it runs
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        t0 = time.monotonic()
        while "_multiarray_umath" not in _maps(p.pid) and time.monotonic() - t0 < 30:
            if p.poll() is not None:
                break
            time.sleep(0.005)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
        if p.returncode == 0:  # finished before the signal: nothing to test this time
            continue
        interrupted += 1
        assert p.returncode == 130, (p.returncode, err)
        assert err.strip().splitlines() == ["fpu: interrupted"], err
    assert interrupted, "every run finished before the signal"


def _swallowing_callback():
    """A C callback (as Numba's cache writer, called through ctypes) in which Ctrl-C lands:
    Python prints the KeyboardInterrupt as "Exception ignored" and returns from the call."""
    import ctypes

    def cb():
        raise KeyboardInterrupt

    return ctypes.CFUNCTYPE(None)(cb)


def test_ctrl_c_swallowed_by_a_c_callback_still_interrupts(monkeypatch, capsys):
    """The CI run of the sweep test above: SIGINT arrived while Numba wrote its cache, the
    interrupt was swallowed and the sweep ran to its end with exit 0.  Now the interrupt is
    raised again at once: one line, exit 130."""
    from fpucore.cli import dispatch

    ran_on = []

    def command(args):
        _swallowing_callback()()
        time.sleep(5)  # the interrupt surfaces within the sleep
        ran_on.append(1)  # never reached
        return 0

    def parser():
        class P:
            def parse_args(self, argv):
                class A:
                    light = True
                    func = staticmethod(command)

                return A()

        return P()

    monkeypatch.setattr(dispatch, "build_parser", parser)
    assert dispatch.main([]) == 130
    assert capsys.readouterr().err.strip().splitlines() == ["fpu: interrupted"]
    assert not ran_on
    import sys

    assert sys.unraisablehook is not None  # restored (pytest's own, or Python's)
