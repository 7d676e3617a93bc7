"""``fpu qc``: the quasicontinuum numbers for (law, w₊[, V]) — a stable contract for scripts
(closed forms for the cubic --a/--b, the numerical §3 theory for --law; both with error bars)."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from fpucore.cli.common import add_law_args, law_fields, law_from_args, print_json

if TYPE_CHECKING:
    from fpucore.law import HardeningSofteningLaw


def register(sub) -> None:
    p = sub.add_parser("qc", help="QC superkink / solitary wave numbers (paper §3-4)")
    add_law_args(p)
    p.add_argument("--w-plus", type=float, required=True, help="state ahead of the superkink")
    p.add_argument("--V", type=float, default=None, help="solitary-wave velocity (optional)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def compute(law: HardeningSofteningLaw, w_plus: float, V: float | None) -> dict:
    from fpucore import qc  # heavy: Numba, SciPy

    t0 = time.perf_counter()
    sk = qc.superkink_from_w_plus(law, w_plus)
    cp, vsk, cm = qc.sound_speeds(law, w_plus)
    out = {
        **law_fields(law),
        "w_plus": w_plus,
        "w_star": law.w_star,
        "alpha": law.alpha,
        "beta": law.beta,
        "c_plus": cp,
        "V_SK": vsk,
        "c_minus": cm,
        "superkink": sk.as_dict(),
    }
    if V is not None:
        sw = qc.solitary(law, w_plus, V)
        out["solitary"] = sw.as_dict()
    out["elapsed_s"] = time.perf_counter() - t0
    return out


def run(args) -> int:
    out = compute(law_from_args(args), args.w_plus, args.V)
    if args.json:
        print_json(out)
        return 0
    sk = out["superkink"]
    lines = [
        f"law      {out['law']}{_consts(out)}   w* = {out['w_star']:.10g}",
        f"convex   (alpha, beta) = ({out['alpha']:.10g}, {out['beta']:.10g})",
        f"speeds   c+ = {out['c_plus']:.10g}   V_SK = {out['V_SK']:.10g}   "
        f"c- = {out['c_minus']:.10g}",
        f"superkink  w+ = {out['w_plus']:.10g} -> w- = {sk['w_minus']:.10g}, p = {sk['p']:.10g} "
        f"(Rayleigh residual {sk['rayleigh_residual']:.1e}, "
        f"driving force {sk['driving_force']:.1e})",
    ]
    if "solitary" in out:
        s = out["solitary"]
        lines.append(
            f"solitary   V = {s['V']:.10g}: {s['kind']}, w_B = {s['w_B']:.10g}, "
            f"w_M = {s['w_M']:.10g}, w_T = {s['w_T']:.10g}, gamma = {s['gamma']:.10g}"
        )
        lines.append(
            f"           amplitude = {s['amplitude']:.10g}, E_ren = {s['energy']:.10g} "
            f"(+/- {s['energy_error']:.1e})"
        )
    lines.append(f"elapsed  {out['elapsed_s'] * 1e3:.3f} ms")
    print("\n".join(lines))
    return 0


def _consts(out: dict) -> str:
    """ "  with b=10, d=50" for a smooth law's named constants and its representation."""
    c = out.get("constants")
    if c is None:
        return ""
    lo, hi = out["represented_interval"]
    e = out["representation_error"]
    head = ("  with " + ", ".join(f"{k}={v:g}" for k, v in c.items())) if c else ""
    return (
        f"{head}\n         represented on [{lo:.6g}, {hi:.6g}]: |f - f_rep| <= {e['f']:.2g}, "
        f"|f' - f'_rep| <= {e['df']:.2g}, |f'' - f''_rep| <= {e['ddf']:.2g}"
    )
