"""The Numba cache directory is keyed by the package source (fpucore/jit_cache.py): a kernel that
inlines a jitted function from another module must not survive an edit of that module."""

import os
import shutil
from pathlib import Path

import numba

from fpucore import jit_cache


def test_cache_dir_is_keyed_by_the_package_source(monkeypatch, tmp_path):
    monkeypatch.setattr(numba.config, "CACHE_DIR", numba.config.CACHE_DIR)  # restored afterwards
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    keyed = jit_cache.key_cache_dir()
    assert keyed == os.path.join(str(tmp_path), f"fpucore-{jit_cache.source_hash()}")
    assert os.environ["NUMBA_CACHE_DIR"] == keyed
    assert numba.config.CACHE_DIR == keyed  # numba was imported first: its config follows
    assert jit_cache.key_cache_dir() == keyed  # idempotent (child processes inherit it)


def test_unset_cache_dir_is_left_alone(monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    assert jit_cache.key_cache_dir() is None
    assert "NUMBA_CACHE_DIR" not in os.environ


def test_an_edit_in_any_subpackage_changes_the_key(tmp_path):
    src = Path(jit_cache.__file__).parent
    pkg = tmp_path / "fpucore"
    shutil.copytree(src, pkg, ignore=shutil.ignore_patterns("__pycache__"))
    h0 = jit_cache.source_hash(pkg)
    assert h0 == jit_cache.source_hash()  # the copy hashes like the package
    for rel in ("simulate/observer.py", "law/kernels.py", "wave/period_map.py"):
        f = pkg / rel
        text = f.read_text()
        f.write_text(text + "\n# edit\n")
        assert jit_cache.source_hash(pkg) != h0, rel
        f.write_text(text)
    assert jit_cache.source_hash(pkg) == h0
