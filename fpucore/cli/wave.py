"""``fpu wave``: discrete superkinks and solitary waves (paper §5) from the command line.

fpu wave superkink --V 5.2 [--branch lower|upper] [--N N] [--json]
fpu wave solitary --w-plus 1 --V 5.0 [--N N] [--json]
"""

from __future__ import annotations

import math

from fpucore.cli.common import add_law_args, law_fields, law_from_args, print_json


def _common(p) -> None:
    add_law_args(p)
    p.add_argument("--V", type=float, required=True, help="wave velocity V > 0")
    p.add_argument("--N", type=int, default=None, help="sites (even; default: automatic)")
    p.add_argument("--tol", type=float, default=1e-12, help="Newton residual tolerance")
    p.add_argument("--fd", action="store_true", help="paper's finite-difference Jacobian")
    p.add_argument("--json", action="store_true", help="print one JSON object (with profile)")


def register(sub) -> None:
    p = sub.add_parser("wave", help="discrete traveling waves (paper §5)")
    wsub = p.add_subparsers(dest="wave_kind", required=True, parser_class=type(p))
    sk = wsub.add_parser("superkink", help="discrete superkink with velocity V")
    _common(sk)
    sk.add_argument(
        "--branch",
        choices=("lower", "upper"),
        default="lower",
        help="lower: w+ < w* (default); upper: w+ > w*",
    )
    sk.set_defaults(func=run)
    sw = wsub.add_parser("solitary", help="discrete solitary wave for w+ and V")
    _common(sw)
    sw.add_argument("--w-plus", type=float, required=True, help="state ahead of the superkink")
    sw.set_defaults(func=run)


def compute(args):
    from fpucore import wave  # heavy: Numba

    law = law_from_args(args)
    jac = "fd" if args.fd else "exact"
    if args.wave_kind == "superkink":
        return wave.solve_superkink(law, args.V, args.branch, args.N, args.tol, jacobian=jac)
    return wave.solve_solitary(law, args.w_plus, args.V, args.N, args.tol, jacobian=jac)


def _or_na(x: float, spec: str) -> str:
    """x formatted, or "n/a" for a quantity the wave does not have (NaN)."""
    return "n/a" if math.isnan(x) else format(x, spec)


def run(args) -> int:
    r = compute(args)
    if args.json:
        d = r.as_dict(profile=True)
        d.update(law_fields(r.law))
        print_json(d)
        return 0 if r.converged else 1
    if r.kind == "superkink":  # |w_left - w_right|, both given: no error; E_ren: solitary only
        amp_bound, energy = "0 (exact by construction)", "n/a (defined for solitary waves)"
    else:
        amp_bound, energy = f"{r.amplitude_error:.3g}", _or_na(r.energy, ".10g")
    lines = [
        f"{r.kind} V={r.V:.10g}  N={r.N}  w_left={r.w_left:.10g}  w_right={r.w_right:.10g}",
        f"status      {r.message}",
        f"residual    {r.residual:.3g}   dropped eq. {r.dropped_residual:.3g}   "
        f"iterations {r.iterations}",
        f"errors      tail {r.tail_error:.3g}   integrator {r.integrator_error:.3g} (m={r.m})   "
        f"Jacobian truncation {r.jacobian_truncation:.3g}",
        f"bounds      profile {r.profile_error:.3g}   amplitude {amp_bound}   "
        f"energy {_or_na(r.energy_error, '.3g')}   (vs the infinite chain's exact wave)",
        f"amplitude   {r.amplitude:.10g}   energy E_ren^D {energy}",
        f"QC max dev  {r.qc_max_deviation:.3g}   w(0) = {r.w[r.N // 2]:.10g}",
        f"elapsed     {r.elapsed_s:.3f} s   ({r.route})",
    ]
    print("\n".join(lines))
    return 0 if r.converged else 1
