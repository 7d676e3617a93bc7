"""``fpu simulate``: direct simulation of the chain (paper §6) with wave tracking.

    fpu simulate riemann  --w-left 4.6 --w-right 0 --L 3600 --t-end 300 [--json]
    fpu simulate gaussian --w-B 1 --A 6 --L 2400 --t-end 200 --guard bounded [--json]
    fpu simulate velocity-jump --law 'trilinear(w1=0.5, w2=1.5, E1=0, E2=4, E3=0.2)' \
        --w-left 0.2 --w-right 0.2 --v-left -0.2 --L 200 --t-end 60 --guard bounded \
        --probes 104 105 ... 115 --train right [--json]
    fpu simulate wave superkink --V 5.2 [--branch lower] [--periods 50] [--json]
    fpu simulate wave solitary --w-plus 1 --V 5 [--json]

JSON: one object with ``waves`` ([{kind, velocity, velocity_error, amplitude, left_state,
right_state, background, peak, position, n_fit, method, velocity_fit_error,
velocity_window_spread, velocity_threshold_spread, background_error}]; velocity_error = the fit's
standard error + the measured spreads over fit windows and thresholds), ``energy_drift``,
``error_estimate``, ``elapsed_s``, ``status``, ``message`` and ``details`` (with
``work_estimate``).  A progress bar
goes to stderr on long runs (estimated ≥ 2 s, when stderr is a terminal, or always with
``--progress always``).

Budgets: ``--time-budget`` (seconds of simulation, default 60) stops a longer run cleanly with
the times it reached (status "stopped", stop_reason "time_budget", exit 1); ``--memory-budget``
(e.g. 2GiB; default FPU_MEMORY_BUDGET or 25 % of RAM) refuses a request whose memory estimate is
above it before anything is allocated (exit 2).
"""

from __future__ import annotations

import sys
from typing import Any

from fpucore.budget import parse_size, require_time_budget
from fpucore.cli.choices import BOUNDARIES, GUARDS, SIMULATE_METHODS
from fpucore.cli.common import add_law_args, law_from_args, print_json
from fpucore.errors import ParameterError, require_finite

#: the tracker's kinds in the printed table (the JSON keeps fpucore's names)
KIND_WORDS = {"dsw_edge": "DSW edge", "solitary": "solitary"}
TIME_BUDGET_S = 60.0  # default --time-budget: the CLI never runs unbounded


class _Bar:
    """Progress of a simulation on stderr: a tqdm bar (percent done, elapsed, ETA), drawn from
    the first progress report on — a run refused by validation prints only its one-line error."""

    def __init__(self, label: str):
        self.label = label
        self.bar: Any = None  # a tqdm bar once the run reports progress

    def __call__(self, frac: float) -> None:
        if self.bar is None:
            from tqdm import tqdm  # heavy: tqdm

            self.bar = tqdm(
                total=100, desc=self.label, unit="%", file=sys.stderr, dynamic_ncols=True
            )
        pct = int(100 * min(max(frac, 0.0), 1.0))
        if pct > self.bar.n:
            self.bar.update(pct - self.bar.n)
        if pct >= 100:
            self.bar.close()


def _progress(args, law, L: float, t_end: float, method: str, rtol: float):
    """A progress bar when asked, or on a terminal when the run is estimated at ≥ 2 s."""
    from fpucore import simulate  # heavy: Numba

    mode = args.progress
    if mode == "never":
        return None
    if mode == "always":
        return _Bar("simulate")
    if not sys.stderr.isatty():
        return None
    try:
        est = simulate.work_estimate(law, int(L), float(t_end), method, rtol, args.dt or 0.02)
    except (TypeError, ValueError, ZeroDivisionError, OverflowError):
        return None  # bad input: the simulation itself refuses it with the argument's name
    return _Bar("simulate") if est["seconds"] >= 2.0 else None


