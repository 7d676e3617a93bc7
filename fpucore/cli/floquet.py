"""``fpu floquet``: Floquet multipliers of discrete superkinks / solitary waves (paper §6).

fpu floquet superkink --V 5.2 [--N 500] [--branch lower] [--json]
fpu floquet solitary --w-plus 1 --V 5.0 [--N 500] [--json]
fpu floquet sweep superkink --V-min 4.8 --V-max 5.85 --n 22 [--N 300 500] [--out t.csv]
fpu floquet sweep solitary --w-plus 6 --V 4.0 4.5 5.0 [--out t.json]
"""

from __future__ import annotations

import argparse
import json
import sys

from fpucore.cli.choices import DEFAULT_FLOQUET_METHOD, FLOQUET_METHODS, METHOD_HELP
from fpucore.cli.common import (
    add_law_args,
    jsonable,
    law_fields,
    law_from_args,
    output_file,
    print_json,
)
from fpucore.errors import ParameterError


def register(sub) -> None:
    p = sub.add_parser("floquet", help="Floquet multipliers of discrete traveling waves (§6)")
    fs = p.add_subparsers(dest="floquet_command", required=True, parser_class=type(p))

    for name in ("superkink", "solitary"):
        q = fs.add_parser(name, help=f"spectrum of one discrete {name} (max |mu|, quartets)")
        add_law_args(q)
        if name == "solitary":
            q.add_argument("--w-plus", type=float, required=True, help="state ahead (w_+)")
        else:
            q.add_argument("--branch", choices=("lower", "upper"), default="lower")
        q.add_argument("--V", type=float, required=True, help="velocity V > 0")
        q.add_argument("--N", type=int, default=500, help="chain size (even; default 500)")
        q.add_argument("--m", type=int, default=None, help="RK steps per period (default auto)")
        q.add_argument(
            "--no-finite-size",
            action="store_true",
            help="skip the finite-size test (spectra on 5 shorter rings in [N/2, N]); an excess "
            "is then undetermined",
        )
        q.add_argument(
            "--method", choices=FLOQUET_METHODS, default=DEFAULT_FLOQUET_METHOD, help=METHOD_HELP
        )
        q.add_argument("--json", action="store_true", help="print one JSON object")
        q.set_defaults(func=run_one, kind=name)

    s = fs.add_parser("sweep", help="max |mu| against V along a family (cached, progress bar)")
    s.add_argument("kind", choices=("superkink", "solitary"))
    add_law_args(s)
    s.add_argument("--w-plus", type=float, default=None, help="state ahead (solitary waves)")
    s.add_argument("--branch", choices=("lower", "upper"), default="lower")
    s.add_argument("--V", type=float, nargs="+", default=None, help="explicit velocities")
    s.add_argument("--V-min", type=float, default=None)
    s.add_argument("--V-max", type=float, default=None)
    s.add_argument("--n", type=int, default=12, help="number of velocities in [V-min, V-max]")
    s.add_argument("--N", type=int, nargs="+", default=[500], help="chain size(s), one sweep each")
    s.add_argument("--out", default=None, help="write the table to this .csv or .json file")
    s.add_argument(
        "--method", choices=FLOQUET_METHODS, default=DEFAULT_FLOQUET_METHOD, help=METHOD_HELP
    )
    s.add_argument("--no-cache", action="store_true", help="ignore and do not write the cache")
    s.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    s.add_argument("--json", action="store_true", help="print the table as one JSON object")
    s.set_defaults(func=run_sweep)


def _wave(args, law):
    from fpucore import wave  # heavy: Numba

    if args.kind == "superkink":
        return wave.solve_superkink(law, args.V, branch=args.branch, N=args.N)
    return wave.solve_solitary(law, args.w_plus, args.V, N=args.N)


def _check_N(N: int) -> None:
    if N < 8 or N % 2:
        raise ParameterError("N", N, "an even integer >= 8")


def run_one(args) -> int:
    import numpy as np  # heavy: NumPy

    from fpucore import floquet  # heavy: Numba

    _check_N(args.N)
    law = law_from_args(args)
    r = _wave(args, law)
    if not r.converged:
        raise ParameterError(
            "V", args.V, "a velocity where the discrete wave converges", f"wave solver: {r.message}"
        )
    fr = floquet.spectrum(r, m=args.m, finite_size=not args.no_finite_size, method=args.method)
    d = fr.as_dict()
    d["elapsed_s"] = fr.elapsed_s + r.elapsed_s
    d["floquet_elapsed_s"] = fr.elapsed_s
    if args.json:
        print_json(d)
        return 0
    w = fr.wave
    print(
        f"{w.get('kind', args.kind)} V={fr.V:.10g} N={fr.N} (wave residual "
        f"{w.get('residual', float('nan')):.1e}, {r.elapsed_s:.2f} s)"
    )
    print(f"max |mu|                 = {fr.max_modulus:.12f}")
    print(
        f"max |mu| away from mu=1  = {fr.max_modulus_away_from_1:.12f}   (|mu|-1 = {fr.excess:.3e})"
    )
    print(
        f"error bar                = {fr.error:.1e}  (quartet symmetry {fr.symmetry_error:.1e},"
        f" integrator {fr.integrator_error:.1e}; route {fr.route}, "
        f"eig {fr.eig_s:.3f} s)"
    )
    print(
        f"trivial cluster at 1     : {fr.n_trivial} multipliers, split {fr.trivial_split:.1e} "
        f"(radius {fr.trivial_radius:.0e}, phonon gap {fr.phonon_gap:.1e})"
    )
    dec = fr.decision
    k = fr.n_unstable
    print(
        f"classification           : {dec.classification} - {dec.headline} "
        f"({k} multiplier{'' if k == 1 else 's'} beyond error)"
    )
    if fr.finite_size_N.size > 1:
        pts = ", ".join(
            f"N={n}: {e:.3e}" for n, e in zip(fr.finite_size_N, fr.finite_size_excess, strict=True)
        )
        print(f"finite-size window       : max|mu|-1 at {pts} ({fr.finite_size_s:.2f} s)")
    print(f"verdict                  : {dec.sentence}")
    for g in fr.quartets()[:5]:
        mu = g[0]
        print(
            f"  {'quartet' if len(g) == 4 else 'real pair'}: |mu| = {abs(mu):.10f}, "
            f"arg mu = {np.angle(mu):+.6f}, partners |mu| = "
            + ", ".join(f"{abs(x):.10f}" for x in g[1:])
        )
    print(
        f"time: monodromy {fr.monodromy_s:.3f} s, step-doubling check {fr.check_s:.3f} s, "
        f"eig {fr.eig_s:.3f} s, total {fr.elapsed_s:.2f} s"
    )
    if not fr.converged:
        print(f"warning: {fr.message}", file=sys.stderr)
    return 0


