"""Work–precision of the discrete traveling-wave solver (paper §5, eqs. nonlin_system, Eren_D).

Waves (a = −1, b = 10): the superkink at V = 5.2 (error: profile max_n |w_n − w_n^ref|) and the
tensile solitary wave w₊ = 1, V = 5.0 (errors: amplitude |w_amp − w_amp^ref| and renormalized
energy |E_ren^D − E^ref|).  Two panels:

* "traveling wave: m, Jacobian, baseline" — RK steps per period m at fixed N (N = 64 for the
  superkink, the automatic N for the solitary wave).  Reference: the same N, m_ref = 8 × the
  largest m of the grid, Newton to round-off.  Curves: fpucore's exact banded Jacobian, the
  paper's finite-difference Jacobian (``jacobian="fd"``, dense LU), and the SciPy baseline of
  :func:`benchmarks.bench_wave.baseline_scipy` (solve_ivp DOP853 rtol = 1e-12 + forward-FD
  Jacobian + dense solve) over its Newton tolerance, all at N = 64, measured in this run.
* "traveling wave: chain length N" — N at m = 48 for wider waves (superkink V = 5.75 near the
  upper bound, near-sonic solitary wave w₊ = 1, V = 4.3); reference at 4 × the largest N.
  Energy errors are relative, |ΔE|/|E_ref|; references iterate Newton to round-off.

Times: the whole solve from the QC guess (period integrations, Jacobians, LU), best of 3, warm
JIT.  Floors: one period integration and one banded LU of the exact Jacobian at the same N.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

from fpucore import wave
from fpucore.law import CubicLaw
from fpucore.wave.system import newton

from .bench_wave import baseline_scipy
from .wp_common import Floor, Row, best_time

ROUTE_M = "traveling wave: m, Jacobian, baseline"
ROUTE_N = "traveling wave: chain length N"
LAW = CubicLaw(-1.0, 10.0)
V_SK_CASE, N_SMALL = 5.2, 64  # superkink; N where the SciPy baseline is affordable
W_PLUS_SW, V_SW = 1.0, 5.0  # tensile solitary wave below V_SK = 2√65/3
# N panel: wider waves, so that truncation by N is visible (superkink near V_hi; near-sonic wave)
V_BY_PANEL = {"m": {"superkink": V_SK_CASE, "solitary": V_SW},
              "N": {"superkink": 5.75, "solitary": 4.3}}  # fmt: skip
REF_TOL = 1e-15  # references: Newton until it stagnates at round-off


def _spec(kind: str, V: float):
    if kind == "superkink":
        return wave.superkink_spec(LAW, V, "lower")
    return wave.solitary_spec(LAW, W_PLUS_SW, V)


def _fixed_m(kind, V, N, m, jacobian="exact", tol=1e-12):
    """Newton from the QC guess with a fixed step count m (the solver picks m by step doubling;
    here m is the work–precision knob).  Returns (w, wdot, reached tol)."""
    sp = _spec(kind, V)
    scale = max(1.0, abs(sp.w_left), abs(sp.w_right))
    x0 = sp.qc_guess(N)
    K = sp.choose_K(x0, max(m, 8))
    o = newton(sp.system(N, m, K), x0, tol * scale, 40, jacobian, 120.0)
    return o.x[0::2], o.x[1::2], o.converged


def _metrics(kind: str, V: float, w: np.ndarray, wd: np.ndarray) -> dict:
    sp = _spec(kind, V)
    N = w.size
    out = {"w": w, "N": N}
    if kind != "superkink":
        out["amplitude"] = abs(w[N // 2] - sp.w_left)
        out["energy"] = wave.renormalized_energy(LAW, w, wd, sp.V, sp.w_left, sp.w_right, sp.w_left)
    return out


def _profile_err(w: np.ndarray, w_ref: np.ndarray) -> float:
    """max |w_n − w_n^ref| over the sites n = −N/2 … N/2−1 of the shorter chain."""
    N, Nr = w.size, w_ref.size
    lo = Nr // 2 - N // 2
    return float(np.max(np.abs(w - w_ref[lo : lo + N])))


def _errors(kind: str, got: dict, ref: dict) -> dict:
    e = {"profile": _profile_err(got["w"], ref["w"])}
    if kind != "superkink":
        e["amplitude"] = abs(got["amplitude"] - ref["amplitude"])
        e["energy"] = abs(got["energy"] - ref["energy"]) / abs(ref["energy"])  # relative
    return e


def _rows_for(route, label, setting, kind, errs, sec, note):
    if kind == "superkink":
        return [Row(route, f"{label}: superkink profile", setting, errs["profile"], sec, note)]
    return [
        Row(route, f"{label}: solitary amplitude", setting, errs["amplitude"], sec, note),
        Row(route, f"{label}: solitary energy (rel.)", setting, errs["energy"], sec, note),
    ]


def _m_panel(quick: bool) -> list[Row]:
    rows: list[Row] = []
    reps = 2 if quick else 3
    ms = (4, 6, 8, 12) if quick else (4, 5, 6, 8, 10, 12, 16, 24)
    m_ref = 8 * ms[-1]
    N_sw = wave.solve_solitary(LAW, W_PLUS_SW, V_SW).N  # automatic N of the solitary wave
    for kind, N in (("superkink", N_SMALL), ("solitary", N_sw)):
        V = V_BY_PANEL["m"][kind]
        ref = _metrics(kind, V, *_fixed_m(kind, V, N, m_ref, tol=REF_TOL)[:2])
        for jac, label, grid in (
            ("exact", "fpucore exact Jacobian", ms),
            ("fd", "fpucore FD Jacobian (paper)", ms[1::2]),
        ):
            for m in grid:
                w, wd, ok = _fixed_m(kind, V, N, m, jac)
                sec = best_time(
                    lambda k=kind, V=V, N=N, m=m, jac=jac: _fixed_m(k, V, N, m, jac), repeat=reps
                )
                errs = _errors(kind, _metrics(kind, V, w, wd), ref)
                note = f"V={V}; N={N}; ref m={m_ref}" + ("" if ok else "; Newton NOT converged")
                rows += _rows_for(ROUTE_M, label, f"m={m}", kind, errs, sec, note)
    # the SciPy baseline (adaptive DOP853, rtol = 1e-12) on the superkink at the same N
    ref = _metrics("superkink", V_SK_CASE, *_fixed_m("superkink", V_SK_CASE, N_SMALL, m_ref,
                                                      tol=REF_TOL)[:2])  # fmt: skip
    for tol in (1e-6,) if quick else (1e-6, 1e-9, 1e-11):
        sec, hist, xb = baseline_scipy(V=V_SK_CASE, N=N_SMALL, tol=tol)
        err = _profile_err(xb[:N_SMALL], ref["w"])
        rows.append(
            Row(ROUTE_M, "scipy solve_ivp DOP853 + FD Jacobian: superkink profile",
                f"Newton tol={tol:g}", err, sec,
                f"N={N_SMALL}; {len(hist) - 1} Newton steps; single timing")
        )  # fmt: skip
    return rows


def _n_panel(quick: bool) -> list[Row]:
    rows: list[Row] = []
    reps = 2 if quick else 3
    m = 48
    grids = {
        "superkink": (40, 80, 120) if quick else (32, 48, 64, 80, 96, 120, 160, 200),
        "solitary": (40, 80, 120) if quick else (32, 48, 64, 80, 96, 120, 160, 200),
    }
    for kind, Ns in grids.items():
        V = V_BY_PANEL["N"][kind]
        N_ref = 4 * Ns[-1]
        ref = _metrics(kind, V, *_fixed_m(kind, V, N_ref, m, tol=REF_TOL)[:2])
        for N in Ns:
            w, wd, ok = _fixed_m(kind, V, N, m)
            sec = best_time(lambda k=kind, V=V, N=N: _fixed_m(k, V, N, m), repeat=reps)
            errs = _errors(kind, _metrics(kind, V, w, wd), ref)
            note = f"V={V}; m={m}; ref N={N_ref}" + ("" if ok else "; Newton NOT converged")
            rows += _rows_for(ROUTE_N, "fpucore exact Jacobian", f"N={N}", kind, errs, sec, note)
    return rows


def _floors(N: int, route: str) -> list[Floor]:
    """One period integration (m = 12) and one banded LU of the exact Jacobian, same N."""
    sp = _spec("superkink", V_SK_CASE)
    x = sp.qc_guess(N)
    S = sp.system(N, 12, sp.choose_K(x, 12))
    t_int = best_time(lambda: S.integrate(x), min_time=0.1)
    ab, kl, ku, *_ = S.jacobian_banded(x)
    t_lu = best_time(lambda: lapack.dgbtrf(ab, kl, ku), min_time=0.1)
    return [
        Floor(route, f"one period integration (DOP853, m = 12) at N = {N}", t_int),
        Floor(route, f"one banded LU (kl = {kl}, ku = {ku}) at N = {N}", t_lu),
    ]


def study(quick: bool = False) -> tuple[list[Row], list[Floor]]:
    wave.warm(LAW)
    rows = _m_panel(quick) + _n_panel(quick)
    floors = _floors(N_SMALL, ROUTE_M) + _floors(120, ROUTE_N)
    return rows, floors