def _add_run_args(p, t_end_default=None) -> None:
    add_law_args(p)
    p.add_argument("--method", choices=SIMULATE_METHODS, default="rkn12")
    p.add_argument("--rtol", type=float, default=None, help="adaptive tolerance (default 1e-10)")
    p.add_argument("--dt", type=float, default=None, help="symplectic step (default 0.02)")
    p.add_argument("--boundary", choices=BOUNDARIES, default=None)
    p.add_argument(
        "--guard",
        choices=GUARDS,
        default="convex",
        help="stop when a strain leaves (alpha, beta) [convex] or the zeros of f [bounded]",
    )
    p.add_argument("--snapshots", type=int, default=200, help="number of output snapshots")
    p.add_argument("--max-sites", type=int, default=1000, help="sites kept per snapshot")
    p.add_argument("--probes", type=int, nargs="*", default=(), help="site numbers to record")
    p.add_argument("--progress", choices=("auto", "always", "never"), default="auto")
    p.add_argument(
        "--time-budget",
        type=float,
        default=TIME_BUDGET_S,
        help=f"wall seconds for the simulation (default {TIME_BUDGET_S:g}); past it the run stops "
        "with the times it reached",
    )
    p.add_argument(
        "--memory-budget",
        default=None,
        help="refuse runs estimated above this memory (bytes, 2GiB, 50%%; default "
        "FPU_MEMORY_BUDGET or 25%% of RAM)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")


def register(sub) -> None:
    p = sub.add_parser("simulate", help="direct simulation of the chain with wave tracking (§6)")
    ss = p.add_subparsers(dest="scenario", required=True, parser_class=type(p))

    r = ss.add_parser("riemann", help="Riemann data (eq. Riemann_data)")
    r.add_argument("--w-left", type=float, required=True)
    r.add_argument("--w-right", type=float, required=True)
    r.add_argument("--L", type=int, required=True, help="number of sites (even)")
    r.add_argument("--t-end", type=float, required=True)
    _add_run_args(r)
    r.set_defaults(func=run_riemann)

    j = ss.add_parser("velocity-jump", help="Riemann data with a velocity jump (an impact)")
    j.add_argument("--w-left", type=float, required=True)
    j.add_argument("--w-right", type=float, required=True)
    j.add_argument(
        "--v-left",
        type=float,
        required=True,
        help="velocity of the particles j < L/2 (the others at rest)",
    )
    j.add_argument("--L", type=int, required=True, help="number of sites (even)")
    j.add_argument("--t-end", type=float, required=True)
    j.add_argument(
        "--train",
        choices=("right", "left"),
        default=None,
        help="track the train of waves moving that way (needs >= 4 --probes in it; "
        "a law with a zero-modulus regime)",
    )
    _add_run_args(j)
    j.set_defaults(func=run_velocity_jump)

    g = ss.add_parser("gaussian", help="Gaussian data (eq. GaussIC)")
    g.add_argument("--w-B", type=float, required=True, help="background strain")
    g.add_argument("--A", type=float, required=True, help="signed amplitude")
    g.add_argument("--L", type=int, required=True)
    g.add_argument("--t-end", type=float, required=True)
    _add_run_args(g)
    g.set_defaults(func=run_gaussian)

    w = ss.add_parser("wave", help="seeded with a computed discrete traveling wave")
    ws = w.add_subparsers(dest="wave_kind", required=True, parser_class=type(p))
    sk = ws.add_parser("superkink", help="computed superkink (fpucore.wave.solve_superkink)")
    sk.add_argument("--V", type=float, required=True)
    sk.add_argument("--branch", choices=("lower", "upper"), default="lower")
    sw = ws.add_parser("solitary", help="computed solitary wave (fpucore.wave.solve_solitary)")
    sw.add_argument("--w-plus", type=float, required=True, help="background strain")
    sw.add_argument("--V", type=float, required=True)
    for q in (sk, sw):
        q.add_argument("--N", type=int, default=None, help="sites of the computed wave")
        q.add_argument("--L", type=int, default=None, help="chain length (default: fits)")
        q.add_argument("--periods", type=float, default=50.0, help="run length in periods 1/V")
        _add_run_args(q)
        q.set_defaults(func=run_wave)


def _common(args, default_boundary: str, default_rtol: float) -> dict:
    return dict(
        method=args.method,
        rtol=default_rtol if args.rtol is None else args.rtol,
        dt=args.dt,
        boundary=args.boundary or default_boundary,
        guard=args.guard,
        n_snapshots=args.snapshots,
        max_sites_out=args.max_sites,
        probes=tuple(args.probes),
        time_budget_s=require_time_budget(args.time_budget, "time_budget"),
        memory_budget=None if args.memory_budget is None else parse_size(args.memory_budget),
    )


