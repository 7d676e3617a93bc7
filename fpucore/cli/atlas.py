"""``fpu atlas``: waves, energies and Floquet multipliers over a grid, stored in Zarr.

fpu atlas solitary --w-plus 0.2:6.5:40 --V 40 --N 500 --floquet --out atlas.zarr
fpu atlas superkink --V 4.8:5.85:22 --N 500 --floquet [--method dense] --out sk.zarr [--branch both]
    [--scheduler tcp://HOST:8786 | --workers K [--force-workers] | --backend dask] [--resume]
    [--memory-budget 4GiB] [--json]

``--V K``: K velocities spanning the union of the existence intervals over the rows;
``--V LO:HI:K``: an explicit range.  Before the work, stderr says the point count and an
estimate (two points timed here × the points to do / the workers, :mod:`fpucore.atlas.estimate`);
a ``--time-budget`` below the estimate is refused (exit 2).  Progress: a tqdm bar on stderr
(points, failed, ETA).  Each chunk is saved when it finishes: Ctrl-C stops cleanly (exit 130),
every chunk written so far is kept and ``--resume`` goes on.
Everything is checked before the store is created (exit 2, one line): the options, the grid's
memory against the budget, ``--out``, and ``--scheduler`` (a bounded connect and handshake);
``--workers`` above the cores is capped (a note on stderr) unless ``--force-workers``.
"""

from __future__ import annotations

import sys

from fpucore.cli.choices import DEFAULT_FLOQUET_METHOD, FLOQUET_METHODS, METHOD_HELP
from fpucore.cli.common import OutputError, add_law_args, law_from_args, print_json
from fpucore.errors import ParameterError


def register(sub) -> None:
    p = sub.add_parser("atlas", help="sweeps over the existence region, stored in Zarr")
    asub = p.add_subparsers(dest="atlas_kind", required=True, parser_class=type(p))
    for kind in ("solitary", "superkink"):
        q = asub.add_parser(
            kind, help=f"{kind} atlas over " + ("(w+, V)" if kind == "solitary" else "V")
        )
        add_law_args(q)
        if kind == "solitary":
            q.add_argument("--w-plus", required=True, help="LO:HI:K or one value (state ahead)")
        else:
            q.add_argument("--branch", choices=("lower", "upper", "both"), default="lower")
        q.add_argument(
            "--V", default="40", help="K (spanning the existence intervals) or LO:HI:K (default 40)"
        )
        q.add_argument("--N", type=int, default=None, help="chain size (default: automatic)")
        q.add_argument("--tol", type=float, default=1e-12, help="Newton residual tolerance")
        q.add_argument("--floquet", action="store_true", help="also the Floquet spectra")
        q.add_argument("--m", type=int, default=None, help="RK steps per period (Floquet)")
        q.add_argument(
            "--method", choices=FLOQUET_METHODS, default=DEFAULT_FLOQUET_METHOD, help=METHOD_HELP
        )
        q.add_argument(
            "--no-finite-size",
            action="store_true",
            help="skip the spectra's finite-size test (no classification; faster)",
        )
        q.add_argument("--chunk", type=int, default=None, help="points per chunk along V")
        q.add_argument("--no-continuation", action="store_true", help="every point cold")
        q.add_argument("--out", required=True, help="Zarr store (a directory)")
        q.set_defaults(out_is_store=True)
        q.add_argument("--resume", action="store_true", help="continue an interrupted store")
        q.add_argument("--scheduler", default=None, help="Dask scheduler tcp://HOST:PORT")
        q.add_argument(
            "--backend",
            choices=("process", "dask", "inline"),
            default=None,
            help="process pool (default), dask (LocalCluster unless --scheduler)",
        )
        q.add_argument(
            "--workers",
            type=int,
            default=None,
            help="worker processes (default and cap: min(cores, chunks))",
        )
        q.add_argument(
            "--force-workers",
            action="store_true",
            help="run --workers processes even above the cores",
        )
        q.add_argument(
            "--memory-budget",
            default=None,
            help="memory the table and workers may take (e.g. 4GiB, 50%%; default "
            "FPU_MEMORY_BUDGET or 25%% of RAM)",
        )
        q.add_argument(
            "--time-budget",
            type=float,
            default=None,
            metavar="S",
            help="refuse a grid estimated above S seconds (two points are timed "
            "first); stop after S seconds",
        )
        q.add_argument("--no-progress", action="store_true", help="no progress bar")
        q.add_argument("--json", action="store_true", help="print the summary as JSON")
        q.set_defaults(func=run, kind=kind, threads=1)  # the parent only orchestrates