def _velocities(args):
    import numpy as np  # heavy: NumPy

    if args.V is not None:
        return np.asarray(args.V, float)
    if args.V_min is None or args.V_max is None:
        raise ParameterError("V", None, "--V v1 v2 ... or both --V-min and --V-max")
    if not (2 <= args.n <= 10000):
        raise ParameterError("n", args.n, "[2, 10000]")
    return np.linspace(args.V_min, args.V_max, args.n)


def run_sweep(args) -> int:
    from fpucore import atlas  # heavy: Numba, xarray

    law = law_from_args(args)
    Vs = _velocities(args)
    for N in args.N:
        _check_N(N)
    tables = []
    for N in args.N:
        prog = None if (args.no_progress or args.json) else True
        if prog and len(args.N) > 1:
            sys.stderr.write(f"N = {N}\n")
        sw = atlas.sweep(
            law,
            args.kind,
            Vs,
            w_plus=args.w_plus,
            N=N,
            progress=prog,
            branch=args.branch,
            use_cache=not args.no_cache,
            method=args.method,
        )
        tables.append(sw)
    obj = {
        "kind": args.kind,
        **law_fields(law),
        "w_plus": args.w_plus,
        "sweeps": [t.as_dict(arrays=False) for t in tables],
        "elapsed_s": sum(t.elapsed_s for t in tables),
    }
    if args.out:  # atomically: a full disk leaves no partial table (fpucore/cli/common.py)
        kept = (
            "the sweep's points are in the cache: rerun to write the table"
            if (not args.no_cache)
            else "the sweep was not cached (--no-cache)"
        )
        with output_file(args.out, "--out", kept) as tmp, open(tmp, "w") as fh:
            if args.out.endswith(".json"):
                json.dump(jsonable(obj), fh)
            else:
                for i, t in enumerate(tables):
                    buf = _Buf()
                    t.to_csv(buf)
                    lines = buf.text.splitlines(keepends=True)
                    fh.writelines(lines if i == 0 else lines[1:])
    if args.json:
        print_json(obj)
        return 0
    print(
        f"{'N':>5} {'V':>12} {'max|mu|-1':>11} {'away-1':>11} {'error':>9} {'unst':>4}  "
        f"{'class':<12}  decision"
    )
    for t in tables:
        for row, c in zip(t.rows, t.cached, strict=True):
            mm, ma = row["max_modulus"], row["max_modulus_away_from_1"]
            f = lambda x: "nan" if x is None else f"{x - 1:.3e}"  # noqa: E731
            err = row["max_modulus_error"]
            e = "nan" if err is None else f"{err:.1e}"
            tag = " (cached)" if c else ""
            cls = row["classification"] or "-"
            said = (
                row["headline"]
                or row["verdict"]
                or (f"{row['status'] or 'not computed'}: {row['message']}")
            )  # no spectrum: why
            print(
                f"{t.N:>5} {row['V']:>12.8g} {f(mm):>11} {f(ma):>11} {e:>9} "
                f"{max(row['n_unstable'], 0):>4}  {cls:<12}  {said}"
                f"{tag}"
            )
        missing = sum(r["status"] == "" for r in t.rows)
        if missing or t.cached.any():  # a partial or cached table says so
            print(f"{t.N:>5} {t.message}" + (f" ({missing} not computed)" if missing else ""))
        if args.kind == "solitary" and args.w_plus is not None:
            print(f"{t.N:>5} energy criterion: {_energy_line(law, t)}")
    print(
        f"total {obj['elapsed_s']:.1f} s" + (f"; table written to {args.out}" if args.out else "")
    )
    return 0


def _energy_line(law, t) -> str:
    """The sweep's cross-check against the extrema of E_ren, one line."""
    from fpucore import floquet  # heavy: Numba

    try:
        ec = floquet.criterion_from_samples(
            law, t.w_plus, t.V, t.energy, t.energy_error, t.floquet_converged
        )
        ch = floquet.stability_changes(law, t.w_plus, t.V, t.classification, ec)
    except ParameterError as exc:
        return f"not evaluated ({exc})"
    return floquet.changes_summary(ch)


class _Buf:
    def __init__(self):
        self.text = ""

    def write(self, s):
        self.text += s


_ = argparse  # argparse types are used through the parent parser