def _emit(args, s, extra: dict | None = None) -> int:
    out = s.summary()
    if extra:
        out.update(extra)
    if args.json:
        print_json(out)
    else:
        print(f"{s.scenario}: L = {s.L}, boundary = {s.boundary}, method = {s.method}")
        print(f"status   {s.status}: {s.message}")
        print(f"energy   drift {s.energy_drift:.3e} (relative), {s.energy_drift_abs:.3e} (abs)")
        print(f"error    integrator estimate {s.error_estimate:.3e}")
        print(f"time     {s.elapsed_s:.3f} s, {s.n_steps} steps, {s.n_rhs} RHS evaluations")
        if s.waves:
            print(
                f"{'kind':10s} {'velocity':>14s} {'+- error':>9s} {'amplitude':>11s} "
                f"{'left':>10s} {'right':>10s}"
            )
            for w in s.waves:
                print(
                    f"{KIND_WORDS.get(w.kind, w.kind):10s} {w.velocity:14.8f} "
                    f"{w.velocity_error:9.1e} {w.amplitude:11.5f} "
                    f"{w.left_state:10.5f} {w.right_state:10.5f}"
                )
            print("(+- error: fit error + spread over fit windows and tracking thresholds)")
        for k, v in (extra or {}).items():
            print(f"{k}: {v}")
        for k, v in s.details.items():
            if k == "left_convex_interval":  # a sentence, not a flag (--json keeps the flag)
                where = "went outside (strain_range)" if v else "stayed inside"
                print(f"convex interval (α, β): the strains {where}")
            else:
                print(f"{k}: {v}")
    return 0 if s.success else 1


def run_riemann(args) -> int:
    from fpucore import simulate  # heavy: Numba

    law = law_from_args(args)
    kw = _common(args, "fixed_particles", 1e-10)
    prog = _progress(args, law, args.L, args.t_end, kw["method"], kw["rtol"])
    s = simulate.riemann(law, args.w_left, args.w_right, args.L, args.t_end, progress=prog, **kw)
    return _emit(args, s)


def run_velocity_jump(args) -> int:
    from fpucore import simulate  # heavy: Numba

    law = law_from_args(args)
    kw = _common(args, "fixed_strain", 1e-10)
    prog = _progress(args, law, args.L, args.t_end, kw["method"], kw["rtol"])
    s = simulate.velocity_jump(
        law, args.w_left, args.w_right, args.v_left, args.L, args.t_end, progress=prog, **kw
    )
    extra = None
    if args.train is not None:
        tr = simulate.track_train(s, law, side=1 if args.train == "right" else -1)
        extra = {"train": tr.as_dict() if args.json else tr.message}
    return _emit(args, s, extra)


def run_gaussian(args) -> int:
    from fpucore import simulate  # heavy: Numba

    law = law_from_args(args)
    kw = _common(args, "fixed_particles", 1e-10)
    prog = _progress(args, law, args.L, args.t_end, kw["method"], kw["rtol"])
    s = simulate.gaussian(law, args.w_B, args.A, args.L, args.t_end, progress=prog, **kw)
    return _emit(args, s)


def run_wave(args) -> int:
    from fpucore import simulate, wave  # heavy: Numba

    law = law_from_args(args)
    # checked before the wave is solved, and named as typed (not as the t_end it implies)
    periods = require_finite("periods", args.periods)
    if not (0.0 < periods <= 1e6):
        raise ParameterError("periods", periods, "(0, 1e+06]", "the run length in periods 1/V")
    kw = _common(args, "fixed_strain", 1e-12)  # budgets checked before the wave is solved too
    if args.wave_kind == "superkink":
        r = wave.solve_superkink(law, args.V, branch=args.branch, N=args.N)
    else:
        r = wave.solve_solitary(law, args.w_plus, args.V, N=args.N)
    solve = {
        "wave_solve": {
            "kind": r.kind,
            "V": r.V,
            "N": r.N,
            "converged": r.converged,
            "residual": r.residual,
            "message": r.message,
            "elapsed_s": r.elapsed_s,
        }
    }
    if not r.converged:
        if args.json:
            print_json({"status": "not_converged", "stop_reason": "wave_not_converged", **solve})
        else:
            print(f"traveling wave did not converge: {r.message}", file=sys.stderr)
        return 1
    t_end = periods / r.V
    L_est = args.L or r.N + r.V * t_end + 200
    prog = _progress(args, law, L_est, t_end, kw["method"], kw["rtol"])
    s = simulate.seeded(r, L=args.L, t_end=t_end, progress=prog, **kw)
    return _emit(args, s, solve)
