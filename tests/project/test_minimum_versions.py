"""The declared ranges are true: pyproject.toml's core dependencies at their lower bounds
(requirements/minimum.txt) install on this Python into a fresh virtual environment, and a fast
subset of the suite passes there.  Slow (the install): kept in the suite, listed by ``-m slow``.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MINIMUM = ROOT / "requirements" / "minimum.txt"
LOCK = ROOT / "requirements" / "lock.txt"
# core only (no Panel, no atlas extra): the QC closed forms, laws, discrete waves (Numba kernels
# compiled by the oldest Numba) through the CLI
SUBSET = ["tests/qc/test_qc.py", "tests/law/test_law_range.py", "tests/cli/test_cli_wave.py"]
TOOLS = ("pytest", "hypothesis")  # the test runner itself, at the lock's versions
pytestmark = pytest.mark.slow


def _pins(path: Path) -> dict[str, str]:
    return _pins_text(path.read_text())


def _lower_bounds() -> dict[str, str]:
    doc = tomllib.loads((ROOT / "pyproject.toml").read_text())
    bounds = {}
    for req in doc["project"]["dependencies"]:
        m = re.match(r"^([A-Za-z0-9_.\-]+)\s*>=\s*([^,;\s]+)", req)
        assert m, f"{req}: a core dependency without a lower bound"
        bounds[m.group(1).lower()] = m.group(2)
    return bounds


def test_minimum_txt_is_pyprojects_lower_bounds():
    pins = _pins(MINIMUM)
    assert set(pins) == set(_lower_bounds())
    for name, low in _lower_bounds().items():
        assert pins[name].split(".")[: len(low.split("."))] == low.split("."), (name, pins[name])


def test_suite_subset_passes_at_the_lower_bounds():
    # not under pytest's basetemp, which other pytest sessions prune during a long install
    tmp_path = Path(tempfile.mkdtemp(prefix="fpu-minimum-"))
    try:
        _install_and_run(tmp_path)
    finally:
        shutil.rmtree(tmp_path, ignore_errors=True)


def _install_and_run(tmp_path: Path) -> None:
    t = time.monotonic()
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = str(venv / "bin" / "python")
    lock = _pins(LOCK)
    tools = [f"{name}=={lock[name]}" for name in TOOLS]
    deps = list(_lower_bounds())
    p = subprocess.run([py, "-m", "pip", "install", "-q", "-c", str(MINIMUM), *deps, *tools],
                       capture_output=True, text=True, timeout=1800)  # fmt: skip
    assert p.returncode == 0, p.stderr[-3000:]
    installed = subprocess.run([py, "-m", "pip", "freeze"], capture_output=True, text=True).stdout
    got = {k: v for k, v in _pins_text(installed).items() if k in _pins(MINIMUM)}
    assert got == _pins(MINIMUM)  # the lower bounds themselves, not newer releases
    t_install = time.monotonic() - t
    # the repository's fpucore (first on the path: -m pytest from the root) on those versions
    env = {"PATH": "/usr/bin:/bin", "NUMBA_CACHE_DIR": str(tmp_path / "numba_cache"),
           "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1",
           "HOME": str(tmp_path)}  # fmt: skip
    p = subprocess.run([py, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", *SUBSET],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)  # fmt: skip
    assert p.returncode == 0, p.stdout[-4000:] + p.stderr[-2000:]
    print(f"\n[minimum] install {t_install:.0f} s, subset {time.monotonic() - t - t_install:.0f}"
          f" s: {p.stdout.strip().splitlines()[-1]}")  # fmt: skip


def _pins_text(text: str) -> dict[str, str]:
    out = {}
    for line in text.splitlines():
        m = re.match(r"^([A-Za-z0-9_.\-]+)==(\S+)", line.strip())
        if m:
            out[m.group(1).lower().replace("_", "-")] = m.group(2)
    return out
