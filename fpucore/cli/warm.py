"""``fpu warm``: compile (and cache) the Numba kernels so no user waits for the JIT."""

from __future__ import annotations

import time

from fpucore.cli.choices import LAZY_WARM


def register(sub) -> None:
    p = sub.add_parser("warm", help="compile and cache the Numba kernels (run before serving)")
    p.add_argument(
        "--essential",
        action="store_true",
        help=f"leave out the routes no first page needs ({', '.join(LAZY_WARM)}): the server "
        "compiles them in the background after it is up",
    )
    p.add_argument("--serial", action="store_true", help="one process (default: in parallel)")
    p.set_defaults(func=run)


def run(args) -> int:
    from fpucore.warm import warm_all  # heavy: Numba

    t0 = time.perf_counter()
    done = warm_all(parallel=not args.serial, lazy=not args.essential)
    print(f"warmed {', '.join(done) or 'nothing'} in {time.perf_counter() - t0:.1f} s")
    return 0
