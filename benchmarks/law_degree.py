"""How high a polynomial degree do the solvers handle accurately?  (The parser's MAX_DEGREE.)

Family of hardening–softening laws with known convex interval, of any degree n = m + 3:

    f′(w) = (1 + 20 w − 3 w²) · T_m(s w / R),   T_m(x) = Σ_{j ≤ m} x^j / j!  (m even: T_m > 0)

so α, β are the roots of 1 + 20w − 3w² (the paper's cubic a = −1, b = 10) at every degree, and
the degree-n terms are genuine (s = −1: alternating coefficients, cancellation ~e^{β/R} in the
monomial basis).  The float coefficients c_k define the law exactly; the references are that
law's β, w* and QC superkink w₋ computed with mpmath at 50 digits (a second, independent method).
For each degree: relative errors of β, w*, w₋ and whether each stays within the error bar the
code reports; the discrete solitary wave's and its Floquet spectrum's convergence and run time.

    python benchmarks/law_degree.py [--degrees 3,5,9,13,17,21,25,33] [--R 1.0]
"""

from __future__ import annotations

import argparse
import math
import time

import mpmath as mp

from fpucore import floquet, qc, wave
from fpucore.law import PolynomialLaw, polynomial

polynomial.MAX_DEGREE = 1000  # measure beyond the limit this script sets

mp.mp.dps = 50


def coeffs(m: int, R: float, s: int) -> tuple[float, ...]:
    """(c_1, …, c_{m+3}) of f with f′ = (1 + 20w − 3w²) T_m(s w/R), f(0) = 0."""
    t = [mp.mpf(s) ** j / (mp.factorial(j) * mp.mpf(R) ** j) for j in range(m + 1)]
    q = [mp.mpf(1), mp.mpf(20), mp.mpf(-3)]
    d = [mp.mpf(0)] * (m + 3)
    for i, qi in enumerate(q):
        for j, tj in enumerate(t):
            d[i + j] += qi * tj
    return tuple(float(dk / (k + 1)) for k, dk in enumerate(d))  # c_{k+1} = d_k/(k+1)


def horner(c, w, der=0):
    acc = mp.mpf(0)
    for k in range(len(c), 0, -1):  # Σ c_k w^k and its derivatives, exactly in mpmath
        if k < der:
            break
        fac = mp.mpf(1)
        for j in range(der):
            fac *= k - j
        acc += mp.mpf(c[k - 1]) * fac * mp.mpf(w) ** (k - der)
    return acc


def measure(n: int, R: float, s: int) -> dict:
    c = coeffs(n - 3, R, s)
    t0 = time.perf_counter()
    law = PolynomialLaw(c)
    t_law = time.perf_counter() - t0
    beta = mp.findroot(lambda w: horner(c, w, 1), law.beta)
    wstar = mp.findroot(lambda w: horner(c, w, 2), law.w_star)
    out = {
        "n": n,
        "beta_rel": float(abs(law.beta - beta) / beta),
        "beta_in_bar": bool(abs(law.beta - beta) <= law.beta_error),
        "wstar_rel": float(abs(law.w_star - wstar) / wstar),
        "wstar_in_bar": bool(abs(law.w_star - wstar) <= law.w_star_error),
        "t_law_ms": 1e3 * t_law,
    }
    lo, hi = qc.superkink_w_plus_range(law, "lower")
    w_plus = lo + 0.5 * (hi - lo)
    t0 = time.perf_counter()
    sk = qc.superkink_from_w_plus(law, w_plus)
    out["t_qc_ms"] = 1e3 * (time.perf_counter() - t0)

    def G(wm):  # eq. zero_G with exact Φ: Φ(w₋) − Φ(w₊) − ½(f₊ + f₋)(w₋ − w₊)
        def phi(w):
            return sum(mp.mpf(ck) * mp.mpf(w) ** (k + 1) / (k + 1) for k, ck in enumerate(c, 1))

        return phi(wm) - phi(w_plus) - (horner(c, w_plus) + horner(c, wm)) / 2 * (wm - w_plus)

    wm = mp.findroot(G, sk.w_minus)
    out["wminus_rel"] = float(abs(sk.w_minus - wm) / abs(wm))
    out["wminus_in_bar"] = bool(abs(sk.w_minus - wm) <= sk.w_minus_error)
    cp, vsk, _cm = qc.sound_speeds(law, w_plus)
    V = cp + 0.5 * (vsk - cp)
    t0 = time.perf_counter()
    r = wave.solve_solitary(law, w_plus, V)
    out["t_wave_s"] = time.perf_counter() - t0
    out["wave_ok"] = bool(r.converged)
    out["wave_residual"] = float(r.residual)
    t0 = time.perf_counter()
    fl = floquet.spectrum(r, finite_size=False)
    out["t_floquet_s"] = time.perf_counter() - t0
    out["floquet_ok"] = bool(fl.converged)
    out["floquet_err"] = float(fl.error)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--degrees", default="3,5,9,13,17,21,25,33")
    ap.add_argument("--R", type=float, default=1.0)
    ap.add_argument("--sign", type=int, default=-1)
    args = ap.parse_args()
    for n in (int(x) for x in args.degrees.split(",")):
        try:
            d = measure(n, args.R, args.sign)
        except Exception as exc:  # report and go on: the point is where it breaks
            print(f"n={n}: {type(exc).__name__}: ...{str(exc)[-200:]}", flush=True)
            continue
        print(" ".join(f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}"
                       for k, v in d.items()), flush=True)  # fmt: skip
        if not math.isfinite(d["beta_rel"]):
            break


if __name__ == "__main__":
    main()
