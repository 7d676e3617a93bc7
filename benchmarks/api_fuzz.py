"""Fuzz of the public API's numeric parameters: every entry point of :data:`ENTRY_POINTS` is
called with valid small arguments except one numeric parameter, which takes each value of
:data:`BAD` in turn (huge Python ints, NaN, ±inf, None, strings, sequences, bools, zero,
negatives, extremes of double precision).  The standard: a result or a ``ParameterError`` —
anything else (OverflowError, TypeError, ZeroDivisionError, LinAlgError, ...) is counted.

    python -m benchmarks.api_fuzz            # the count and each escaping exception
    python -m benchmarks.api_fuzz --quiet    # the count only

The corpus is fixed (no randomness): the same calls on every run and every version, so counts
compare.  Valid arguments are small (N = 32, L = 20, short times) so that a bad value accepted
by mistake does little work.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from collections import Counter

BIG_INT = 10**400  # float(BIG_INT): OverflowError
BAD = [BIG_INT, -BIG_INT, 10**20, math.nan, math.inf, -math.inf, None, "5", "x", [1.0], (),
       {"a": 1}, True, 1j, 0, -1, 0.0, -1e-300, 1e308, -1e308, 5e-324]  # fmt: skip


def entry_points():
    """[(name, fn, kwargs of valid values, names of the numeric parameters)]."""
    import numpy as np

    import fpucore as F
    from fpucore import atlas, floquet, qc, simulate, wave
    from fpucore.qc import diagram, phase

    law = F.CubicLaw(-1.0, 10.0)
    poly = F.PolynomialLaw((1.0, 10.0, -1.0))
    r = wave.solve_superkink(law, 5.2, N=64)
    mat = np.eye(8)
    E = [
        ("CubicLaw", F.CubicLaw, dict(a=-1.0, b=10.0), ["a", "b"]),
        ("PolynomialLaw", lambda c1, c2, c3: F.PolynomialLaw((c1, c2, c3)),
         dict(c1=1.0, c2=10.0, c3=-1.0), ["c1", "c2", "c3"]),
        ("PolynomialLaw(coeffs)", F.PolynomialLaw, dict(coeffs=(1.0, 10.0, -1.0)), ["coeffs"]),
        ("law_from_expression", F.law_from_expression, dict(expression="w+10*w**2-w**3"),
         ["expression"]),
        ("law.require_convex", lambda w: law.require_convex("w", w), dict(w=1.0), ["w"]),
        ("qc.sound_speeds", qc.sound_speeds, dict(law=law, w_plus=1.0), ["w_plus"]),
        ("qc.sound_speeds poly", qc.sound_speeds, dict(law=poly, w_plus=1.0), ["w_plus"]),
        ("qc.superkink_from_w_plus", qc.superkink_from_w_plus, dict(law=law, w_plus=1.0),
         ["w_plus"]),
        ("qc.superkink_from_w_plus poly", qc.superkink_from_w_plus, dict(law=poly, w_plus=1.0),
         ["w_plus"]),
        ("qc.superkink_from_V", qc.superkink_from_V, dict(law=law, V=5.2), ["V"]),
        ("qc.superkink_from_V poly", qc.superkink_from_V, dict(law=poly, V=5.2), ["V"]),
        ("qc.solitary", qc.solitary, dict(law=law, w_plus=1.0, V=5.0), ["w_plus", "V"]),
        ("qc.solitary poly", qc.solitary, dict(law=poly, w_plus=1.0, V=5.0), ["w_plus", "V"]),
        ("qc.solitary_intervals", qc.solitary_intervals, dict(law=law, w_plus=1.0), ["w_plus"]),
        ("qc.w_minus_sonic", qc.w_minus_sonic, dict(law=law, w_plus=1.0), ["w_plus"]),
        ("qc.rayleigh_roots", qc.rayleigh_roots, dict(law=law, w_plus=1.0, V=5.0),
         ["w_plus", "V"]),
        ("qc.rayleigh_roots poly", qc.rayleigh_roots, dict(law=poly, w_plus=1.0, V=5.0),
         ["w_plus", "V"]),
        ("qc.w_S", qc.w_S, dict(law=law, w_plus=1.0, V=5.0), ["w_plus", "V"]),
        ("qc.first_integral", qc.first_integral, dict(law=law, w=1.0, wp=0.1, w_ref=1.0, V=5.0),
         ["w", "wp", "w_ref", "V"]),
        ("qc.solitary_closed_form", qc.solitary_closed_form, dict(law=law, w_B=1.0, V=5.0),
         ["w_B", "V"]),
        ("qc.sound_speed_plus", qc.sound_speed_plus, dict(law=law, w_plus=1.0), ["w_plus"]),
        ("qc.require_V", qc.require_V, dict(V=5.0), ["V"]),
        ("qc.superkink_w_plus_range", qc.superkink_w_plus_range, dict(law=law), []),
        ("diagram.existence_diagram", diagram.existence_diagram, dict(law=law, n=20), ["n"]),
        ("diagram.solitary_family", diagram.solitary_family, dict(law=law, w_plus=1.0, n=20),
         ["w_plus", "n"]),
        ("diagram.classify", diagram.classify, dict(law=law, w_plus=1.0, V=5.0),
         ["w_plus", "V"]),
        ("phase.phase_plane", phase.phase_plane,
         dict(law=law, w_plus=1.0, V=5.0, n_grid=21, n_orbit=21, sk_tol=1e-9),
         ["w_plus", "V", "n_grid", "n_orbit", "sk_tol"]),
        ("phase.critical_points", phase.critical_points, dict(law=law, w_plus=1.0, V=5.0),
         ["w_plus", "V"]),
        ("wave.solve_superkink", wave.solve_superkink,
         dict(law=law, V=5.2, N=64, tol=1e-10, max_iter=20, time_budget_s=10.0),
         ["V", "N", "tol", "max_iter", "time_budget_s"]),
        ("wave.solve_solitary", wave.solve_solitary,
         dict(law=law, w_plus=1.0, V=5.0, N=64, tol=1e-10, max_iter=20, time_budget_s=10.0),
         ["w_plus", "V", "N", "tol", "max_iter", "time_budget_s"]),
        ("wave.superkink_family", wave.superkink_family,
         dict(law=law, V_values=[5.2], N=64, tol=1e-10), ["V_values", "N", "tol"]),
        ("wave.solitary_family", wave.solitary_family,
         dict(law=law, w_plus=1.0, V_values=[5.0], N=64, tol=1e-10),
         ["w_plus", "V_values", "N", "tol"]),
        ("wave.strain_scale", wave.strain_scale, dict(w_left=1.0, w_right=2.0),
         ["w_left", "w_right"]),
        ("wave.superkink_spec", wave.superkink_spec, dict(law=law, V=5.2, branch="lower"), ["V"]),
        ("wave.solitary_spec", wave.solitary_spec, dict(law=law, w_plus=1.0, V=5.0),
         ["w_plus", "V"]),
        ("floquet.homogeneous_multipliers", floquet.homogeneous_multipliers,
         dict(law=law, w0=1.0, V=5.0, N=16), ["w0", "V", "N"]),
        ("floquet.phonon_gap", floquet.phonon_gap, dict(law=law, w_bg=1.0, V=5.0, N=16),
         ["w_bg", "V", "N"]),
        ("floquet.chain_lengths", floquet.chain_lengths, dict(N=64, n_min=8), ["N", "n_min"]),
        ("floquet.default_steps", floquet.default_steps, dict(law=law, V=5.0), ["V"]),
        ("floquet.monodromy", floquet.monodromy, dict(r=r, m=None), ["m"]),
        ("floquet.spectrum", floquet.spectrum,
         dict(r=r, m=None, trivial_radius=None, finite_size=False), ["m", "trivial_radius"]),
        ("floquet.multipliers_of", floquet.multipliers_of, dict(mat=mat, n=4), ["n"]),
        ("floquet.energy_criterion", floquet.energy_criterion,
         dict(law=law, w_plus=1.0, V_values=[4.4, 4.6], N=64, tol=1e-10, qc_samples=20),
         ["w_plus", "V_values", "N", "tol", "qc_samples"]),
        ("simulate.riemann", simulate.riemann,
         dict(law=law, w_left=1.0, w_right=0.0, L=20, t_end=1.0, rtol=1e-8, n_snapshots=5,
              max_sites_out=20, n_probe_t=11, time_budget_s=10.0),
         ["w_left", "w_right", "L", "t_end", "rtol", "n_snapshots", "max_sites_out",
          "n_probe_t", "time_budget_s"]),
        ("simulate.gaussian", simulate.gaussian,
         dict(law=law, w_B=0.0, A=0.5, L=20, t_end=1.0, rtol=1e-8, n_snapshots=5,
              max_sites_out=20, n_probe_t=11, time_budget_s=10.0),
         ["w_B", "A", "L", "t_end", "rtol", "n_snapshots", "max_sites_out", "n_probe_t",
          "time_budget_s"]),
        ("simulate.seeded", simulate.seeded,
         dict(r=r, L=None, t_end=0.5, n_snapshots=5, max_sites_out=20, time_budget_s=10.0),
         ["L", "t_end", "n_snapshots", "max_sites_out", "time_budget_s"]),
        ("simulate.work_estimate", simulate.work_estimate,
         dict(law=law, L=100, t_end=1.0, method="rkn12", rtol=1e-10, dt=0.02),
         ["L", "t_end", "rtol", "dt"]),
        ("simulate.whole_periods", simulate.whole_periods, dict(t_end=10.0, T=0.2),
         ["t_end", "T"]),
        ("atlas.make_grid", atlas.make_grid,
         dict(law=law, kind="superkink", rows="lower", V="5.0:5.3:3", chunk=2), ["V", "chunk"]),
        ("atlas.parse_values", atlas.parse_values, dict(name="V", spec="5:6:3"), ["spec"]),
        ("atlas.run", atlas.run,
         dict(law=law, kind="superkink", rows="lower", V="5.1:5.2:2", N=64, tol=1e-10,
              chunk=2, time_budget_s=10.0, backend="inline", workers=None),
         ["V", "N", "tol", "chunk", "time_budget_s", "workers"]),
        ("atlas.sweep", atlas.sweep,
         dict(law=law, kind="superkink", V_values=[5.2], N=64, tol=1e-10, use_cache=False,
              time_budget_s=10.0),
         ["V_values", "N", "tol", "time_budget_s"]),
    ]  # fmt: skip
    return E


def run(quiet: bool = False) -> tuple[int, int, Counter]:
    """(calls, escapes, escapes by exception type)."""
    from fpucore.errors import ParameterError

    n, escapes, kinds = 0, 0, Counter()
    for name, fn, kw, params in entry_points():
        for p in params:
            for bad in BAD:
                n += 1
                args = {**kw, p: bad}
                t0 = time.perf_counter()
                try:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        fn(**args)
                except ParameterError:
                    pass
                except Exception as exc:  # noqa: BLE001  (what is counted)
                    escapes += 1
                    kinds[type(exc).__name__] += 1
                    if not quiet:
                        text = str(exc).splitlines()[0][:110] if str(exc) else ""
                        print(f"{name}({p}={bad!r:.30}): {type(exc).__name__}: {text}")
                dt = time.perf_counter() - t0
                if dt > 20 and not quiet:
                    print(f"  slow: {name}({p}={bad!r:.30}) took {dt:.0f} s")
    return n, escapes, kinds


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    n, escapes, kinds = run(args.quiet)
    print(f"{escapes} of {n} calls raised something other than ParameterError "
          f"({dict(kinds)}) in {time.perf_counter() - t0:.0f} s")  # fmt: skip
    return 0 if escapes == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