def run(args) -> int:
    from tqdm import tqdm  # heavy: tqdm

    from fpucore import atlas  # heavy: Numba, xarray
    from fpucore.atlas.store import check_out  # heavy: Numba
    from fpucore.parallel import apply_thread_policy  # heavy: Numba

    law = law_from_args(args)
    check_out(args.out)  # before anything is computed
    if args.scheduler is not None and args.backend not in (None, "dask"):
        raise ParameterError("backend", args.backend, "dask (or none) with --scheduler")
    backend = args.backend or ("dask" if args.scheduler else "process")
    rows = (
        args.w_plus
        if args.kind == "solitary"
        else (["lower", "upper"] if args.branch == "both" else [args.branch])
    )
    apply_thread_policy(1)
    bar = None

    def say(text: str) -> None:  # the plan and the estimate, on stderr before the work
        sys.stderr.write(f"fpu: {text}\n")
        sys.stderr.flush()

    def progress(done: int, total: int, failed: int) -> None:
        nonlocal bar
        if args.no_progress or args.json:
            return
        if bar is None:
            bar = tqdm(
                total=total,
                initial=done,
                unit="pt",
                desc=f"atlas {args.kind}",
                file=sys.stderr,
                dynamic_ncols=True,
            )
        bar.update(done - bar.n)
        bar.set_postfix(failed=failed, refresh=True)

    try:
        res = atlas.run(
            law,
            args.kind,
            rows=rows,
            V=args.V,
            N=args.N,
            tol=args.tol,
            floquet=args.floquet,
            finite_size=not args.no_finite_size,
            floquet_method=args.method,
            m=args.m,
            chunk=args.chunk,
            continuation=not args.no_continuation,
            out=args.out,
            resume=args.resume,
            backend=backend,
            workers=args.workers,
            address=args.scheduler,
            progress=progress,
            time_budget_s=args.time_budget,
            force_workers=args.force_workers,
            memory_budget=args.memory_budget,
            note=say,
            estimate=True,
        )
    except ParameterError as exc:
        if exc.name == "address":  # the API's name of what this command calls --scheduler
            raise ParameterError("scheduler", exc.value, exc.valid, exc.reason) from None
        raise
    except KeyboardInterrupt:
        if bar is not None:
            bar.close()
        sys.stderr.write(
            f"fpu: interrupted; the store keeps what was done: resume with "
            f"--resume --out {args.out}\n"
        )
        return 130
    except OSError as exc:  # disk full, quota, permission lost while the store is written
        if bar is not None:
            bar.close()
        raise OutputError(
            f"could not write the store --out {args.out}: "
            f"{exc.strerror or exc}; it keeps every chunk written before: make room "
            f"and resume with --resume --out {args.out}"
        ) from None
    if bar is not None:
        bar.close()
    d = res.as_dict()
    if args.json:
        print_json(d)
    else:
        print(f"atlas {res.kind} {res.shape[0]} x {res.shape[1]} -> {res.path}")
        print(
            f"points   {res.n_ok} ok, {res.n_not_converged} not converged, {res.n_no_wave} no "
            f"wave, {res.n_failed} failed, {res.n_pending} pending"
        )
        print(
            f"errors   max residual {res.max_residual:.2g}, max |mu| error "
            f"{res.max_modulus_error:.2g}"
        )
        if res.n_computed:
            print(
                f"run      {res.n_computed} computed, {res.n_loaded} from the store, "
                f"{res.elapsed_s:.1f} s, {res.points_per_s:.3g} points/s on {res.workers} "
                f"{res.backend} workers"
            )
        else:  # --resume of a finished store: no pool was started, there is no rate to give
            print(
                f"run      nothing left to compute: all {res.n_loaded} points from the store "
                f"({res.elapsed_s:.1f} s)"
            )
        if res.stopped:
            print(f"stopped  {res.message}")
    return 0 if res.n_failed == 0 else 1
