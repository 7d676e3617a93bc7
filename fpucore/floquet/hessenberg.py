"""Eigenvalues of an upper Hessenberg matrix by LAPACK ``dhseqr`` directly (the structured route's
H is Hessenberg already; ``scipy.linalg.eigvals`` would balance and re-reduce it, ~25 % more).

scipy exposes ``dhseqr`` only in ``scipy.linalg.cython_lapack``; its function pointer is taken from
the module's C-API capsule and called through ctypes (Fortran calling convention: every argument
by reference).
"""

from __future__ import annotations

import ctypes

import numpy as np
from scipy.linalg import cython_lapack

_p_int = ctypes.POINTER(ctypes.c_int)
_p_dbl = ctypes.POINTER(ctypes.c_double)
_PROTO = ctypes.CFUNCTYPE(
    None, ctypes.c_char_p, ctypes.c_char_p, _p_int, _p_int, _p_int, _p_dbl, _p_int,
    _p_dbl, _p_dbl, _p_dbl, _p_int, _p_dbl, _p_int, _p_int,
)  # fmt: skip


def _lapack(name: str):
    cap = cython_lapack.__pyx_capi__[name]
    get_name = ctypes.pythonapi.PyCapsule_GetName
    get_name.restype, get_name.argtypes = ctypes.c_char_p, [ctypes.py_object]
    get_ptr = ctypes.pythonapi.PyCapsule_GetPointer
    get_ptr.restype, get_ptr.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
    return _PROTO(get_ptr(cap, get_name(cap)))


_DHSEQR = _lapack("dhseqr")


def hessenberg_eigvals(h: np.ndarray) -> np.ndarray:
    """All eigenvalues of the upper Hessenberg matrix h (n×n float64; entries below the first
    subdiagonal are ignored; h is overwritten).  Raises ArithmeticError if QR does not converge."""
    n = h.shape[0]
    a = np.asfortranarray(h, dtype=np.float64)
    wr, wi = np.empty(n), np.empty(n)
    z = np.empty(1)
    ci = lambda v: ctypes.byref(ctypes.c_int(v))  # noqa: E731
    info = ctypes.c_int(0)
    dp = lambda x: x.ctypes.data_as(_p_dbl)  # noqa: E731
    work_q = np.empty(1)
    _DHSEQR(b"E", b"N", ci(n), ci(1), ci(n), dp(a), ci(n), dp(wr), dp(wi), dp(z), ci(1),
            dp(work_q), ci(-1), ctypes.byref(info))  # fmt: skip
    work = np.empty(max(int(work_q[0]), n))
    _DHSEQR(b"E", b"N", ci(n), ci(1), ci(n), dp(a), ci(n), dp(wr), dp(wi), dp(z), ci(1),
            dp(work), ci(work.size), ctypes.byref(info))  # fmt: skip
    if info.value != 0:
        raise ArithmeticError(f"dhseqr failed: info = {info.value}")
    return wr + 1j * wi
