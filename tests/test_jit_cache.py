"""The Numba cache directory is keyed by the package source (fpucore/_jit_cache.py): a kernel that
inlines a jitted function from another module must not survive an edit of that module."""

import os

import numba

from fpucore import _jit_cache


def test_cache_dir_is_keyed_by_the_package_source(monkeypatch, tmp_path):
    monkeypatch.setattr(numba.config, "CACHE_DIR", numba.config.CACHE_DIR)  # restored afterwards
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    keyed = _jit_cache.key_cache_dir()
    assert keyed == os.path.join(str(tmp_path), f"fpucore-{_jit_cache.source_hash()}")
    assert os.environ["NUMBA_CACHE_DIR"] == keyed
    assert numba.config.CACHE_DIR == keyed  # numba was imported first: its config follows
    assert _jit_cache.key_cache_dir() == keyed  # idempotent (child processes inherit it)


def test_unset_cache_dir_is_left_alone(monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    assert _jit_cache.key_cache_dir() is None
    assert "NUMBA_CACHE_DIR" not in os.environ


def test_source_hash_covers_every_module():
    files = sorted(p.name for p in _jit_cache.Path(_jit_cache.__file__).parent.glob("*.py"))
    assert {"chain_kernels.py", "chain_rkn.py", "law.py"} <= set(files)
    assert len(_jit_cache.source_hash()) == 12
